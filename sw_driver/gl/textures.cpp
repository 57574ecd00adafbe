// Texture objects, images, parameters and the texture environment.
#include "gl/context.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/context_internal.h"
#include "gl/runtime.h"
#include "gl/texture_formats.h"

namespace tessera::gl {

void Context::gen_textures(GLsizei n, GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    while (m_texture.objects.count(m_texture.next_name)) ++m_texture.next_name;
    names[i] = m_texture.next_name;
    m_texture.objects[m_texture.next_name++] = TextureObject{};
  }
}

void Context::delete_textures(GLsizei n, const GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    if (names[i] == 0) continue;
    m_texture.objects.erase(names[i]);  // system memory of the texels is not reused (bump allocator)
    for (TextureUnitState& unit : m_texture.units)
      if (unit.bound == names[i]) unit.bound = 0;
  }
}

void Context::bind_texture(GLenum target, GLuint name) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  if (name != 0 && !m_texture.objects.count(name)) m_texture.objects[name] = TextureObject{};
  active_unit().bound = name;
}

bool Context::is_texture(GLuint name) {
  charge_call();
  return name != 0 && m_texture.objects.count(name) != 0;
}

TextureObject* Context::bound_texture() {
  // Texture object 0 is the default texture, which exists like any other.
  return &m_texture.objects[active_unit().bound];
}

bool Context::unit_textured(unsigned u) const {
  if (u >= m_texture.offered_units || !m_texture.units[u].enabled) return false;
  const auto it = m_texture.objects.find(m_texture.units[u].bound);
  return it != m_texture.objects.end() && texture_complete(it->second);
}

namespace {

// log2 of a power of two.
unsigned log2_of(unsigned v) {
  unsigned n = 0;
  while ((1u << n) < v) ++n;
  return n;
}

// Levels of a complete mipmap of level 0's size: down to 1 x 1.
unsigned full_levels(unsigned width, unsigned height) {
  return log2_of(std::max(width, height)) + 1;
}

bool internal_format_ok(GLint format) {
  const auto f = static_cast<GLenum>(format);
  return f == GL_RGBA || f == GL_RGB || f == GL_LUMINANCE || f == GL_ALPHA || f == GL_LUMINANCE_ALPHA;
}

// A level's size: power of two from 0 to the largest texture, a level no
// deeper than the largest texture has.
bool level_size_ok(GLint level, GLsizei width, GLsizei height) {
  return level >= 0 && static_cast<unsigned>(level) < MAX_TEXTURE_LEVELS && width >= 0 && height >= 0 &&
         width <= MAX_TEXTURE_SIZE && height <= MAX_TEXTURE_SIZE && (!width || is_power_of_two(width)) &&
         (!height || is_power_of_two(height));
}

}  // namespace

bool texture_complete(const TextureObject& object) {
  const TextureImage& base = object.image[0];
  if (!object.defined || base.width == 0 || base.height == 0) return false;
  if (object.texture.min_mipmap == MipmapFilter::none) return true;
  const unsigned levels = full_levels(base.width, base.height);
  for (unsigned level = 1; level < levels; ++level) {
    const TextureImage& image = object.image[level];
    if (image.format != base.format || image.width != std::max(1u, base.width >> level) ||
        image.height != std::max(1u, base.height >> level))
      return false;
  }
  return true;
}

Texture drawn_texture(const TextureObject& object) {
  Texture t = object.texture;
  const TextureImage& base = object.image[0];
  t.address = base.address;
  t.width = base.width;
  t.height = base.height;
  t.levels = t.min_mipmap == MipmapFilter::none ? 1 : full_levels(base.width, base.height);
  t.has_color = base.format != GL_ALPHA;
  t.has_alpha = base.format == GL_RGBA || base.format == GL_LUMINANCE_ALPHA || base.format == GL_ALPHA;
  for (unsigned level = 0; level < MAX_TEXTURE_LEVELS; ++level) {
    t.level[level] = level < t.levels ? TextureLevel{object.image[level].address, object.image[level].width,
                                                     object.image[level].height}
                                      : TextureLevel{};
  }
  return t;
}

