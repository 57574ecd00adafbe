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
//
// Speed: inline; wrap and filter only select between values, so there is no
// branch.
#pragma once

#include <algorithm>
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

namespace texel_detail {
constexpr int64_t HALF_TEXEL = int64_t{1} << 15;
constexpr unsigned saturate_log2(unsigned log2_size) {
  return log2_size > TEXTURE_MAX_LOG2 ? TEXTURE_MAX_LOG2 : log2_size;
}
}  // namespace texel_detail

constexpr TexelAxis texel_axis_for(q15_16 coord, unsigned log2_size, TexWrap wrap, TexFilter filter) {
  using texel_detail::HALF_TEXEL;
  const unsigned log2n = texel_detail::saturate_log2(log2_size);
  const int64_t size = int64_t{1} << log2n;
  const bool clamp = wrap == TexWrap::clamp_to_edge;
  const bool linear = filter == TexFilter::linear;

  const int64_t u_raw = coord.raw * size;  // exact: |s| < 2^31, size <= 2^8
  const int64_t u = clamp ? clamp_i64(u_raw, HALF_TEXEL, (size << 16) - HALF_TEXEL) : u_raw;
  const int64_t v = linear ? u - HALF_TEXEL : u;
  const int64_t i0 = v >> 16;  // floor
  const int64_t i1 = linear ? i0 + 1 : i0;
  TexelAxis axis;
  axis.index0 = static_cast<uint8_t>(clamp ? i0 : (i0 & (size - 1)));
  axis.index1 = static_cast<uint8_t>(clamp ? std::min(i1, size - 1) : (i1 & (size - 1)));
  axis.weight = static_cast<uint8_t>(linear ? (v >> 8) & 0xff : 0);
  return axis;
}

constexpr uint32_t texel_address(uint32_t base, unsigned log2_width, uint8_t i, uint8_t j) {
  const uint32_t texel = (uint32_t{j} << texel_detail::saturate_log2(log2_width)) + i;
  return base + texel * 4;
}

// Everything the Verilog unit texel_address.sv computes, in one call.
constexpr TexelFootprint texel_lookup(const TextureState& state, q15_16 s, q15_16 t) {
  TexelFootprint f;
  f.s = texel_axis_for(s, state.log2_width, state.wrap_s, state.filter);
  f.t = texel_axis_for(t, state.log2_height, state.wrap_t, state.filter);
  f.address = {texel_address(state.base, state.log2_width, f.s.index0, f.t.index0),
               texel_address(state.base, state.log2_width, f.s.index1, f.t.index0),
               texel_address(state.base, state.log2_width, f.s.index0, f.t.index1),
               texel_address(state.base, state.log2_width, f.s.index1, f.t.index1)};
  return f;
}

}  // namespace tessera::raster
