// Texture combiner: the environment of one texture unit (OpenGL ES 1.1,
// section 3.7.12, tables 3.15 to 3.18) on RGBA8 (0.8) colour, for the
// rasterizer's texture units (command_format.h, TextureUnitState). Units
// are chained: each takes the previous unit's result (the interpolated
// colour for the first) and the interpolated colour itself (GL_PRIMARY_COLOR).
//
// Ports: env (TexEnv, 3 bits), base format (TexBaseFormat, 3 bits), primary,
// previous, the filtered texel as the texture stores it (missing components
// expanded: colour 0, alpha 255), the env colour (GL_TEXTURE_ENV_COLOR) and
// the two combiner words (TextureUnitState::combine_rgb and combine_alpha,
// COMBINE_* fields); out: the unit's colour. f is `previous`, t the texel,
// c the env colour; "1 - x" is 255 - x and a product is divided by 255 with
// one exact rounding to nearest (texture_env.h, div255_round):
//     REPLACE   C = Ct                    A = At
//     MODULATE  C = Cf Ct (rounded)       A = Af At (rounded)
//     DECAL     C = Cf (1 - At) + Ct At   A = Af          (rounded once)
//     BLEND     C = Cf (1 - Ct) + Cc Ct   A = Af At       (each rounded once)
//     ADD       C = min(Cf + Ct, 255)     A = Af At       (rounded)
//     COMBINE   below
//     codes 6, 7: C, A = f (the input passes through)
// Base format (table 3.15): a texture without alpha (RGB, LUMINANCE) takes
// A = Af under REPLACE; one without colour (ALPHA) takes C = Cf under
// REPLACE and MODULATE. The other modes give the table's result from the
// expanded texel as it is (Af * 255 rounds to Af, Cf (1 - 0) + Cc 0 = Cf).
// Base format codes 5 to 7 act as RGBA.
//
// COMBINE: argument k of a stage is its source (texture, constant, primary,
// previous) through its operand (channel, 255 - channel, alpha, 255 -
// alpha; the alpha stage's channel is the alpha). The function's value is
// exact in units of 1/510 of a code:
//     REPLACE 510 a0            MODULATE 2 a0 a1        ADD 510 (a0 + a1)
//     ADD_SIGNED 510 (a0 + a1) - 65025                  SUBTRACT 510 (a0 - a1)
//     INTERPOLATE 2 (a0 a2 + a1 (255 - a2))
//     DOT3_RGB(A) 2 sum over R, G, B of (2 a0 - 255)(2 a1 - 255)
// then shifted left by the stage's scale field (log2: 0, 1, 2; 3 gives 8,
// not a GL value), rounded once to nearest with halves up, floor((n + 255)
// / 510), and clamped to 0 .. 255. DOT3_RGBA puts the dot product, scaled
// by the alpha stage's scale, in alpha too; a DOT3 code in the alpha
// stage's function gives 0. This is the arithmetic of the arm back end
// (sw_driver/renderers/arm/README.md, "Rounding"), so the two pictures agree
// bit for bit.
//
// Hardware: combinational; per channel every mode's result is computed and
// the code selects one, and the divisions by 510 are a multiply-free
// reciprocal (floor(m / 255) = (m + 1 + ((m + 1) >> 8)) >> 8 for m < 65280).
// Its Verilog twin is rtl_models/raster/texture_combiner.sv.
//
// Speed: inline, allocation-free, no data-dependent branch: the state's
// codes pick among every candidate by masks (select_code, select_if). The
// batch form (texture_combiner_batch, batch.h) takes fragments through one
// unit's state.
#pragma once

#include <algorithm>
#include <cstdint>

#include "batch.h"
#include "common/fixed_function.h"
#include "fixed_point.h"
#include "raster/command_format.h"