void Context::store_level(TextureObject* object, unsigned level, unsigned width, unsigned height, GLenum format,
                          const uint32_t* rows) {
  TextureImage& image = object->image[level];
  // Stored as RGBA8 in system memory, where every back end fetches it; the
  // memory of a level whose size changes is not reused (bump allocator).
  if (image.width != width || image.height != height || image.address == 0)
    image.address = allocate(width * height * 4);
  image.width = width;
  image.height = height;
  image.format = format;
  if (level == 0) object->defined = true;
  if (!rows) return;
  for (unsigned j = 0; j < height; ++j) {
    const uint32_t address = image.address + j * width * 4;
    for (unsigned i = 0; i < width; i += 8)
      m_host.write_words(address + 4 * i, rows + size_t{j} * width + i, std::min(8u, width - i));
  }
}

void Context::generate_mipmaps(TextureObject* object) {
  const TextureImage base = object->image[0];
  if (!object->defined || base.width == 0 || base.height == 0) return;
  std::vector<uint32_t> in(size_t{base.width} * base.height), out;
  for (unsigned j = 0; j < base.height; ++j) {
    for (unsigned i = 0; i < base.width; i += 8)
      m_host.read_words(base.address + (j * base.width + i) * 4, &in[size_t{j} * base.width + i],
                        std::min(8u, base.width - i));
  }
  unsigned width = base.width, height = base.height;
  for (unsigned level = 1; level < full_levels(base.width, base.height); ++level) {
    const unsigned w = std::max(1u, width / 2), h = std::max(1u, height / 2);
    out.resize(size_t{w} * h);
    box_filter_level(in.data(), width, height, out.data());
    charge(costs::HostCost::gl_texel_filtered, uint64_t{w} * h);
    store_level(object, level, w, h, base.format, out.data());
    in.swap(out);
    width = w;
    height = h;
  }
}

void Context::tex_image(GLenum target, GLint level, GLint internal_format, GLsizei width, GLsizei height, GLint border,
                        GLenum format, GLenum type, const void* pixels) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  const GLenum format_error = format_type_error(format, type);
  if (format_error == GL_INVALID_ENUM) return error(GL_INVALID_ENUM);
  if (!internal_format_ok(internal_format) || border != 0 || !level_size_ok(level, width, height))
    return error(GL_INVALID_VALUE);
  if (static_cast<GLenum>(internal_format) != format || format_error != 0) return error(GL_INVALID_OPERATION);
  TextureObject* object = bound_texture();
  if (static_cast<uint32_t>(width) * static_cast<uint32_t>(height) == 0) {
    object->image[level] = TextureImage{};
    if (level == 0) object->defined = false;
    return;
  }
  store_level(object, static_cast<unsigned>(level), static_cast<unsigned>(width), static_cast<unsigned>(height), format,
              nullptr);
  if (pixels)
    tex_sub_image(target, level, 0, 0, width, height, format, type, pixels);
  else if (level == 0 && object->generate_mipmap)
    generate_mipmaps(object);
}

void Context::tex_sub_image(GLenum target, GLint level, GLint x, GLint y, GLsizei width, GLsizei height, GLenum format,
                            GLenum type, const void* pixels) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  const GLenum format_error = format_type_error(format, type);
  if (format_error == GL_INVALID_ENUM) return error(GL_INVALID_ENUM);
  if (level < 0 || static_cast<unsigned>(level) >= MAX_TEXTURE_LEVELS) return error(GL_INVALID_VALUE);
  TextureObject* object = bound_texture();
  const TextureImage& image = object->image[level];
  if (image.format == 0) return error(GL_INVALID_OPERATION);
  if (x < 0 || y < 0 || width < 0 || height < 0 || !fits(x, width, image.width) || !fits(y, height, image.height))
    return error(GL_INVALID_VALUE);
  if (format_error != 0) return error(GL_INVALID_OPERATION);
  if (!pixels) return;
  const unsigned bytes = pixel_bytes(format, type);
  const auto* in = static_cast<const uint8_t*>(pixels);
  const size_t row_bytes = static_cast<size_t>(width) * bytes;
  const size_t stride = (row_bytes + m_pixel_store.unpack_alignment - 1) / m_pixel_store.unpack_alignment *
                        m_pixel_store.unpack_alignment;
  std::vector<uint32_t> row(static_cast<size_t>(width));
  for (GLsizei j = 0; j < height; ++j) {
    for (GLsizei i = 0; i < width; ++i) row[i] = unpack_pixel(format, type, in + j * stride + size_t{bytes} * i);
    charge(costs::HostCost::gl_texel_converted, static_cast<uint64_t>(width));
    const uint32_t address = image.address + ((y + j) * image.width + x) * 4;
    for (GLsizei i = 0; i < width; i += 8)
      m_host.write_words(address + 4 * i, &row[i], static_cast<unsigned>(std::min<GLsizei>(8, width - i)));
  }
  if (level == 0 && object->generate_mipmap) generate_mipmaps(object);
}

