// Texel formats and their conversion to RGBA8; see texture_formats.h.
#include "gl/texture_formats.h"

#include <algorithm>

#include "common/little_endian.h"

namespace tessera::gl {

namespace {

bool is_format(GLenum format) {
  return format == GL_RGBA || format == GL_RGB || format == GL_LUMINANCE || format == GL_ALPHA ||
         format == GL_LUMINANCE_ALPHA;
}

bool is_type(GLenum type) {
  return type == GL_UNSIGNED_BYTE || type == GL_UNSIGNED_SHORT_5_6_5 || type == GL_UNSIGNED_SHORT_4_4_4_4 ||
         type == GL_UNSIGNED_SHORT_5_5_5_1;
}

// Component `c` of `bits` bits as an 8-bit code, round(c * 255 / (2^bits - 1)).
uint32_t widen(uint32_t c, unsigned bits) {
  const uint32_t max = (1u << bits) - 1;
  return (c * 255 + max / 2) / max;
}

uint32_t rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return r | g << 8 | b << 16 | a << 24;
}

}  // namespace

GLenum format_type_error(GLenum format, GLenum type) {
  if (!is_format(format) || !is_type(type)) return GL_INVALID_ENUM;
  if (type == GL_UNSIGNED_SHORT_5_6_5 && format != GL_RGB) return GL_INVALID_OPERATION;
  if ((type == GL_UNSIGNED_SHORT_4_4_4_4 || type == GL_UNSIGNED_SHORT_5_5_5_1) && format != GL_RGBA)
    return GL_INVALID_OPERATION;
  return 0;
}

unsigned pixel_bytes(GLenum format, GLenum type) {
  if (format_type_error(format, type) != 0) return 0;
  if (type != GL_UNSIGNED_BYTE) return 2;
  switch (format) {
    case GL_RGBA: return 4;
    case GL_RGB: return 3;
    case GL_LUMINANCE_ALPHA: return 2;
    default: return 1;
  }
}

uint32_t unpack_pixel(GLenum format, GLenum type, const uint8_t* in) {
  if (type != GL_UNSIGNED_BYTE) {
    const uint32_t p = load_le16(in);
    switch (type) {
      case GL_UNSIGNED_SHORT_5_6_5: return rgba(widen(p >> 11, 5), widen((p >> 5) & 63, 6), widen(p & 31, 5), 255);
      case GL_UNSIGNED_SHORT_4_4_4_4:
        return rgba(widen(p >> 12, 4), widen((p >> 8) & 15, 4), widen((p >> 4) & 15, 4), widen(p & 15, 4));
      default:  // GL_UNSIGNED_SHORT_5_5_5_1
        return rgba(widen(p >> 11, 5), widen((p >> 6) & 31, 5), widen((p >> 1) & 31, 5), (p & 1) ? 255 : 0);
    }
  }
  switch (format) {
    case GL_RGBA: return rgba(in[0], in[1], in[2], in[3]);
    case GL_RGB: return rgba(in[0], in[1], in[2], 255);
    case GL_LUMINANCE: return rgba(in[0], in[0], in[0], 255);
    case GL_LUMINANCE_ALPHA: return rgba(in[0], in[0], in[0], in[1]);
    default: return rgba(0, 0, 0, in[0]);  // GL_ALPHA
  }
}

const PaletteFormat PALETTE_FORMATS[PALETTE_FORMAT_COUNT] = {
    {GL_PALETTE4_RGB8_OES, 4, GL_RGB, GL_UNSIGNED_BYTE},
    {GL_PALETTE4_RGBA8_OES, 4, GL_RGBA, GL_UNSIGNED_BYTE},
    {GL_PALETTE4_R5_G6_B5_OES, 4, GL_RGB, GL_UNSIGNED_SHORT_5_6_5},
    {GL_PALETTE4_RGBA4_OES, 4, GL_RGBA, GL_UNSIGNED_SHORT_4_4_4_4},
    {GL_PALETTE4_RGB5_A1_OES, 4, GL_RGBA, GL_UNSIGNED_SHORT_5_5_5_1},
    {GL_PALETTE8_RGB8_OES, 8, GL_RGB, GL_UNSIGNED_BYTE},
    {GL_PALETTE8_RGBA8_OES, 8, GL_RGBA, GL_UNSIGNED_BYTE},
    {GL_PALETTE8_R5_G6_B5_OES, 8, GL_RGB, GL_UNSIGNED_SHORT_5_6_5},
    {GL_PALETTE8_RGBA4_OES, 8, GL_RGBA, GL_UNSIGNED_SHORT_4_4_4_4},
    {GL_PALETTE8_RGB5_A1_OES, 8, GL_RGBA, GL_UNSIGNED_SHORT_5_5_5_1},
};

const PaletteFormat* find_palette_format(GLenum name) {
  for (const PaletteFormat& f : PALETTE_FORMATS)
    if (f.name == name) return &f;
  return nullptr;
}

namespace {

size_t palette_bytes(const PaletteFormat& format) {
  return (size_t{1} << format.index_bits) * pixel_bytes(format.entry_format, format.entry_type);
}

size_t level_index_bytes(const PaletteFormat& format, unsigned width, unsigned height, unsigned level) {
  const size_t texels = size_t{std::max(1u, width >> level)} * std::max(1u, height >> level);
  return (texels * format.index_bits + 7) / 8;
}

}  // namespace

size_t paletted_image_size(const PaletteFormat& format, unsigned width, unsigned height, unsigned levels) {
  size_t bytes = palette_bytes(format);
  for (unsigned level = 0; level < levels; ++level) bytes += level_index_bytes(format, width, height, level);
  return bytes;
}

void decode_paletted_level(const PaletteFormat& format, const uint8_t* data, unsigned width, unsigned height,
                           unsigned level, uint32_t* out) {
  const unsigned entry_bytes = pixel_bytes(format.entry_format, format.entry_type);
  const uint8_t* indices = data + palette_bytes(format);
  for (unsigned k = 0; k < level; ++k) indices += level_index_bytes(format, width, height, k);
  const size_t texels = size_t{std::max(1u, width >> level)} * std::max(1u, height >> level);
  for (size_t i = 0; i < texels; ++i) {
    const unsigned index =
        format.index_bits == 8 ? indices[i] : (i % 2 == 0 ? indices[i / 2] >> 4 : indices[i / 2] & 15u);
    out[i] = unpack_pixel(format.entry_format, format.entry_type, data + size_t{index} * entry_bytes);
  }
}

void box_filter_level(const uint32_t* in, unsigned width, unsigned height, uint32_t* out) {
  const unsigned w = std::max(1u, width / 2), h = std::max(1u, height / 2);
  const unsigned dx = width > 1 ? 1 : 0, dy = height > 1 ? 1 : 0;
  for (unsigned j = 0; j < h; ++j) {
    for (unsigned i = 0; i < w; ++i) {
      const unsigned x0 = i * (dx + 1), y0 = j * (dy + 1);
      const uint32_t t[4] = {in[y0 * width + x0], in[y0 * width + x0 + dx], in[(y0 + dy) * width + x0],
                             in[(y0 + dy) * width + x0 + dx]};
      uint32_t result = 0;
      for (unsigned ch = 0; ch < 4; ++ch) {
        uint32_t sum = 0;
        for (uint32_t texel : t) sum += (texel >> (8 * ch)) & 255;
        result |= ((sum + 2) / 4) << (8 * ch);
      }
      out[j * w + i] = result;
    }
  }
}

}  // namespace tessera::gl
