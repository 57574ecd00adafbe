// Unit tests of blending and logic op (tlm/raster/datapath/blend_logic_op.h).
#include <gtest/gtest.h>

#include <cmath>

#include "raster/datapath/blend_logic_op.h"

namespace tessera::raster {
namespace {

Rgba8 colour(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return {unorm8{r}, unorm8{g}, unorm8{b}, unorm8{a}};
}

BlendState blending(BlendFactor sf, BlendFactor df) {
  BlendState s;
  s.blend_enable = true;
  s.src_factor = sf;
  s.dst_factor = df;
  return s;
}

TEST(BlendLogicOp, MultiplyIsExactlyRoundedEverywhere) {
  for (uint32_t a = 0; a < 256; ++a) {
    for (uint32_t b = 0; b < 256; ++b) {
      // Integer round-half-up of a*b/255 (ties cannot occur).
      const uint32_t expected = (2 * a * b + 255) / 510;
      ASSERT_EQ(mul_unorm8(unorm8{a}, unorm8{b}).raw, expected) << a << "*" << b;
    }
  }
  EXPECT_EQ(mul_unorm8(unorm8{200}, unorm8{255}).raw, 200u);
  EXPECT_EQ(mul_unorm8(unorm8{128}, unorm8{128}).raw, 64u);  // 64.25
}

TEST(BlendLogicOp, OneOneSaturates) {
  const Rgba8 r =
      blend_logic_op(blending(BlendFactor::one, BlendFactor::one), colour(200, 100, 0, 255), colour(100, 100, 0, 1));
  EXPECT_EQ(r, colour(255, 200, 0, 255));
}

TEST(BlendLogicOp, ClassicAlphaBlend) {
  // SRC_ALPHA, ONE_MINUS_SRC_ALPHA with alpha 0.5 (code 128): 255*128/255 +
  // 0*127/255 = 128; 0 + 255*127/255 = 127.
  const Rgba8 r = blend_logic_op(blending(BlendFactor::src_alpha, BlendFactor::one_minus_src_alpha),
                                 colour(255, 0, 60, 128), colour(0, 255, 60, 255));
  EXPECT_EQ(r.r.raw, 128u);
  EXPECT_EQ(r.g.raw, 127u);
  EXPECT_EQ(r.b.raw, 60u);   // round(60*128/255) + round(60*127/255) = 30 + 30
  EXPECT_EQ(r.a.raw, 191u);  // 64 + 127 (round(128*128/255) = 64.25 -> 64)
}

TEST(BlendLogicOp, FactorsByHand) {
  const Rgba8 src = colour(10, 20, 30, 200);
  const Rgba8 dst = colour(40, 50, 60, 100);
  EXPECT_EQ(blend_factor_value(BlendFactor::zero, 0, src, dst).raw, 0u);
  EXPECT_EQ(blend_factor_value(BlendFactor::one, 0, src, dst).raw, 255u);
  EXPECT_EQ(blend_factor_value(BlendFactor::src_color, 1, src, dst).raw, 20u);
  EXPECT_EQ(blend_factor_value(BlendFactor::one_minus_src_color, 1, src, dst).raw, 235u);
  EXPECT_EQ(blend_factor_value(BlendFactor::src_alpha, 0, src, dst).raw, 200u);
  EXPECT_EQ(blend_factor_value(BlendFactor::one_minus_src_alpha, 0, src, dst).raw, 55u);
  EXPECT_EQ(blend_factor_value(BlendFactor::dst_alpha, 2, src, dst).raw, 100u);
  EXPECT_EQ(blend_factor_value(BlendFactor::one_minus_dst_alpha, 2, src, dst).raw, 155u);
  EXPECT_EQ(blend_factor_value(BlendFactor::dst_color, 2, src, dst).raw, 60u);
  EXPECT_EQ(blend_factor_value(BlendFactor::one_minus_dst_color, 2, src, dst).raw, 195u);
  // SRC_ALPHA_SATURATE: min(As, 1 - Ad) = min(200, 155) for RGB, 1 for A.
  EXPECT_EQ(blend_factor_value(BlendFactor::src_alpha_saturate, 0, src, dst).raw, 155u);
  EXPECT_EQ(blend_factor_value(BlendFactor::src_alpha_saturate, 3, src, dst).raw, 255u);
  EXPECT_EQ(code_of(BlendFactor::src_alpha_saturate), 10u);
  EXPECT_EQ(code_of(static_cast<BlendFactor>(15)), 15u);
}

TEST(BlendLogicOp, LogicOpsInGlOrder) {
  const unorm8 s{0xCA};
  const unorm8 d{0x5F};
  const uint32_t expected[16] = {0x00, 0x4A, 0x80, 0xCA, 0x15, 0x5F, 0x95, 0xDF,
                                 0x20, 0x6A, 0xA0, 0xEA, 0x35, 0x7F, 0xB5, 0xFF};
  for (uint16_t i = 0; i < 16; ++i) {
    const auto op = static_cast<LogicOp>(i);
    EXPECT_EQ(apply_logic_op(op, s, d).raw, expected[i]) << i;
    EXPECT_EQ(code_of(op), i);
  }
}

TEST(BlendLogicOp, LogicOpReplacesBlendingAndMaskKeepsDestination) {
  BlendState st = blending(BlendFactor::one, BlendFactor::one);
  st.logic_op_enable = true;
  st.op = LogicOp::xor_;
  const Rgba8 src = colour(0xff, 0x0f, 0x00, 0xaa);
  const Rgba8 dst = colour(0x0f, 0x0f, 0x33, 0x55);
  EXPECT_EQ(blend_logic_op(st, src, dst), colour(0xf0, 0x00, 0x33, 0xff));
  st.color_mask = COLOR_MASK_R | COLOR_MASK_A;
  EXPECT_EQ(blend_logic_op(st, src, dst), colour(0xf0, 0x0f, 0x33, 0xff));
  // Neither blending nor logic op: the source is written, through the mask.
  BlendState plain;
  plain.color_mask = COLOR_MASK_G;
  EXPECT_EQ(blend_logic_op(plain, src, dst), colour(0x0f, 0x0f, 0x33, 0x55));
  plain.color_mask = COLOR_MASK_ALL;
  EXPECT_EQ(blend_logic_op(plain, src, dst), src);
}

}  // namespace
}  // namespace tessera::raster