void Context::compressed_tex_image(GLenum target, GLint level, GLenum internal_format, GLsizei width, GLsizei height,
                                   GLint border, GLsizei image_size, const void* data) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  const PaletteFormat* format = find_palette_format(internal_format);
  if (!format) return error(GL_INVALID_ENUM);
  // OES_compressed_paletted_texture: level 0 or -n, n + 1 levels in one
  // image from width x height down.
  if (level > 0 || border != 0 || !level_size_ok(-level, width, height) || width == 0 || height == 0)
    return error(GL_INVALID_VALUE);
  const unsigned levels = static_cast<unsigned>(1 - level);
  const auto w = static_cast<unsigned>(width), h = static_cast<unsigned>(height);
  if (levels > full_levels(w, h)) return error(GL_INVALID_VALUE);
  if (image_size < 0 || static_cast<size_t>(image_size) != paletted_image_size(*format, w, h, levels))
    return error(GL_INVALID_VALUE);
  if (!data) return error(GL_INVALID_VALUE);
  TextureObject* object = bound_texture();
  const GLenum expanded = format->entry_format;
  std::vector<uint32_t> texels(size_t{w} * h);
  for (unsigned k = 0; k < levels; ++k) {
    const unsigned lw = std::max(1u, w >> k), lh = std::max(1u, h >> k);
    decode_paletted_level(*format, static_cast<const uint8_t*>(data), w, h, k, texels.data());
    charge(costs::HostCost::gl_texel_converted, uint64_t{lw} * lh);
    store_level(object, k, lw, lh, expanded, texels.data());
  }
  if (levels == 1 && object->generate_mipmap) generate_mipmaps(object);
}

void Context::tex_parameter(GLenum target, GLenum name, float value) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  Texture& t = bound_texture()->texture;
  const std::optional<GLenum> v = enum_from_float(value);
  switch (name) {
    case GL_TEXTURE_MIN_FILTER:
      if (!v || !tex_min_filter_value(*v, &t.min_filter, &t.min_mipmap)) error(GL_INVALID_ENUM);
      break;
    case GL_TEXTURE_MAG_FILTER:
      if (!v || !tex_filter_value(*v, &t.mag_filter)) error(GL_INVALID_ENUM);
      break;
    case GL_TEXTURE_WRAP_S:
      if (!v || !tex_wrap_value(*v, &t.wrap_s)) error(GL_INVALID_ENUM);
      break;
    case GL_TEXTURE_WRAP_T:
      if (!v || !tex_wrap_value(*v, &t.wrap_t)) error(GL_INVALID_ENUM);
      break;
    case GL_GENERATE_MIPMAP:
      bound_texture()->generate_mipmap = value != 0.0f;  // any non-zero value is GL_TRUE, as in Mesa
      break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::get_tex_parameter(GLenum target, GLenum name, float* value) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  const Texture& t = bound_texture()->texture;
  switch (name) {
    case GL_TEXTURE_MIN_FILTER: *value = static_cast<float>(tex_min_filter_enum(t.min_filter, t.min_mipmap)); break;
    case GL_TEXTURE_MAG_FILTER: *value = static_cast<float>(gl_value(t.mag_filter)); break;
    case GL_TEXTURE_WRAP_S: *value = static_cast<float>(gl_value(t.wrap_s)); break;
    case GL_TEXTURE_WRAP_T: *value = static_cast<float>(gl_value(t.wrap_t)); break;
    case GL_GENERATE_MIPMAP: *value = bound_texture()->generate_mipmap ? 1.0f : 0.0f; break;
    default: error(GL_INVALID_ENUM);
  }
}

