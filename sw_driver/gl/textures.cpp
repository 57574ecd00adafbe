// Texture objects, images, parameters and the texture environment.
#include "gl/context.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/context_internal.h"
#include "gl/runtime.h"

namespace tessera::gl {

void Context::gen_textures(GLsizei n, GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    while (m_textures.count(m_next_texture)) ++m_next_texture;
    names[i] = m_next_texture;
    m_textures[m_next_texture++] = TextureObject{};
  }
}

void Context::delete_textures(GLsizei n, const GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    if (names[i] == 0) continue;
    m_textures.erase(names[i]);  // system memory of the texels is not reused (bump allocator)
    if (m_bound_texture == names[i]) m_bound_texture = 0;
  }
}

void Context::bind_texture(GLenum target, GLuint name) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  if (name != 0 && !m_textures.count(name)) m_textures[name] = TextureObject{};
  m_bound_texture = name;
}

bool Context::is_texture(GLuint name) {
  charge_call();
  return name != 0 && m_textures.count(name) != 0;
}

TextureObject* Context::bound_texture() {
  // Texture object 0 is the default texture, which exists like any other.
  return &m_textures[m_bound_texture];
}

namespace {

// Bytes per pixel of an external format, 0 for a bad combination.
int pixel_bytes(GLenum format, GLenum type, bool* format_ok, bool* type_ok) {
  *format_ok = format == GL_RGBA || format == GL_RGB || format == GL_LUMINANCE || format == GL_ALPHA ||
               format == GL_LUMINANCE_ALPHA;
  *type_ok = type == GL_UNSIGNED_BYTE;
  if (!*format_ok || !*type_ok) return 0;
  switch (format) {
    case GL_RGBA: return 4;
    case GL_RGB: return 3;
    case GL_LUMINANCE_ALPHA: return 2;
    default: return 1;
  }
}

void expand_texel(GLenum format, const uint8_t* in, uint8_t* out) {
  switch (format) {
    case GL_RGBA: std::memcpy(out, in, 4); break;
    case GL_RGB: out[0] = in[0], out[1] = in[1], out[2] = in[2], out[3] = 255; break;
    case GL_LUMINANCE: out[0] = out[1] = out[2] = in[0], out[3] = 255; break;
    case GL_LUMINANCE_ALPHA: out[0] = out[1] = out[2] = in[0], out[3] = in[1]; break;
    case GL_ALPHA: out[0] = out[1] = out[2] = 0, out[3] = in[0]; break;
  }
}

}  // namespace

void Context::tex_image(GLenum target, GLint level, GLint internal_format, GLsizei width, GLsizei height, GLint border,
                        GLenum format, GLenum type, const void* pixels) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  bool format_ok, type_ok;
  pixel_bytes(format, type, &format_ok, &type_ok);
  if (!format_ok || !type_ok) return error(GL_INVALID_ENUM);
  if (level < 0 || border != 0 || width < 0 || height < 0 || width > MAX_TEXTURE_SIZE || height > MAX_TEXTURE_SIZE ||
      (width && !is_power_of_two(width)) || (height && !is_power_of_two(height)))
    return error(GL_INVALID_VALUE);
  if (static_cast<GLenum>(internal_format) != format) return error(GL_INVALID_OPERATION);
  if (level > 0) return;  // mipmap levels are accepted and not used: no mipmapping (documented)
  TextureObject* object = bound_texture();
  const uint32_t texel_bytes = static_cast<uint32_t>(width) * height * 4;
  if (texel_bytes == 0) {
    object->defined = false;
    return;
  }
  // Stored as RGBA8 in system memory, where every back end fetches it.
  if (object->texture.width != static_cast<unsigned>(width) ||
      object->texture.height != static_cast<unsigned>(height) || object->texture.address == 0)
    object->texture.address = allocate(texel_bytes);
  object->texture.width = static_cast<unsigned>(width);
  object->texture.height = static_cast<unsigned>(height);
  object->defined = true;
  if (pixels) tex_sub_image(target, 0, 0, 0, width, height, format, type, pixels);
}

