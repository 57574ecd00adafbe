// Unit tests of the attribute interpolator (tlm/raster/datapath/attribute_interpolator.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raster/datapath/attribute_interpolator.h"

namespace tessera::raster {
namespace {

constexpr int64_t colour_units(double codes) {
  return static_cast<int64_t>(codes * 65536.0);
}

TEST(AttributeInterpolator, GouraudColourByHand) {
  // start 10.5 codes, +1.25 per pixel in x, -0.5 per row.
  const AttributePlane p{AttributeKind::color, colour_units(10.5), colour_units(1.25), colour_units(-0.5)};
  EXPECT_EQ(attribute_at(p, 4, 3).raw, colour_units(14.0));
  EXPECT_EQ(evaluate_attribute(p, 4, 3).output, 14u);
  EXPECT_EQ(evaluate_attribute(p, 1, 0).output, 12u);  // 11.75
  EXPECT_EQ(evaluate_attribute(p, 0, 1).output, 10u);  // 10.0
  EXPECT_EQ(evaluate_attribute(p, 0, 0).output, 11u);  // 10.5: ties go up
  EXPECT_EQ(evaluate_attribute(p, -9, 0).output, 0u);  // -0.75 clamps to 0
  EXPECT_EQ(evaluate_attribute(p, 300, 0).output, 255u);
  EXPECT_EQ(attribute_to_color(attribute_sum{colour_units(254.5) - 1}).raw, 254u);
}

TEST(AttributeInterpolator, DepthRoundsAndClamps) {
  // Depth words are 0.24 codes with 8 fraction bits.
  EXPECT_EQ(attribute_to_depth(attribute_sum{(int64_t{0xffffff} << 8)}).raw, 0xffffffu);
  EXPECT_EQ(attribute_to_depth(attribute_sum{(int64_t{0xffffff} << 8) + 127}).raw, 0xffffffu);
  EXPECT_EQ(attribute_to_depth(attribute_sum{(int64_t{0x1000000} << 8)}).raw, 0xffffffu);
  EXPECT_EQ(attribute_to_depth(attribute_sum{(int64_t{5} << 8) + 127}).raw, 5u);
  EXPECT_EQ(attribute_to_depth(attribute_sum{(int64_t{5} << 8) + 128}).raw, 6u);
  EXPECT_EQ(attribute_to_depth(attribute_sum{-1}).raw, 0u);
  // A plane from depth 0.25 to 0.75 over 256 pixels reaches 0.75 exactly.
  const int64_t quarter = int64_t{1} << 30;  // 0.25 * 2^24 codes * 2^8
  const AttributePlane p{AttributeKind::depth, quarter, (2 * quarter) / 256, 0};
  EXPECT_EQ(evaluate_attribute(p, 256, 7).output, 3u << 22);
}

TEST(AttributeInterpolator, TexcoordKeepsSignAndSaturates) {
  // -0.25 in q15.24 is -0.25 in q15.16.
  const AttributePlane p{AttributeKind::texcoord, -(int64_t{1} << 22), 0, 0};
  EXPECT_EQ(static_cast<int32_t>(evaluate_attribute(p, 0, 0).output), -(1 << 14));
  EXPECT_EQ(attribute_to_texcoord(attribute_sum{int64_t{1} << 45}).raw, q15_16::MAX_RAW);
  EXPECT_EQ(attribute_to_texcoord(attribute_sum{-(int64_t{1} << 45)}).raw, q15_16::MIN_RAW);
  // s = 2.5 across 10 pixels at 0.125 per pixel: 3.75.
  const AttributePlane q{AttributeKind::texcoord, int64_t{5} << 23, int64_t{1} << 21, 0};
  EXPECT_EQ(evaluate_attribute(q, 10, 0).output, 0x3c000u);
}

TEST(AttributeInterpolator, UndefinedKindGivesZero) {
  const AttributePlane p{static_cast<AttributeKind>(3), colour_units(100), 0, 0};
  EXPECT_EQ(evaluate_attribute(p, 0, 0).output, 0u);
}

TEST(AttributeInterpolator, ExtremesAreExact) {
  // Computed independently in double, exact below 2^53.
  const int64_t lo = -(int64_t{1} << 39), hi = (int64_t{1} << 39) - 1;
  for (int64_t s : {lo, hi, int64_t{0}})
    for (int64_t gx : {lo, hi})
      for (int64_t gy : {lo, hi})
        for (int dx : {-512, 511})
          for (int dy : {-512, 511}) {
            const double expected = double(s) + double(gx) * dx + double(gy) * dy;
            const AttributePlane p{AttributeKind::depth, s, gx, gy};
            EXPECT_EQ(double(attribute_at(p, dx, dy).raw), expected);
          }
}

TEST(AttributeInterpolator, SteppingEqualsDirectEvaluation) {
  std::mt19937_64 rng(77);
  for (int n = 0; n < 200; ++n) {
    const AttributePlane p =
        attribute_plane_from_raw(static_cast<AttributeKind>(n % 3), int64_t(rng()), int64_t(rng()), int64_t(rng()));
    const int row = static_cast<int>(rng() % 1024) - 512;
    attribute_sum v = attribute_at(p, -512, row);
    for (int dx = -512; dx < 511; ++dx) {
      v = attribute_step_x(p, v);
      ASSERT_EQ(v, attribute_at(p, dx + 1, row));
    }
    const int col = static_cast<int>(rng() % 1024) - 512;
    v = attribute_at(p, col, -512);
    for (int dy = -512; dy < 511; ++dy) {
      v = attribute_step_y(p, v);
      ASSERT_EQ(v, attribute_at(p, col, dy + 1));
    }
    const AttributeEvaluation e = evaluate_attribute(p, col, row);
    EXPECT_EQ(e.value_next_x, attribute_at(p, col + 1, row));
    EXPECT_EQ(e.value_next_y, attribute_at(p, col, row + 1));
  }
}

TEST(AttributeInterpolator, ColourConversionMatchesRealRounding) {
  std::mt19937_64 rng(5);
  for (int n = 0; n < 100000; ++n) {
    const int64_t raw = static_cast<int64_t>(rng() % (int64_t{300} << 16)) - (int64_t{20} << 16);
    const double real = double(raw) / 65536.0;
    const double want = std::clamp(std::floor(real + 0.5), 0.0, 255.0);
    ASSERT_EQ(attribute_to_color(attribute_sum{raw}).raw, static_cast<uint32_t>(want)) << raw;
  }
}

}  // namespace
}  // namespace tessera::raster