namespace {

// The GL_COMBINE enums and their codes in gl::RasterState, one table each.
constexpr std::pair<GLenum, CombineFunc> COMBINE_FUNCS[] = {
    {GL_REPLACE, CombineFunc::replace},
    {GL_MODULATE, CombineFunc::modulate},
    {GL_ADD, CombineFunc::add},
    {GL_ADD_SIGNED, CombineFunc::add_signed},
    {GL_INTERPOLATE, CombineFunc::interpolate},
    {GL_SUBTRACT, CombineFunc::subtract},
    {GL_DOT3_RGB, CombineFunc::dot3_rgb},
    {GL_DOT3_RGBA, CombineFunc::dot3_rgba},
};
constexpr std::pair<GLenum, CombineSource> COMBINE_SOURCES[] = {
    {GL_TEXTURE, CombineSource::texture},
    {GL_CONSTANT, CombineSource::constant},
    {GL_PRIMARY_COLOR, CombineSource::primary_color},
    {GL_PREVIOUS, CombineSource::previous},
};
constexpr std::pair<GLenum, CombineOperand> COMBINE_OPERANDS[] = {
    {GL_SRC_COLOR, CombineOperand::src_color},
    {GL_ONE_MINUS_SRC_COLOR, CombineOperand::one_minus_src_color},
    {GL_SRC_ALPHA, CombineOperand::src_alpha},
    {GL_ONE_MINUS_SRC_ALPHA, CombineOperand::one_minus_src_alpha},
};
constexpr std::pair<GLenum, TexEnvMode> ENV_MODES[] = {
    {GL_MODULATE, TexEnvMode::modulate}, {GL_REPLACE, TexEnvMode::replace}, {GL_DECAL, TexEnvMode::decal},
    {GL_BLEND, TexEnvMode::blend},       {GL_ADD, TexEnvMode::add},         {GL_COMBINE, TexEnvMode::combine},
};

template <typename Code, size_t N>
std::optional<Code> lookup(const std::pair<GLenum, Code> (&table)[N], GLenum value) {
  for (const auto& entry : table)
    if (entry.first == value) return entry.second;
  return std::nullopt;
}

// The glTexEnv names of the sources and operands: SRCi_RGB, SRCi_ALPHA,
// OPERANDi_RGB, OPERANDi_ALPHA, each i = 0..2 consecutive.
bool in_triple(GLenum name, GLenum first, int* i) {
  if (name < first || name > first + 2) return false;
  *i = static_cast<int>(name - first);
  return true;
}

}  // namespace

void set_unit_environment(const TextureUnitState& in, TextureUnit* out) {
  out->env = lookup(ENV_MODES, in.env_mode).value_or(TexEnvMode::modulate);
  for (int ch = 0; ch < 4; ++ch) out->env_color[ch] = static_cast<uint8_t>(std::lround(in.env_color[ch] * 255.0f));
  const GLenum funcs[2] = {in.combine_rgb, in.combine_alpha};
  const GLenum* sources[2] = {in.source_rgb, in.source_alpha};
  const GLenum* operands[2] = {in.operand_rgb, in.operand_alpha};
  const float scales[2] = {in.rgb_scale, in.alpha_scale};
  CombineStage* stages[2] = {&out->combine_rgb, &out->combine_alpha};
  for (int half = 0; half < 2; ++half) {
    CombineStage& stage = *stages[half];
    stage.func = lookup(COMBINE_FUNCS, funcs[half]).value_or(CombineFunc::modulate);
    for (int i = 0; i < 3; ++i) {
      stage.source[i] = lookup(COMBINE_SOURCES, sources[half][i]).value_or(CombineSource::texture);
      stage.operand[i] = lookup(COMBINE_OPERANDS, operands[half][i]).value_or(CombineOperand::src_color);
    }
    stage.scale = static_cast<uint8_t>(scales[half]);
  }
}

