// Memory's byte order, which hardware and software share: the little-endian
// 32-bit words of the rasterizer's tile table, command lists, state blocks,
// triangle records, texels and depth/stencil buffers (raster/command_format.h),
// the 16-bit pixels of an RGB565 colour buffer, and the driver's reads of
// an application's arrays (vertices, indices, packed pixels).
#pragma once

#include <cstdint>
#include <cstring>

namespace tessera {

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
constexpr bool HOST_LITTLE_ENDIAN = true;
#else
constexpr bool HOST_LITTLE_ENDIAN = false;
#endif

// Whether a word is read as a plain copy. On a little-endian host that can
// load a word from any address it is, and the compiler vectorises the
// rasterizer's row loops with it (byte by byte it does not). The ARM922T
// (ARMv4T, the driver on the ISS) has no unaligned loads: there GCC makes a
// copy of unknown alignment a call into the C library's memcpy, about 30
// instructions for four bytes, which a board's driver would not pay, so the
// bytes are put together instead (four LDRBs and three ORRs).
#if defined(__arm__) && !defined(__ARM_FEATURE_UNALIGNED)
constexpr bool WORD_COPY = false;
#else
constexpr bool WORD_COPY = HOST_LITTLE_ENDIAN;
#endif

inline uint32_t load_le32(const uint8_t* p) {
  if constexpr (WORD_COPY) {
    uint32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

inline void store_le32(uint8_t* p, uint32_t v) {
  if constexpr (WORD_COPY) {
    std::memcpy(p, &v, sizeof v);
    return;
  }
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
  p[2] = uint8_t(v >> 16);
  p[3] = uint8_t(v >> 24);
}

inline uint32_t load_le16(const uint8_t* p) {
  if constexpr (WORD_COPY) {
    uint16_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  return uint32_t{p[0]} | uint32_t{p[1]} << 8;
}

inline void store_le16(uint8_t* p, uint32_t v) {
  if constexpr (WORD_COPY) {
    const auto half = static_cast<uint16_t>(v);
    std::memcpy(p, &half, sizeof half);
    return;
  }
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
}

// The float whose IEEE bits are the little-endian word at p (a copy of a
// register's bits: no library call on any host).
inline float load_float(const uint8_t* p) {
  const uint32_t bits = load_le32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// Copies the four bytes of an RGBA8 texel (or any 32-bit word, byte order
// kept) from `from` to `out`.
inline void copy_word(const uint8_t* from, uint8_t* out) {
  if constexpr (WORD_COPY) {
    std::memcpy(out, from, 4);
    return;
  }
  out[0] = from[0];
  out[1] = from[1];
  out[2] = from[2];
  out[3] = from[3];
}

}  // namespace tessera