namespace tessera::raster {

// Everything but the colours: the unit's state.
struct TextureUnitEnv {
  TexEnv env = TexEnv::modulate;
  TexBaseFormat base_format = TexBaseFormat::rgba;
  Rgba8 env_color;
  CombineStage rgb;
  CombineStage alpha{CombineFunc::modulate,
                     {CombineSource::texture, CombineSource::previous, CombineSource::constant},
                     {CombineOperand::src_alpha, CombineOperand::src_alpha, CombineOperand::src_alpha},
                     0};
};

namespace combiner_detail {

constexpr uint32_t div255(uint32_t x) {  // round(x / 255), x <= 65025
  const uint32_t t = x + 128;
  return (t + (t >> 8)) >> 8;
}

constexpr uint32_t channel(uint32_t rgba, unsigned ch) {
  return (rgba >> (8 * ch)) & 0xff;
}

// floor((n + 255) / 510) clamped to 0 .. 255, for |n| < 2^23.
constexpr uint32_t combine_round(int32_t n) {
  const int32_t m = n + 255;
  const uint32_t h = static_cast<uint32_t>(m) >> 1;  // floor(m / 510) = floor(floor(m / 2) / 255)
  const uint32_t quotient = (h + 1 + ((h + 1) >> 8)) >> 8;
  // The clamps as selects (the quotient of a negative m is not used).
  return m < 0 ? 0u : (m >= 256 * 510 ? 255u : quotient);
}

// The colours a combiner argument may take, by CombineSource code.
struct CombineSources {
  uint32_t texture, constant, primary, previous;
};

// Argument k of `stage` for channel ch (3: alpha).
constexpr int32_t argument(const CombineStage& stage, unsigned k, unsigned ch, const CombineSources& sources) {
  const uint32_t colour = select_code<uint32_t>(code_of(stage.source[k]), 0, sources.texture, sources.constant,
                                                sources.primary, sources.previous);
  // The operand's alpha or channel, and 255 - x as x ^ 255: shift and mask
  // the same for every lane of a batch.
  const uint32_t op = code_of(stage.operand[k]);
  const uint32_t x = (colour >> ((op & 2) != 0 ? 24 : 8 * ch)) & 0xff;
  return static_cast<int32_t>(x ^ ((op & 1) != 0 ? 0xffu : 0u));
}

// The function's value in 1/510 of a code (DOT3 codes: 0, see combine_dot3).
constexpr int32_t combine_value(CombineFunc func, int32_t a0, int32_t a1, int32_t a2) {
  return select_code<int32_t>(code_of(func), 0, 510 * a0, 2 * a0 * a1, 510 * (a0 + a1), 510 * (a0 + a1) - 65025,
                              2 * (a0 * a2 + a1 * (255 - a2)), 510 * (a0 - a1));
}

}  // namespace combiner_detail

constexpr Rgba8 texture_combiner(const TextureUnitEnv& unit, Rgba8 primary, Rgba8 previous, Rgba8 texel) {
  using namespace combiner_detail;
  const uint32_t f = previous.pack(), t = texel.pack(), c = unit.env_color.pack();
  const TexBaseFormat base = unit.base_format;
  const bool no_alpha = base == TexBaseFormat::rgb || base == TexBaseFormat::luminance;
  const bool no_colour = base == TexBaseFormat::alpha;
  const uint32_t fa = f >> 24, ta = t >> 24;

  // REPLACE, MODULATE, DECAL, BLEND, ADD, per channel.
  uint32_t replace = 0, modulate = 0, decal = f & 0xff000000u, blend = 0, add = 0;
#pragma GCC unroll 3
  for (unsigned ch = 0; ch < 3; ++ch) {
    const uint32_t fc = channel(f, ch), tc = channel(t, ch), cc = channel(c, ch);
    replace |= select_if(no_colour, fc, tc) << (8 * ch);
    modulate |= select_if(no_colour, fc, div255(fc * tc)) << (8 * ch);
    decal |= div255(fc * (255 - ta) + tc * ta) << (8 * ch);
    blend |= div255(fc * (255 - tc) + cc * tc) << (8 * ch);
    add |= std::min<uint32_t>(fc + tc, 255) << (8 * ch);
  }
  const uint32_t alpha_product = div255(fa * ta) << 24;
  replace |= select_if(no_alpha, fa, ta) << 24;
  modulate |= alpha_product;
  blend |= alpha_product;
  add |= alpha_product;

  // COMBINE. Sources indexed by CombineSource code.
  const CombineSources sources{t, c, primary.pack(), f};
  const CombineStage& rgb = unit.rgb;
  const CombineStage& alpha = unit.alpha;
  uint32_t combine = 0;
  int32_t dot = 0;
#pragma GCC unroll 3
  for (unsigned ch = 0; ch < 3; ++ch) {
    const int32_t a0 = argument(rgb, 0, ch, sources), a1 = argument(rgb, 1, ch, sources);
    const int32_t a2 = argument(rgb, 2, ch, sources);
    dot += (2 * a0 - 255) * (2 * a1 - 255);
    combine |= combine_round(combine_value(rgb.func, a0, a1, a2) * (1 << rgb.scale_log2)) << (8 * ch);
  }
  dot *= 2;
  const bool dot3 = rgb.func == CombineFunc::dot3_rgb || rgb.func == CombineFunc::dot3_rgba;
  const uint32_t dot_rgb = combine_round(dot * (1 << rgb.scale_log2)) * 0x010101u;
  const uint32_t alpha_value =
      select_if(rgb.func == CombineFunc::dot3_rgba, combine_round(dot * (1 << alpha.scale_log2)),
                combine_round(combine_value(alpha.func, argument(alpha, 0, 3, sources), argument(alpha, 1, 3, sources),
                                            argument(alpha, 2, 3, sources)) *
                              (1 << alpha.scale_log2)));
  combine = select_if(dot3, dot_rgb, combine) | alpha_value << 24;

  return Rgba8::unpack(select_code<uint32_t>(code_of(unit.env), f, replace, modulate, decal, blend, add, combine));
}

// Batch form (batch.h): `count` fragments through one unit's state,
// colours as packed words (Rgba8::pack).
struct TextureCombinerKernel {
  TESSERA_BATCH_KERNEL void run(const TextureUnitEnv& unit, const uint32_t* primary, const uint32_t* previous,
                                const uint32_t* texel, unsigned count, uint32_t* out) {
    loop(unit, primary, previous, texel, count, out);
  }
  TESSERA_BATCH_KERNEL void loop(const TextureUnitEnv unit, const uint32_t* __restrict primary,
                                 const uint32_t* __restrict previous, const uint32_t* __restrict texel, unsigned count,
                                 uint32_t* __restrict out) {
    for (unsigned i = 0; i < count; ++i)
      out[i] =
          texture_combiner(unit, Rgba8::unpack(primary[i]), Rgba8::unpack(previous[i]), Rgba8::unpack(texel[i])).pack();
  }
};

void texture_combiner_batch(const TextureUnitEnv& unit, const uint32_t* primary, const uint32_t* previous,
                            const uint32_t* texel, unsigned count, uint32_t* out, BatchIsa isa = best_batch_isa());

}  // namespace tessera::raster
