// The frame-buffer pixel formats (pixel_format.def), and the one conversion
// rule between them and 8-bit colour that the display, the renderers, the
// rasterizer core, the comparison tools and the tests all use.
//
// Reduction of an 8-bit channel c to n bits rounds to nearest:
//   round(c * (2^n - 1) / 255)
// which is GL's conversion of a normalised colour c / 255 to an n-bit unsigned
// normalised value, and what Mesa does when it writes an RGB565 surface. There
// is no tie to break: 2 * c * (2^n - 1) is even and 255 * (2k + 1) is odd.
// Expansion of an n-bit channel back to 8 bits is bit replication (the code's
// top bits repeated below it: 0 -> 0, 31 -> 255), as Mesa widens unorm
// values and as display hardware does; it is within one step of
// round(v * 255 / (2^n - 1)), and reducing an expanded value gives the code
// back (the tests check every code).
//
// Pixels are little-endian in memory; a colour word holds R in bits 7:0, G in
// 15:8, B in 23:16 and A in 31:24 (RGBA8888's layout). Plain C++, no SystemC.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tessera {

enum class PixelFormat : uint32_t {
#define TESSERA_PIXEL_FORMAT(name, code, bytes, r, g, b, a, description) name = (code),
#include "common/pixel_format.def"
#undef TESSERA_PIXEL_FORMAT
};

struct PixelFormatInfo {
  PixelFormat format;
  const char* name;
  unsigned bytes;
  unsigned red_bits, green_bits, blue_bits, alpha_bits;
  const char* description;
};

inline constexpr PixelFormatInfo PIXEL_FORMATS[] = {
#define TESSERA_PIXEL_FORMAT(name, code, bytes, r, g, b, a, description) \
  {PixelFormat::name, #name, bytes, r, g, b, a, description},
#include "common/pixel_format.def"
#undef TESSERA_PIXEL_FORMAT
};

constexpr const PixelFormatInfo& pixel_format_info(PixelFormat format) {
  for (const PixelFormatInfo& info : PIXEL_FORMATS)
    if (info.format == format) return info;
  return PIXEL_FORMATS[0];
}

constexpr unsigned bytes_per_pixel(PixelFormat format) {
  return pixel_format_info(format).bytes;
}
constexpr const char* pixel_format_name(PixelFormat format) {
  return pixel_format_info(format).name;
}

// The format a register code or a name stands for; nothing if none.
inline std::optional<PixelFormat> pixel_format_from_code(uint32_t code) {
  for (const PixelFormatInfo& info : PIXEL_FORMATS)
    if (static_cast<uint32_t>(info.format) == code) return info.format;
  return std::nullopt;
}
inline std::optional<PixelFormat> pixel_format_from_name(std::string_view name) {
  for (const PixelFormatInfo& info : PIXEL_FORMATS)
    if (name == info.name) return info.format;
  return std::nullopt;
}

// "rgb565, rgba8888": for messages and the configuration's choices.
inline std::string pixel_format_names(const char* separator = ", ") {
  std::string names;
  for (const PixelFormatInfo& info : PIXEL_FORMATS) names += (names.empty() ? "" : separator) + std::string(info.name);
  return names;
}

// round(c * (2^bits - 1) / 255), for c in [0, 255] and bits in [1, 8].
constexpr uint32_t reduce_channel(uint32_t c, unsigned bits) {
  const uint32_t max = (1u << bits) - 1;
  return (c * max + 127) / 255;
}

// Bit replication of a `bits`-bit code to 8 bits.
constexpr uint32_t expand_channel(uint32_t v, unsigned bits) {
  uint32_t out = 0;
  for (int shift = 8 - static_cast<int>(bits); shift > -static_cast<int>(bits); shift -= static_cast<int>(bits))
    out |= shift >= 0 ? v << shift : v >> -shift;
  return out & 0xff;
}

// A colour word in the format's packed layout (the low bytes_per_pixel bytes).
constexpr uint32_t pack_pixel(PixelFormat format, uint32_t rgba) {
  if (format == PixelFormat::rgba8888) return rgba;
  const uint32_t r = reduce_channel(rgba & 0xff, 5), g = reduce_channel((rgba >> 8) & 0xff, 6),
                 b = reduce_channel((rgba >> 16) & 0xff, 5);
  return r << 11 | g << 5 | b;
}

// The colour word a packed pixel shows; alpha is 255 where the format has none.
constexpr uint32_t unpack_pixel(PixelFormat format, uint32_t packed) {
  if (format == PixelFormat::rgba8888) return packed;
  return expand_channel((packed >> 11) & 31, 5) | expand_channel((packed >> 5) & 63, 6) << 8 |
         expand_channel(packed & 31, 5) << 16 | 0xffu << 24;
}

// What a display in `format` shows for a colour: pack, then unpack.
constexpr uint32_t quantize_color(PixelFormat format, uint32_t rgba) {
  return unpack_pixel(format, pack_pixel(format, rgba));
}

// The packed bits that hold the channels a glColorMask leaves writable
// (mask bit 0 red, 1 green, 2 blue, 3 alpha).
constexpr uint32_t channel_bits(PixelFormat format, unsigned color_mask) {
  if (format == PixelFormat::rgba8888)
    return (color_mask & 1 ? 0xffu : 0) | (color_mask & 2 ? 0xff00u : 0) | (color_mask & 4 ? 0xff0000u : 0) |
           (color_mask & 8 ? 0xff000000u : 0);
  return (color_mask & 1 ? 0xf800u : 0) | (color_mask & 2 ? 0x07e0u : 0) | (color_mask & 4 ? 0x001fu : 0);
}

// Little-endian pixel access in a frame buffer.
inline uint32_t load_pixel(PixelFormat format, const uint8_t* p) {
  return format == PixelFormat::rgba8888
             ? uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24
             : uint32_t{p[0]} | uint32_t{p[1]} << 8;
}
inline void store_pixel(PixelFormat format, uint8_t* p, uint32_t packed) {
  p[0] = static_cast<uint8_t>(packed);
  p[1] = static_cast<uint8_t>(packed >> 8);
  if (format == PixelFormat::rgba8888) {
    p[2] = static_cast<uint8_t>(packed >> 16);
    p[3] = static_cast<uint8_t>(packed >> 24);
  }
}

}  // namespace tessera
