// Bilinear texel filter and texture environment (OpenGL 1.2 "Texture
// Minification" and "Texture Environments and Texture Functions"; RGBA
// texture, environments REPLACE, MODULATE, DECAL) on RGBA8 (0.8) colour.
//
// Filter. The four texels of texel_address.h's footprint, (i0,j0), (i1,j0),
// (i0,j1), (i1,j1), are weighted with the 8-bit weights a (of i1) and b (of
// j1), both in 1/256:
//     w00 = (256 - a)(256 - b), w10 = a(256 - b), w01 = (256 - a) b, w11 = a b
// (sum 2^16), and each channel is (sum w * texel + 2^15) >> 16: the GL
// bilinear formula with 8-bit weights, rounded once to nearest, ties up. With
// NEAREST the weights are 0 and the result is texel (i0,j0) exactly, so the
// filter needs no mode input.
//
// Environment: the codes of common/fixed_function.def (TexEnv) that the
// StateBlock's 2-bit field carries; any other code (3 and up: BLEND, ADD
// and COMBINE, which the texture units' combiner draws, texture_combiner.h)
// passes the fragment colour through untouched. f = fragment colour, t = filtered
// texel colour, all 0.8 codes, "1 - x" is 255 - x:
//     REPLACE   C = Ct                     A = At
//     MODULATE  C = Cf * Ct                A = Af * At
//     DECAL     C = Cf (1 - At) + Ct At    A = Af
// Each product or sum of products x is divided by 255 with one exact
// rounding to nearest (x <= 65025; 255 is odd, ties cannot occur):
// t = x + 128, (t + (t >> 8)) >> 8 (the same divider as blending).
//
// Speed: inline, on packed words; the environment computes all three
// results and the code picks one, so there is no branch. The batch form
// (texture_filter_env_batch, batch.h) takes fragments under one environment.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "batch.h"
#include "common/fixed_function.h"
#include "fixed_point.h"

namespace tessera::raster {

// Exact round(x / 255) for 0 <= x <= 65025.
constexpr uint32_t div255_round(uint32_t x) {
  const uint32_t t = x + 128;
  return (t + (t >> 8)) >> 8;
}

// The filter on packed words (Rgba8::pack), texels in the order (i0,j0),
// (i1,j0), (i0,j1), (i1,j1), weights a and b in 0..255: what
// bilinear_filter and the batch form share.
constexpr uint32_t bilinear_filter_word(uint32_t t00, uint32_t t10, uint32_t t01, uint32_t t11, uint32_t a,
                                        uint32_t b) {
  const uint32_t w00 = (256 - a) * (256 - b), w10 = a * (256 - b), w01 = (256 - a) * b, w11 = a * b;
  uint32_t out = 0;
  for (unsigned c = 0; c < 32; c += 8) {
    const uint32_t sum =
        w00 * ((t00 >> c) & 0xff) + w10 * ((t10 >> c) & 0xff) + w01 * ((t01 >> c) & 0xff) + w11 * ((t11 >> c) & 0xff);
    out |= ((sum + (1u << 15)) >> 16) << c;
  }
  return out;
}

constexpr Rgba8 bilinear_filter(const std::array<Rgba8, 4>& texels, uint8_t weight_s, uint8_t weight_t) {
  return Rgba8::unpack(
      bilinear_filter_word(texels[0].pack(), texels[1].pack(), texels[2].pack(), texels[3].pack(), weight_s, weight_t));
}

// The environment on packed words: what texture_environment and the batch
// form share.
constexpr uint32_t texture_environment_word(TexEnv mode, uint32_t f, uint32_t t) {
  const uint32_t ta = t >> 24;
  uint32_t modulate = 0, decal = f & 0xff000000u;
  for (unsigned c = 0; c < 32; c += 8) {
    const uint32_t fc = (f >> c) & 0xff, tc = (t >> c) & 0xff;
    modulate |= div255_round(fc * tc) << c;
    if (c < 24) decal |= div255_round(fc * (255 - ta) + tc * ta) << c;
  }
  // Code 3 and above: the fragment.
  return select_code<uint32_t>(static_cast<unsigned>(mode), f, t, modulate, decal);
}

constexpr Rgba8 texture_environment(TexEnv mode, Rgba8 fragment, Rgba8 texel) {
  return Rgba8::unpack(texture_environment_word(mode, fragment.pack(), texel.pack()));
}

struct TextureEnvResult {
  Rgba8 texel;     // filtered
  Rgba8 fragment;  // after the environment
};

// Everything the Verilog unit texture_env.sv computes, in one call.
constexpr TextureEnvResult texture_filter_env(TexEnv mode, const std::array<Rgba8, 4>& texels, uint8_t weight_s,
                                              uint8_t weight_t, Rgba8 fragment) {
  TextureEnvResult r;
  r.texel = bilinear_filter(texels, weight_s, weight_t);
  r.fragment = texture_environment(mode, fragment, r.texel);
  return r;
}

// Batch form (batch.h): `count` fragments under one environment, colours as
// packed words (Rgba8::pack), weights as 8-bit codes in 32-bit elements (no
// output array may overlap an input array).
struct TextureEnvBatchInput {
  const uint32_t* texel[4];  // (i0,j0), (i1,j0), (i0,j1), (i1,j1)
  const uint32_t* weight_s;
  const uint32_t* weight_t;
  const uint32_t* fragment;
};
struct TextureEnvBatch {
  uint32_t* texel;     // filtered
  uint32_t* fragment;  // after the environment
};

struct TextureEnvKernel {
  TESSERA_BATCH_KERNEL void run(TexEnv mode, const TextureEnvBatchInput& in, unsigned count,
                                const TextureEnvBatch& out) {
    loop(mode, in.texel[0], in.texel[1], in.texel[2], in.texel[3], in.weight_s, in.weight_t, in.fragment, count,
         out.texel, out.fragment);
  }
  TESSERA_BATCH_KERNEL void loop(TexEnv mode, const uint32_t* __restrict t00, const uint32_t* __restrict t10,
                                 const uint32_t* __restrict t01, const uint32_t* __restrict t11,
                                 const uint32_t* __restrict ws, const uint32_t* __restrict wt,
                                 const uint32_t* __restrict fragment, unsigned count, uint32_t* __restrict texel,
                                 uint32_t* __restrict fragment_out) {
    for (unsigned i = 0; i < count; ++i) {
      const uint32_t filtered = bilinear_filter_word(t00[i], t10[i], t01[i], t11[i], ws[i] & 0xff, wt[i] & 0xff);
      texel[i] = filtered;
      fragment_out[i] = texture_environment_word(mode, fragment[i], filtered);
    }
  }
};

void texture_filter_env_batch(TexEnv mode, const TextureEnvBatchInput& in, unsigned count, const TextureEnvBatch& out,
                              BatchIsa isa = best_batch_isa());

}  // namespace tessera::raster
