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
// Speed: inline; the environment computes all three results and the code
// picks one, so there is no branch.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "common/fixed_function.h"
#include "fixed_point.h"

namespace tessera::raster {

// Exact round(x / 255) for 0 <= x <= 65025.
constexpr uint32_t div255_round(uint32_t x) {
  const uint32_t t = x + 128;
  return (t + (t >> 8)) >> 8;
}

// texels in the order (i0,j0), (i1,j0), (i0,j1), (i1,j1).
constexpr Rgba8 bilinear_filter(const std::array<Rgba8, 4>& texels, uint8_t weight_s, uint8_t weight_t) {
  const uint32_t a = weight_s;
  const uint32_t b = weight_t;
  const uint32_t w[4] = {(256 - a) * (256 - b), a * (256 - b), (256 - a) * b, a * b};
  const uint32_t t[4] = {texels[0].pack(), texels[1].pack(), texels[2].pack(), texels[3].pack()};
  uint32_t out = 0;
  for (unsigned c = 0; c < 32; c += 8) {
    uint32_t sum = 0;
    for (unsigned k = 0; k < 4; ++k) sum += w[k] * ((t[k] >> c) & 0xff);
    out |= ((sum + (1u << 15)) >> 16) << c;
  }
  return Rgba8::unpack(out);
}

constexpr Rgba8 texture_environment(TexEnv mode, Rgba8 fragment, Rgba8 texel) {
  const uint32_t f = fragment.pack(), t = texel.pack();
  const uint32_t ta = t >> 24;
  uint32_t modulate = 0, decal = f & 0xff000000u;
  for (unsigned c = 0; c < 32; c += 8) {
    const uint32_t fc = (f >> c) & 0xff, tc = (t >> c) & 0xff;
    modulate |= div255_round(fc * tc) << c;
    if (c < 24) decal |= div255_round(fc * (255 - ta) + tc * ta) << c;
  }
  const uint32_t results[4] = {t, modulate, decal, f};  // code 3 and above: the fragment
  return Rgba8::unpack(results[std::min(static_cast<unsigned>(mode), 3u)]);
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

}  // namespace tessera::raster
