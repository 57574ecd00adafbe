// The little-endian 32-bit words of the tile table, command lists, state
// blocks, triangle records, texels and depth/stencil buffers in memory
// (command_format.h), and the 16-bit pixels of an RGB565 colour buffer.
#pragma once

#include <cstdint>
#include <cstring>

namespace tessera::raster {

// On a little-endian host a word is a plain copy, which the compiler
// vectorises in the tile cache's row loops (byte by byte it does not).
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
constexpr bool HOST_LITTLE_ENDIAN = true;
#else
constexpr bool HOST_LITTLE_ENDIAN = false;
#endif

inline uint32_t load_le32(const uint8_t* p) {
  if constexpr (HOST_LITTLE_ENDIAN) {
    uint32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

inline void store_le32(uint8_t* p, uint32_t v) {
  if constexpr (HOST_LITTLE_ENDIAN) {
    std::memcpy(p, &v, sizeof v);
    return;
  }
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
  p[2] = uint8_t(v >> 16);
  p[3] = uint8_t(v >> 24);
}

inline uint32_t load_le16(const uint8_t* p) {
  if constexpr (HOST_LITTLE_ENDIAN) {
    uint16_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  return uint32_t{p[0]} | uint32_t{p[1]} << 8;
}

inline void store_le16(uint8_t* p, uint32_t v) {
  if constexpr (HOST_LITTLE_ENDIAN) {
    const auto half = static_cast<uint16_t>(v);
    std::memcpy(p, &half, sizeof half);
    return;
  }
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
}

inline float load_float(const uint8_t* p) {
  const uint32_t bits = load_le32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

}  // namespace tessera::raster
