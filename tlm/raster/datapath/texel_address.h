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
// Speed: inline, in 32-bit arithmetic (below); wrap and filter only select
// between values, so there is no branch. The batch form
// (texel_lookup_batch, batch.h) takes coordinate pairs on one texture.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "batch.h"
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

// In 32 bits, exactly as the 40-bit u of the header: with p = floor(u / 2^8)
// = s >> (8 - log2 N) (s * 2^log2 N needs 40 bits, p 32), CLAMP_TO_EDGE's
// bounds on u, multiples of 2^8, become [2^7, N * 2^8 - 2^7] on p, and
// w = floor(v / 2^8) = p - 2^7 (LINEAR) or p (NEAREST); i0 = w >> 8 and the
// weight is w's low byte. REPEAT keeps only the low bits of i0 and i1, so w
// may wrap modulo 2^32 there. Only 32-bit lanes: a batch of them vectorises
// where 64-bit multiplies and shifts would not.
constexpr TexelAxis texel_axis_for(q15_16 coord, unsigned log2_size, TexWrap wrap, TexFilter filter) {
  const unsigned log2n = texel_detail::saturate_log2(log2_size);
  const uint32_t last = (1u << log2n) - 1;
  const bool clamp = wrap == TexWrap::clamp_to_edge;
  const bool linear = filter == TexFilter::linear;

  const int32_t p = static_cast<int32_t>(coord.raw) >> (8 - log2n);
  const int32_t half = 1 << 7;  // half a texel in units of 2^8 of u
  const int32_t top = static_cast<int32_t>((last + 1) << 8) - half;
  const int32_t clamped = p < half ? half : (p > top ? top : p);
  const uint32_t w = static_cast<uint32_t>(clamp ? clamped : p) - (linear ? static_cast<uint32_t>(half) : 0u);
  const uint32_t i0 = w >> 8;
  const uint32_t i1 = linear ? i0 + 1 : i0;
  TexelAxis axis;
  axis.index0 = static_cast<uint8_t>(clamp ? i0 : (i0 & last));
  axis.index1 = static_cast<uint8_t>(clamp ? std::min(i1, last) : (i1 & last));
  axis.weight = static_cast<uint8_t>(linear ? w & 0xff : 0);
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

// Batch form (batch.h): `count` coordinate pairs (q15.16 codes) on one
// texture, every field of the footprints in an array of its own.
struct TexelBatch {
  uint32_t* s_index0;
  uint32_t* s_index1;
  uint32_t* s_weight;
  uint32_t* t_index0;
  uint32_t* t_index1;
  uint32_t* t_weight;
  uint32_t* address[4];  // (i0,j0), (i1,j0), (i0,j1), (i1,j1)
};

struct TexelKernel {
  TESSERA_BATCH_KERNEL void run(const TextureState& state, const int32_t* s, const int32_t* t, unsigned count,
                                const TexelBatch& out) {
    loop(state, s, t, count, out.s_index0, out.s_index1, out.s_weight, out.t_index0, out.t_index1, out.t_weight,
         out.address[0], out.address[1], out.address[2], out.address[3]);
  }
  TESSERA_BATCH_KERNEL void loop(const TextureState state, const int32_t* __restrict s, const int32_t* __restrict t,
                                 unsigned count, uint32_t* __restrict i0, uint32_t* __restrict i1,
                                 uint32_t* __restrict wi, uint32_t* __restrict j0, uint32_t* __restrict j1,
                                 uint32_t* __restrict wj, uint32_t* __restrict a00, uint32_t* __restrict a10,
                                 uint32_t* __restrict a01, uint32_t* __restrict a11) {
    for (unsigned i = 0; i < count; ++i) {
      const TexelAxis u = texel_axis_for(q15_16{s[i]}, state.log2_width, state.wrap_s, state.filter);
      const TexelAxis v = texel_axis_for(q15_16{t[i]}, state.log2_height, state.wrap_t, state.filter);
      i0[i] = u.index0;
      i1[i] = u.index1;
      wi[i] = u.weight;
      j0[i] = v.index0;
      j1[i] = v.index1;
      wj[i] = v.weight;
      a00[i] = texel_address(state.base, state.log2_width, u.index0, v.index0);
      a10[i] = texel_address(state.base, state.log2_width, u.index1, v.index0);
      a01[i] = texel_address(state.base, state.log2_width, u.index0, v.index1);
      a11[i] = texel_address(state.base, state.log2_width, u.index1, v.index1);
    }
  }
};

void texel_lookup_batch(const TextureState& state, const int32_t* s, const int32_t* t, unsigned count,
                        const TexelBatch& out, BatchIsa isa = best_batch_isa());

}  // namespace tessera::raster
