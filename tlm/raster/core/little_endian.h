// The little-endian 32-bit words of the tile table, command lists, state
// blocks, triangle records, texels and depth/stencil buffers in memory
// (command_format.h).
#pragma once

#include <cstdint>
#include <cstring>

namespace tessera::raster {

inline uint32_t load_le32(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

inline void store_le32(uint8_t* p, uint32_t v) {
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
  p[2] = uint8_t(v >> 16);
  p[3] = uint8_t(v >> 24);
}

inline float load_float(const uint8_t* p) {
  const uint32_t bits = load_le32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

}  // namespace tessera::raster
