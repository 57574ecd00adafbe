// Texture combiner (tlm/raster/datapath/texture_combiner.h): each
// environment, base format rule, combiner function, source, operand and
// scale against values worked out by hand from OpenGL ES 1.1 section 3.7.12
// (tables 3.15 to 3.18), the combiner words' encoding, and random vectors
// against the arm back end's texture environment (renderers/common/
// texturing.h, apply_texture_unit), so the raster and arm pictures agree.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "raster/datapath/texture_combiner.h"
#include "renderers/common/texturing.h"

namespace tessera::raster {
namespace {

constexpr Rgba8 colour(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return Rgba8::unpack(r | g << 8 | b << 16 | a << 24);
}

// The fragment of the worked examples: f (previous), t (texel), c (env
// colour), p (primary colour).
const Rgba8 F = colour(200, 100, 50, 128), T = colour(128, 255, 0, 64), C = colour(10, 20, 30, 40),
            P = colour(60, 70, 80, 90);

Rgba8 run(TexEnv env, TexBaseFormat base, Rgba8 texel = T) {
  TextureUnitEnv unit;
  unit.env = env;
  unit.base_format = base;
  unit.env_color = C;
  return texture_combiner(unit, P, F, texel);
}

TEST(TextureCombiner, EnvironmentsOnRgba) {
  // REPLACE: Ct, At. MODULATE: 200*128/255 = 100.4, 100*255/255, 0, 128*64/255 = 32.1.
  EXPECT_EQ(run(TexEnv::replace, TexBaseFormat::rgba), T);
  EXPECT_EQ(run(TexEnv::modulate, TexBaseFormat::rgba), colour(100, 100, 0, 32));
  // DECAL: Cf (1 - At) + Ct At: (200*191 + 128*64)/255 = 182.0, (100*191 + 255*64)/255 = 138.9,
  // 50*191/255 = 37.5 (37.45), A = Af.
  EXPECT_EQ(run(TexEnv::decal, TexBaseFormat::rgba), colour(182, 139, 37, 128));
  // BLEND: Cf (1 - Ct) + Cc Ct: (200*127 + 10*128)/255 = 104.6, (0 + 20*255)/255 = 20, 50; A = Af At = 32.1.
  EXPECT_EQ(run(TexEnv::blend, TexBaseFormat::rgba), colour(105, 20, 50, 32));
  // ADD: min(Cf + Ct, 1): 328 -> 255, 355 -> 255, 50; A = Af At.
  EXPECT_EQ(run(TexEnv::add, TexBaseFormat::rgba), colour(255, 255, 50, 32));
  // Codes without an entry pass the input through.
  EXPECT_EQ(run(from_code<TexEnv>(6), TexBaseFormat::rgba), F);
  EXPECT_EQ(run(from_code<TexEnv>(7), TexBaseFormat::rgba), F);
}

// Table 3.15: the rows of the formats without alpha or without colour. The
// texels are as the texture stores them (missing alpha 255, colour 0).
TEST(TextureCombiner, BaseFormatRulesOfTable315) {
  const Rgba8 rgb = colour(128, 255, 0, 255), alpha = colour(0, 0, 0, 64);
  for (TexBaseFormat base : {TexBaseFormat::rgb, TexBaseFormat::luminance}) {
    SCOPED_TRACE(name_of(base));
    EXPECT_EQ(run(TexEnv::replace, base, rgb), colour(128, 255, 0, 128));   // C = Ct, A = Af
    EXPECT_EQ(run(TexEnv::modulate, base, rgb), colour(100, 100, 0, 128));  // C = Cf Ct, A = Af
    EXPECT_EQ(run(TexEnv::decal, base, rgb), colour(128, 255, 0, 128));     // C = Ct, A = Af
    EXPECT_EQ(run(TexEnv::blend, base, rgb), colour(105, 20, 50, 128));     // A = Af
    EXPECT_EQ(run(TexEnv::add, base, rgb), colour(255, 255, 50, 128));      // A = Af
  }
  // ALPHA: C = Cf under every mode; A = At (REPLACE), Af At otherwise.
  EXPECT_EQ(run(TexEnv::replace, TexBaseFormat::alpha, alpha), colour(200, 100, 50, 64));
  EXPECT_EQ(run(TexEnv::modulate, TexBaseFormat::alpha, alpha), colour(200, 100, 50, 32));
  EXPECT_EQ(run(TexEnv::blend, TexBaseFormat::alpha, alpha), colour(200, 100, 50, 32));
  EXPECT_EQ(run(TexEnv::add, TexBaseFormat::alpha, alpha), colour(200, 100, 50, 32));
  // The same texel as an RGBA texture: the texel's own colour (REPLACE
  // and MODULATE differ), LUMINANCE_ALPHA and codes 5-7 as RGBA.
  EXPECT_EQ(run(TexEnv::replace, TexBaseFormat::rgba, alpha), alpha);
  for (uint32_t code : {4u, 5u, 6u, 7u}) {
    const TexBaseFormat base = from_code<TexBaseFormat>(code);
    EXPECT_EQ(run(TexEnv::replace, base), T) << code;
    EXPECT_EQ(run(TexEnv::modulate, base), colour(100, 100, 0, 32)) << code;
  }
}

CombineStage stage(CombineFunc func, std::array<CombineSource, 3> source, std::array<CombineOperand, 3> operand,
                   unsigned scale_log2) {
  CombineStage s;
  s.func = func;
  for (unsigned k = 0; k < 3; ++k) {
    s.source[k] = source[k];
    s.operand[k] = operand[k];
  }
  s.scale_log2 = scale_log2;
  return s;
}

Rgba8 combine(const CombineStage& rgb, const CombineStage& alpha) {
  TextureUnitEnv unit;
  unit.env = TexEnv::combine;
  unit.env_color = C;
  unit.rgb = rgb;
  unit.alpha = alpha;
  return texture_combiner(unit, P, F, T);
}

using S = CombineSource;
using O = CombineOperand;

TEST(TextureCombiner, CombineFunctionsSourcesOperandsAndScales) {
  // GL's default stages are MODULATE(texture, previous): as the environment.
  EXPECT_EQ(combine(CombineStage{}, TextureUnitEnv{}.alpha), colour(100, 100, 0, 32));

  // RGB INTERPOLATE(texture, previous, constant alpha = 40):
  // (128*40 + 200*215)/255 = 188.7, (255*40 + 100*215)/255 = 124.3, 50*215/255 = 42.2.
  // Alpha ADD_SIGNED(primary alpha 90, texture alpha 64) x 2: ((90 + 64)/255 - 1/2) 2 255 = 53.0.
  const CombineStage interpolate = stage(CombineFunc::interpolate, {S::texture, S::previous, S::constant},
                                         {O::src_color, O::src_color, O::src_alpha}, 0);
  const CombineStage add_signed = stage(CombineFunc::add_signed, {S::primary_color, S::texture, S::texture},
                                        {O::src_alpha, O::src_alpha, O::src_alpha}, 1);
  EXPECT_EQ(combine(interpolate, add_signed), colour(189, 124, 42, 53));

  // SUBTRACT(previous, texture) x 4: (200 - 128) 4 -> 255, (100 - 255) -> 0, 50 4 = 200.
  // Alpha REPLACE(1 - constant alpha) = 215; alpha SUBTRACT(primary, previous) = 90 - 128 -> 0.
  const CombineStage subtract = stage(CombineFunc::subtract, {S::previous, S::texture, S::texture},
                                      {O::src_color, O::src_color, O::src_color}, 2);
  const CombineStage replace_alpha = stage(CombineFunc::replace, {S::constant, S::texture, S::texture},
                                           {O::one_minus_src_alpha, O::src_alpha, O::src_alpha}, 0);
  EXPECT_EQ(combine(subtract, replace_alpha), colour(255, 0, 200, 215));
  const CombineStage subtract_alpha = stage(CombineFunc::subtract, {S::primary_color, S::previous, S::texture},
                                            {O::src_alpha, O::src_alpha, O::src_alpha}, 0);
  EXPECT_EQ(combine(subtract, subtract_alpha), colour(255, 0, 200, 0));

  // RGB ADD(primary, 1 - texture colour): 60 + 127, 70 + 0, 80 + 255 -> 255.
  // RGB REPLACE(previous alpha) x 2: 256 -> 255; MODULATE(primary, constant) x 4:
  // 60*10/255*4 = 9.4, 70*20/255*4 = 22.0, 80*30/255*4 = 37.6 -> 38.
  const CombineStage add = stage(CombineFunc::add, {S::primary_color, S::texture, S::texture},
                                 {O::src_color, O::one_minus_src_color, O::src_color}, 0);
  EXPECT_EQ(combine(add, replace_alpha), colour(187, 70, 255, 215));
  const CombineStage previous_alpha =
      stage(CombineFunc::replace, {S::previous, S::texture, S::texture}, {O::src_alpha, O::src_color, O::src_color}, 1);
  EXPECT_EQ(combine(previous_alpha, replace_alpha), colour(255, 255, 255, 215));
  const CombineStage modulate4 = stage(CombineFunc::modulate, {S::primary_color, S::constant, S::texture},
                                       {O::src_color, O::src_color, O::src_color}, 2);
  EXPECT_EQ(combine(modulate4, replace_alpha), colour(9, 22, 38, 215));

  // DOT3 of texture (128, 255, 0) and 1 - primary (195, 185, 175):
  // 4 ((128/255 - 1/2)(195/255 - 1/2) + (1/2)(185/255 - 1/2) - (1/2)(175/255 - 1/2)) 255 = 20.5 -> 21,
  // exactly 2 (1*135 + 255*115 - 255*95) = 10470 / 510 = 20.53. DOT3_RGBA puts
  // it in alpha with the alpha scale (x 4: 82.1), DOT3_RGB leaves alpha to its stage.
  const CombineStage dot3 = stage(CombineFunc::dot3_rgb, {S::texture, S::primary_color, S::texture},
                                  {O::src_color, O::one_minus_src_color, O::src_color}, 0);
  EXPECT_EQ(combine(dot3, replace_alpha), colour(21, 21, 21, 215));
  CombineStage dot3_rgba = dot3;
  dot3_rgba.func = CombineFunc::dot3_rgba;
  CombineStage alpha_x4 = replace_alpha;
  alpha_x4.scale_log2 = 2;
  EXPECT_EQ(combine(dot3_rgba, alpha_x4), colour(21, 21, 21, 82));
  // The opposite vectors: a negative dot product clamps to 0.
  CombineStage dot3_neg = dot3;
  dot3_neg.operand[1] = O::src_color;
  dot3_neg.source[1] = S::constant;  // (10, 20, 30): 4 (0.002 (-0.46) + 0.5 (-0.42) - 0.5 (-0.38)) < 0
  EXPECT_EQ(combine(dot3_neg, replace_alpha), colour(0, 0, 0, 215));
  // A DOT3 code in the alpha stage gives 0.
  CombineStage alpha_dot3 = replace_alpha;
  alpha_dot3.func = CombineFunc::dot3_rgb;
  EXPECT_EQ(combine(add, alpha_dot3), colour(187, 70, 255, 0));
}

// ADD_SIGNED's exact halves round up: (a0 + a1 - 127.5) with a0 + a1 odd is
// an integer, even gives x.5: 0 + 128 -> 0.5 -> 1.
TEST(TextureCombiner, RoundsHalvesUp) {
  TextureUnitEnv unit;
  unit.env = TexEnv::combine;
  unit.rgb = stage(CombineFunc::add_signed, {S::previous, S::texture, S::texture},
                   {O::src_color, O::src_color, O::src_color}, 0);
  unit.alpha = unit.rgb;
  const Rgba8 out = texture_combiner(unit, P, colour(0, 100, 255, 0), colour(128, 28, 255, 127));
  EXPECT_EQ(out, colour(1, 1, 255, 0));
}

TEST(TextureCombiner, StageWordsRoundTrip) {
  std::mt19937 rng(17);
  for (int i = 0; i < 1000; ++i) {
    const uint32_t word = rng();
    const CombineStage s = CombineStage::decode(word);
    EXPECT_EQ(CombineStage::decode(s.encode()).encode(), s.encode());
    EXPECT_EQ(s.encode() & ~0x33333337u, 0u);  // only the fields: func 0-2, sources, operands, scale
    EXPECT_EQ(code_of(s.func), word & 7);
    EXPECT_EQ(code_of(s.source[2]), (word >> 12) & 3);
    EXPECT_EQ(code_of(s.operand[1]), (word >> 20) & 3);
    EXPECT_EQ(s.scale_log2, (word >> 28) & 3);
  }
  // GL's default RGB stage: MODULATE, TEXTURE / PREVIOUS / CONSTANT, COLOR COLOR ALPHA.
  EXPECT_EQ(CombineStage{}.encode(), 1u | 0u << 4 | 3u << 8 | 1u << 12 | 0u << 16 | 0u << 20 | 2u << 24);
}

// The arm back end draws the same environments with its own code: random
// units (every code, the GL scales) and colours give the same bytes.
TEST(TextureCombiner, AgreesWithTheArmBackEnd) {
  std::mt19937_64 rng(0xc0b1);
  const auto to_arm = [](const CombineStage& s) {
    gl::CombineStage g;
    g.func = s.func;
    for (unsigned k = 0; k < 3; ++k) {
      g.source[k] = s.source[k];
      g.operand[k] = s.operand[k];
    }
    g.scale = static_cast<uint8_t>(1u << s.scale_log2);
    return g;
  };
  uint64_t checked = 0;
  for (int i = 0; i < 300000; ++i) {
    const uint64_t a = rng(), b = rng(), d = rng();
    TextureUnitEnv unit;
    unit.env = from_code<TexEnv>(static_cast<uint32_t>(d % 6));
    unit.base_format = from_code<TexBaseFormat>(static_cast<uint32_t>((d >> 3) % 5));
    unit.env_color = Rgba8::unpack(static_cast<uint32_t>(b >> 32));
    unit.rgb = CombineStage::decode(static_cast<uint32_t>(d >> 8));
    unit.alpha = CombineStage::decode(static_cast<uint32_t>(d >> 32));
    unit.rgb.scale_log2 = std::min(unit.rgb.scale_log2, 2u);
    unit.alpha.scale_log2 = std::min(unit.alpha.scale_log2, 2u);
    if (unit.alpha.func == CombineFunc::dot3_rgb || unit.alpha.func == CombineFunc::dot3_rgba)
      unit.alpha.func = CombineFunc::interpolate;  // not a GL alpha function
    const Rgba8 primary = Rgba8::unpack(static_cast<uint32_t>(a));
    const Rgba8 previous = Rgba8::unpack(static_cast<uint32_t>(a >> 32));
    const Rgba8 texel = Rgba8::unpack(static_cast<uint32_t>(b));

    gl::TextureUnit arm;
    arm.env = unit.env;
    arm.tex.has_color = unit.base_format != TexBaseFormat::alpha;
    arm.tex.has_alpha = unit.base_format != TexBaseFormat::rgb && unit.base_format != TexBaseFormat::luminance;
    EXPECT_EQ(gl::tex_base_format(arm.tex) == unit.base_format,
              unit.base_format != TexBaseFormat::luminance && unit.base_format != TexBaseFormat::luminance_alpha);
    const uint32_t ec = unit.env_color.pack();
    for (unsigned ch = 0; ch < 4; ++ch) arm.env_color[ch] = static_cast<uint8_t>(ec >> (8 * ch));
    arm.combine_rgb = to_arm(unit.rgb);
    arm.combine_alpha = to_arm(unit.alpha);
    const uint32_t t = texel.pack();
    const uint8_t texel_bytes[4] = {static_cast<uint8_t>(t), static_cast<uint8_t>(t >> 8),
                                    static_cast<uint8_t>(t >> 16), static_cast<uint8_t>(t >> 24)};
    const uint32_t want = renderers::apply_texture_unit(arm, previous.pack(), primary.pack(), texel_bytes);
    const Rgba8 got = texture_combiner(unit, primary, previous, texel);
    ASSERT_EQ(got.pack(), want) << std::hex << "env " << code_of(unit.env) << " base " << code_of(unit.base_format)
                                << " rgb " << unit.rgb.encode() << " alpha " << unit.alpha.encode() << " p "
                                << primary.pack() << " f " << previous.pack() << " t " << t << " c " << ec;
    ++checked;
  }
  EXPECT_EQ(checked, 300000u);
}

}  // namespace
}  // namespace tessera::raster