void Context::tex_sub_image(GLenum target, GLint level, GLint x, GLint y, GLsizei width, GLsizei height, GLenum format,
                            GLenum type, const void* pixels) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  bool format_ok, type_ok;
  const int bytes = pixel_bytes(format, type, &format_ok, &type_ok);
  if (!format_ok || !type_ok) return error(GL_INVALID_ENUM);
  TextureObject* object = bound_texture();
  if (!object->defined) return error(GL_INVALID_OPERATION);
  if (level < 0 || x < 0 || y < 0 || width < 0 || height < 0 || !fits(x, width, object->texture.width) ||
      !fits(y, height, object->texture.height))
    return error(GL_INVALID_VALUE);
  if (level > 0 || !pixels) return;
  const auto* in = static_cast<const uint8_t*>(pixels);
  const size_t row_bytes = static_cast<size_t>(width) * bytes;
  const size_t stride = (row_bytes + m_unpack_alignment - 1) / m_unpack_alignment * m_unpack_alignment;
  std::vector<uint32_t> row(static_cast<size_t>(width));
  for (GLsizei j = 0; j < height; ++j) {
    for (GLsizei i = 0; i < width; ++i)
      expand_texel(format, in + j * stride + static_cast<size_t>(i) * bytes, reinterpret_cast<uint8_t*>(&row[i]));
    // The driver's conversion loop: a load, a few shifts and a store per texel.
    m_host.compute(Op::alu, 4ull * width);
    const uint32_t address = object->texture.address + ((y + j) * object->texture.width + x) * 4;
    for (GLsizei i = 0; i < width; i += 8)
      m_host.write_words(address + 4 * i, &row[i], static_cast<unsigned>(std::min<GLsizei>(8, width - i)));
  }
}

void Context::tex_parameter(GLenum target, GLenum name, float value) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  Texture& t = bound_texture()->texture;
  const std::optional<GLenum> v = enum_from_float(value);
  switch (name) {
    case GL_TEXTURE_MIN_FILTER:
      if (!v || !tex_filter_value(*v, true, &t.min_filter)) error(GL_INVALID_ENUM);
      break;
    case GL_TEXTURE_MAG_FILTER:
      if (!v || !tex_filter_value(*v, false, &t.mag_filter)) error(GL_INVALID_ENUM);
      break;
    case GL_TEXTURE_WRAP_S:
      if (!v || !tex_wrap_value(*v, &t.wrap_s)) error(GL_INVALID_ENUM);
      break;
    case GL_TEXTURE_WRAP_T:
      if (!v || !tex_wrap_value(*v, &t.wrap_t)) error(GL_INVALID_ENUM);
      break;
    case GL_GENERATE_MIPMAP: break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::get_tex_parameter(GLenum target, GLenum name, float* value) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  const Texture& t = bound_texture()->texture;
  switch (name) {
    case GL_TEXTURE_MIN_FILTER: *value = static_cast<float>(gl_value(t.min_filter)); break;
    case GL_TEXTURE_MAG_FILTER: *value = static_cast<float>(gl_value(t.mag_filter)); break;
    case GL_TEXTURE_WRAP_S: *value = static_cast<float>(gl_value(t.wrap_s)); break;
    case GL_TEXTURE_WRAP_T: *value = static_cast<float>(gl_value(t.wrap_t)); break;
    case GL_GENERATE_MIPMAP: *value = GL_FALSE; break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::tex_env(GLenum target, GLenum name, const float* values, int count) {
  charge_call();
  if (target != GL_TEXTURE_ENV) return error(GL_INVALID_ENUM);
  if (name == GL_TEXTURE_ENV_MODE) {
    const GLenum mode = enum_from_float(values[0]).value_or(0u);  // 0 is no mode
    if (mode != GL_MODULATE && mode != GL_REPLACE && mode != GL_DECAL && mode != GL_BLEND && mode != GL_ADD &&
        mode != GL_COMBINE)
      return error(GL_INVALID_ENUM);
    // BLEND, ADD and COMBINE are valid GL ES 1.1 and stored; the back ends
    // render them as MODULATE (documented limitation).
    m_tex_env_mode = mode;
  } else if (name == GL_TEXTURE_ENV_COLOR) {
    if (count < 4) return error(GL_INVALID_ENUM);
    for (int i = 0; i < 4; ++i) m_tex_env_color[i] = clamp01(values[i]);
  } else {
    error(GL_INVALID_ENUM);
  }
}

void Context::get_tex_env(GLenum target, GLenum name, float* values) {
  charge_call();
  if (target != GL_TEXTURE_ENV) return error(GL_INVALID_ENUM);
  if (name == GL_TEXTURE_ENV_MODE)
    values[0] = static_cast<float>(m_tex_env_mode);
  else if (name == GL_TEXTURE_ENV_COLOR)
    std::copy(m_tex_env_color, m_tex_env_color + 4, values);
  else
    error(GL_INVALID_ENUM);
}

}  // namespace tessera::gl
