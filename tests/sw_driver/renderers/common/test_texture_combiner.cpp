// The texture environments and the GL_COMBINE arithmetic of
// renderers/common/texturing.h (and, at the end, the unit choice of
// texture_units.h), against values worked out by hand from the
// formulas of the OpenGL ES 1.1 specification (section 3.7.12, tables 3.15,
// 3.18 and 3.19) on the 0..1 scale, times 255, rounded to nearest as the arm
// README states (halves up), clamped to [0, 255].
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "renderers/common/texture_units.h"
#include "renderers/common/texturing.h"

namespace tessera::renderers {
namespace {

using gl::CombineFunc;
using gl::CombineOperand;
using gl::CombineSource;
using gl::TexEnvMode;

uint32_t rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return r | g << 8 | b << 16 | a << 24;
}

// A unit in GL_COMBINE whose two halves read `sources` with the default
// operands (colour for RGB, alpha for alpha).
gl::TextureUnit combine_unit(CombineFunc rgb, CombineFunc alpha, CombineSource s0, CombineSource s1,
                             CombineSource s2 = CombineSource::constant) {
  gl::TextureUnit unit;
  unit.enabled = true;
  unit.env = TexEnvMode::combine;
  unit.combine_rgb.func = rgb;
  unit.combine_alpha.func = alpha;
  for (gl::CombineStage* stage : {&unit.combine_rgb, &unit.combine_alpha}) {
    stage->source[0] = s0;
    stage->source[1] = s1;
    stage->source[2] = s2;
  }
  return unit;
}

TEST(TextureEnvironment, BlendTakesTheConstantWhereTheTextureIsBright) {
  gl::TextureUnit unit;
  unit.env = TexEnvMode::blend;
  const uint8_t constant[4] = {10, 20, 30, 40};
  std::copy(constant, constant + 4, unit.env_color);
  const uint8_t texel[4] = {255, 0, 128, 128};
  // C = Cf (1 - Ct) + Cc Ct: r = 10 (Ct = 1), g = 100 (Ct = 0),
  // b = (50 * 127 + 30 * 128) / 255 = 39.96 -> 40; A = Af At = 200 * 128 / 255
  // = 100.39 -> 100.
  EXPECT_EQ(apply_texture_unit(unit, rgba(200, 100, 50, 200), 0, texel), rgba(10, 100, 40, 100));
}

TEST(TextureEnvironment, AddSaturatesColourAndModulatesAlpha) {
  gl::TextureUnit unit;
  unit.env = TexEnvMode::add;
  const uint8_t texel[4] = {100, 100, 250, 128};
  // C = min(Cf + Ct, 1): 300 -> 255, 200, 300 -> 255; A = 200 * 128 / 255 -> 100.
  EXPECT_EQ(apply_texture_unit(unit, rgba(200, 100, 50, 200), 0, texel), rgba(255, 200, 255, 100));
}

TEST(TextureEnvironment, TheHardwareModesAreUnchanged) {
  gl::TextureUnit unit;
  const uint8_t texel[4] = {128, 255, 0, 64};
  // MODULATE: 200 * 128 / 255 = 100.39 -> 100, 100, 0, 255 * 64 / 255 = 64.
  unit.env = TexEnvMode::modulate;
  EXPECT_EQ(apply_texture_unit(unit, rgba(200, 100, 50, 255), 0, texel), rgba(100, 100, 0, 64));
  unit.env = TexEnvMode::replace;
  EXPECT_EQ(apply_texture_unit(unit, rgba(200, 100, 50, 255), 0, texel), rgba(128, 255, 0, 64));
  // DECAL: C = Cf (1 - At) + Ct At = (200 * 191 + 128 * 64) / 255 = 182.0 ->
  // 182; (100 * 191 + 255 * 64) / 255 = 138.9 -> 139; 50 * 191 / 255 = 37.45
  // -> 37; A = Af.
  unit.env = TexEnvMode::decal;
  EXPECT_EQ(apply_texture_unit(unit, rgba(200, 100, 50, 255), 0, texel), rgba(182, 139, 37, 255));
}

TEST(TextureCombiner, FunctionsOfTable318) {
  const uint32_t previous = rgba(200, 100, 50, 200);
  const uint8_t texel[4] = {100, 128, 255, 60};
  struct Case {
    CombineFunc func;
    uint32_t expected;
  };
  // Arg0 = texture, Arg1 = previous.
  const Case cases[] = {
      // REPLACE: Arg0.
      {CombineFunc::replace, rgba(100, 128, 255, 60)},
      // MODULATE: 100 * 200 / 255 = 78.43 -> 78; 128 * 100 / 255 = 50.2 -> 50;
      // 255 * 50 / 255 = 50; alpha 60 * 200 / 255 = 47.06 -> 47.
      {CombineFunc::modulate, rgba(78, 50, 50, 47)},
      // ADD: 300 -> 255, 228, 305 -> 255; 260 -> 255.
      {CombineFunc::add, rgba(255, 228, 255, 255)},
      // ADD_SIGNED: Arg0 + Arg1 - 127.5: 172.5 -> 173 (halves up), 100.5 ->
      // 101, 177.5 -> 178; alpha 132.5 -> 133.
      {CombineFunc::add_signed, rgba(173, 101, 178, 133)},
      // SUBTRACT: Arg0 - Arg1: -100 -> 0, 28, 205; alpha -140 -> 0.
      {CombineFunc::subtract, rgba(0, 28, 205, 0)},
  };
  for (const Case& c : cases) {
    const gl::TextureUnit unit = combine_unit(c.func, c.func, CombineSource::texture, CombineSource::previous);
    EXPECT_EQ(apply_texture_unit(unit, previous, 0, texel), c.expected) << int(c.func);
  }
}

TEST(TextureCombiner, InterpolateWeighsByTheThirdArgument) {
  // Arg0 = texture, Arg1 = previous, Arg2 = constant with operand SRC_ALPHA
  // (the default): alpha 128 -> weight 128/255.
  gl::TextureUnit unit = combine_unit(CombineFunc::interpolate, CombineFunc::interpolate, CombineSource::texture,
                                      CombineSource::previous, CombineSource::constant);
  const uint8_t constant[4] = {0, 0, 0, 128};
  std::copy(constant, constant + 4, unit.env_color);
  const uint8_t texel[4] = {200, 255, 0, 255};
  // (a0 * 128 + a1 * 127) / 255: (200 * 128 + 100 * 127) / 255 = 150.2 -> 150;
  // (255 * 128 + 0) / 255 = 128; (0 + 255 * 127) / 255 = 127; alpha
  // (255 * 128 + 0 * 127) / 255 = 128.
  EXPECT_EQ(apply_texture_unit(unit, rgba(100, 0, 255, 0), 0, texel), rgba(150, 128, 127, 128));
}

TEST(TextureCombiner, Dot3OfTwoNormals) {
  // 4 ((192/255 - 0.5)^2 + 2 (128/255 - 0.5)^2) = 0.255946 -> 65.27 -> 65.
  const uint8_t texel[4] = {192, 128, 128, 7};
  gl::TextureUnit rgb =
      combine_unit(CombineFunc::dot3_rgb, CombineFunc::replace, CombineSource::texture, CombineSource::previous);
  EXPECT_EQ(apply_texture_unit(rgb, rgba(192, 128, 128, 99), 0, texel), rgba(65, 65, 65, 7));
  // DOT3_RGBA puts it in alpha too and ignores the alpha function.
  gl::TextureUnit rgba_unit = rgb;
  rgba_unit.combine_rgb.func = CombineFunc::dot3_rgba;
  EXPECT_EQ(apply_texture_unit(rgba_unit, rgba(192, 128, 128, 99), 0, texel), rgba(65, 65, 65, 65));
  // Each half takes its own scale: colour 2 x 65.27 = 130.54 -> 131, alpha
  // 4 x 65.27 = 261.1 -> 255.
  rgba_unit.combine_rgb.scale = 2;
  rgba_unit.combine_alpha.scale = 4;
  EXPECT_EQ(apply_texture_unit(rgba_unit, rgba(192, 128, 128, 99), 0, texel), rgba(131, 131, 131, 255));
  // Opposite normals: a negative dot product clamps to 0; equal unit
  // normals (255, 128, 128): 4 (0.25 + 2 (0.5/255)^2) > 1 clamps to 255.
  EXPECT_EQ(apply_texture_unit(rgb, rgba(0, 128, 128, 0), 0, texel) & 0xffffff, 0u);
  const uint8_t x_axis[4] = {255, 128, 128, 0};
  EXPECT_EQ(apply_texture_unit(rgb, rgba(255, 128, 128, 0), 0, x_axis) & 0xffffff, rgba(255, 255, 255, 0));
}

TEST(TextureCombiner, ScalesMultiplyBeforeRoundingAndClamp) {
  gl::TextureUnit unit =
      combine_unit(CombineFunc::modulate, CombineFunc::modulate, CombineSource::texture, CombineSource::previous);
  const uint8_t texel[4] = {200, 50, 10, 100};
  const uint32_t previous = rgba(100, 100, 100, 100);
  // 200 * 100 / 255 = 78.43, 50 * 100 / 255 = 19.61, 10 * 100 / 255 = 3.92;
  // alpha 100 * 100 / 255 = 39.22.
  unit.combine_rgb.scale = 2;    // 156.86 -> 157, 39.22 -> 39, 7.84 -> 8
  unit.combine_alpha.scale = 4;  // 156.86 -> 157
  EXPECT_EQ(apply_texture_unit(unit, previous, 0, texel), rgba(157, 39, 8, 157));
  unit.combine_rgb.scale = 4;    // 313.7 -> 255, 78.43 -> 78, 15.69 -> 16
  unit.combine_alpha.scale = 1;  // 39.22 -> 39
  EXPECT_EQ(apply_texture_unit(unit, previous, 0, texel), rgba(255, 78, 16, 39));
}

TEST(TextureCombiner, OperandsAndSources) {
  // REPLACE of Arg0 under every operand and source.
  gl::TextureUnit unit =
      combine_unit(CombineFunc::replace, CombineFunc::replace, CombineSource::texture, CombineSource::previous);
  const uint8_t constant[4] = {1, 2, 3, 4};
  std::copy(constant, constant + 4, unit.env_color);
  const uint8_t texel[4] = {10, 20, 30, 40};
  const uint32_t previous = rgba(50, 60, 70, 80), primary = rgba(90, 100, 110, 120);
  const struct {
    CombineSource source;
    CombineOperand rgb, alpha;
    uint32_t expected;
  } cases[] = {
      {CombineSource::texture, CombineOperand::src_color, CombineOperand::src_alpha, rgba(10, 20, 30, 40)},
      {CombineSource::texture, CombineOperand::one_minus_src_color, CombineOperand::one_minus_src_alpha,
       rgba(245, 235, 225, 215)},
      {CombineSource::texture, CombineOperand::src_alpha, CombineOperand::src_alpha, rgba(40, 40, 40, 40)},
      {CombineSource::texture, CombineOperand::one_minus_src_alpha, CombineOperand::src_alpha, rgba(215, 215, 215, 40)},
      {CombineSource::constant, CombineOperand::src_color, CombineOperand::src_alpha, rgba(1, 2, 3, 4)},
      {CombineSource::primary_color, CombineOperand::src_color, CombineOperand::src_alpha, primary},
      {CombineSource::previous, CombineOperand::src_color, CombineOperand::src_alpha, previous},
  };
  for (const auto& c : cases) {
    unit.combine_rgb.source[0] = unit.combine_alpha.source[0] = c.source;
    unit.combine_rgb.operand[0] = c.rgb;
    unit.combine_alpha.operand[0] = c.alpha;
    EXPECT_EQ(apply_texture_unit(unit, previous, primary, texel), c.expected);
  }
}

// COMBINE's MODULATE with scale 1 and the MODULATE environment agree for
// every pair of codes, and both are round(a b / 255) computed here in double.
TEST(TextureCombiner, ModulateMatchesTheRoundedProductExhaustively) {
  gl::TextureUnit unit =
      combine_unit(CombineFunc::modulate, CombineFunc::modulate, CombineSource::texture, CombineSource::previous);
  gl::TextureUnit env;
  env.env = TexEnvMode::modulate;
  for (uint32_t a = 0; a < 256; ++a) {
    for (uint32_t b = 0; b < 256; ++b) {
      const uint8_t texel[4] = {static_cast<uint8_t>(a), static_cast<uint8_t>(a), static_cast<uint8_t>(a),
                                static_cast<uint8_t>(a)};
      const uint32_t expected = static_cast<uint32_t>(std::floor(a * b / 255.0 + 0.5));
      const uint32_t got = apply_texture_unit(unit, rgba(b, b, b, b), 0, texel);
      ASSERT_EQ(got, rgba(expected, expected, expected, expected)) << a << " " << b;
      ASSERT_EQ(apply_texture_unit(env, rgba(b, b, b, b), 0, texel), got) << a << " " << b;
    }
  }
}

}  // namespace
}  // namespace tessera::renderers

