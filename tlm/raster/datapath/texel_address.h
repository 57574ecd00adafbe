// Texel addressing: from a texture coordinate pair to texel indices,
// bilinear weights and the byte addresses of the texels (RGBA8, fetched from
// system memory).
//
// Source: OpenGL 1.2.1 specification, "Texturing" (texture wrap
// modes, minification/magnification with NEAREST and LINEAR): u = s * 2^n,
// NEAREST takes i = floor(u); LINEAR takes i0 = floor(u - 1/2),
// i1 = i0 + 1, alpha = frac(u - 1/2); REPEAT reduces indices modulo the size;
// CLAMP_TO_EDGE clamps s to [1/(2N), 1 - 1/(2N)] first, so that only edge
// texels are ever used, and clamps i1 to N - 1.
//
// Formats and rounding:
//   s, t       signed q15.16 (the attribute interpolator's output)
//   sizes      power of two, log2 0..8 (1..256 texels); a larger log2 acts
//              as 8 (the field is 4 bits wide in hardware)
//   u          s << log2 N, signed 40-bit with 16 fraction bits, exact
//   clamp      CLAMP_TO_EDGE: u limited to [2^15, N * 2^16 - 2^15] codes
//   indices    NEAREST: i0 = i1 = floor(u); LINEAR: v = u - 2^15,
//              i0 = floor(v / 2^16), i1 = i0 + 1; then REPEAT masks with
//              N - 1 (two's complement modulo), CLAMP_TO_EDGE sets
//              i1 = min(i1, N - 1). 8 bits each.
//   weights    LINEAR: bits 15:8 of v, i.e. frac(u - 1/2) truncated to 8
//              bits (weight of i1 resp. j1 in units of 1/256); NEAREST: 0
//   address    base + ((j << log2 width) + i) * 4, modulo 2^32, for the four
//              texels (i0,j0), (i1,j0), (i0,j1), (i1,j1); with NEAREST all
//              four are the same texel.
// Wraps and filters are the codes of common/fixed_function.def (TexWrap,
// TexFilter), the numbers the Verilog unit's fields take; a wrap code without
// an entry (2, 3) is taken as REPEAT, the GL default.
#pragma once

#include <array>
#include <cstdint>

#include "common/fixed_function.h"
#include "fixed_point.h"

namespace tessera::raster {

constexpr unsigned TEXTURE_MAX_LOG2 = 8;

struct TextureState {
  uint32_t base = 0;
  uint8_t log2_width = 0;
  uint8_t log2_height = 0;
  TexWrap wrap_s = TexWrap::repeat;
  TexWrap wrap_t = TexWrap::repeat;
  TexFilter filter = TexFilter::nearest;
};

struct TexelAxis {
  uint8_t index0 = 0;
  uint8_t index1 = 0;
  uint8_t weight = 0;  // of index1, in 1/256
};

struct TexelFootprint {
  TexelAxis s;  // i0, i1, alpha
  TexelAxis t;  // j0, j1, beta
  // (i0,j0), (i1,j0), (i0,j1), (i1,j1)
  std::array<uint32_t, 4> address{};
};

TexelAxis texel_axis_for(q15_16 coord, unsigned log2_size, TexWrap wrap, TexFilter filter);
uint32_t texel_address(uint32_t base, unsigned log2_width, uint8_t i, uint8_t j);

// Everything the Verilog unit texel_address.sv computes, in one call.
TexelFootprint texel_lookup(const TextureState& state, q15_16 s, q15_16 t);

}  // namespace tessera::raster