void Context::tex_env(GLenum target, GLenum name, const float* values, int count) {
  charge_call();
  if (target != GL_TEXTURE_ENV) return error(GL_INVALID_ENUM);
  TextureUnitState& unit = active_unit();
  // Every other name takes one value, an enum except for the scales.
  const std::optional<GLenum> value = name == GL_TEXTURE_ENV_COLOR ? std::nullopt : enum_from_float(values[0]);
  const GLenum v = value.value_or(0u);  // 0 is no mode, source or operand
  int i = 0;
  if (name == GL_TEXTURE_ENV_MODE) {
    if (!lookup(ENV_MODES, v)) return error(GL_INVALID_ENUM);
    unit.env_mode = v;
  } else if (name == GL_TEXTURE_ENV_COLOR) {
    if (count < 4) return error(GL_INVALID_ENUM);
    for (int c = 0; c < 4; ++c) unit.env_color[c] = clamp01(values[c]);
  } else if (name == GL_COMBINE_RGB) {
    if (!lookup(COMBINE_FUNCS, v)) return error(GL_INVALID_ENUM);
    unit.combine_rgb = v;
  } else if (name == GL_COMBINE_ALPHA) {
    // The dot products are colour functions only (ES 1.1 table 3.18).
    if (!lookup(COMBINE_FUNCS, v) || v == GL_DOT3_RGB || v == GL_DOT3_RGBA) return error(GL_INVALID_ENUM);
    unit.combine_alpha = v;
  } else if (in_triple(name, GL_SRC0_RGB, &i) || in_triple(name, GL_SRC0_ALPHA, &i)) {
    if (!lookup(COMBINE_SOURCES, v)) return error(GL_INVALID_ENUM);
    (name <= GL_SRC2_RGB ? unit.source_rgb : unit.source_alpha)[i] = v;
  } else if (in_triple(name, GL_OPERAND0_RGB, &i)) {
    if (!lookup(COMBINE_OPERANDS, v)) return error(GL_INVALID_ENUM);
    unit.operand_rgb[i] = v;
  } else if (in_triple(name, GL_OPERAND0_ALPHA, &i)) {
    // An alpha operand reads alpha only (ES 1.1 table 3.19).
    if (v != GL_SRC_ALPHA && v != GL_ONE_MINUS_SRC_ALPHA) return error(GL_INVALID_ENUM);
    unit.operand_alpha[i] = v;
  } else if (name == GL_RGB_SCALE || name == GL_ALPHA_SCALE) {
    if (values[0] != 1.0f && values[0] != 2.0f && values[0] != 4.0f) return error(GL_INVALID_VALUE);
    (name == GL_RGB_SCALE ? unit.rgb_scale : unit.alpha_scale) = values[0];
  } else {
    error(GL_INVALID_ENUM);
  }
}

void Context::get_tex_env(GLenum target, GLenum name, float* values) {
  charge_call();
  if (target != GL_TEXTURE_ENV) return error(GL_INVALID_ENUM);
  const TextureUnitState& unit = active_unit();
  int i = 0;
  if (name == GL_TEXTURE_ENV_MODE)
    values[0] = static_cast<float>(unit.env_mode);
  else if (name == GL_TEXTURE_ENV_COLOR)
    std::copy(unit.env_color, unit.env_color + 4, values);
  else if (name == GL_COMBINE_RGB)
    values[0] = static_cast<float>(unit.combine_rgb);
  else if (name == GL_COMBINE_ALPHA)
    values[0] = static_cast<float>(unit.combine_alpha);
  else if (in_triple(name, GL_SRC0_RGB, &i))
    values[0] = static_cast<float>(unit.source_rgb[i]);
  else if (in_triple(name, GL_SRC0_ALPHA, &i))
    values[0] = static_cast<float>(unit.source_alpha[i]);
  else if (in_triple(name, GL_OPERAND0_RGB, &i))
    values[0] = static_cast<float>(unit.operand_rgb[i]);
  else if (in_triple(name, GL_OPERAND0_ALPHA, &i))
    values[0] = static_cast<float>(unit.operand_alpha[i]);
  else if (name == GL_RGB_SCALE)
    values[0] = unit.rgb_scale;
  else if (name == GL_ALPHA_SCALE)
    values[0] = unit.alpha_scale;
  else
    error(GL_INVALID_ENUM);
}

}  // namespace tessera::gl