namespace tessera::renderers {
namespace {

// The back ends with one unit and three environments (raster, ap-tile,
// ap-pixel) draw the first enabled unit and report the rest.
TEST(SingleTextureUnit, DrawsTheFirstEnabledUnitAndReportsTheRest) {
  gl::RasterState state;
  std::vector<std::string> reports;
  auto report = [&](const std::string& what) { reports.push_back(what); };
  EXPECT_EQ(single_texture_unit(state, report).index, -1);
  EXPECT_TRUE(reports.empty());

  state.unit[1].enabled = true;
  state.unit[1].env = gl::TexEnvMode::decal;
  SingleTextureUnit drawn = single_texture_unit(state, report);
  EXPECT_EQ(drawn.index, 1);
  EXPECT_EQ(drawn.env, gl::TexEnv::decal);
  EXPECT_TRUE(reports.empty());

  state.unit[0].enabled = true;
  state.unit[0].env = gl::TexEnvMode::combine;
  drawn = single_texture_unit(state, report);
  EXPECT_EQ(drawn.index, 0);
  EXPECT_EQ(drawn.env, gl::TexEnv::modulate);
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0], "the GL_COMBINE texture environment: drawn as GL_MODULATE");
  EXPECT_EQ(reports[1], "a second enabled texture unit (texture unit 1): drawn without it");
}

}  // namespace
}  // namespace tessera::renderers
