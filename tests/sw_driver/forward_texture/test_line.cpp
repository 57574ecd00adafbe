// One line by Eq. 6 in fixed point: the border division, the filter tables,
// hand-computed lines, and agreement with Eq. 3 in double on random lines.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <vector>

#include "forward_texture/eq3_reference.h"
#include "forward_texture/filter.h"
#include "forward_texture/resample_line.h"
#include "forward_texture_test_support.h"

namespace tessera::forward_texture {
namespace {

using testing::eq6_error_bound;
using testing::to_fixed;
namespace reference = tessera::test::forward_texture;

constexpr q12_20 XY_ONE = 1 << 20;
constexpr q2_30 W_ONE = 1 << 30;

// Resamples unorm8 `texels` under x = (numerator + t step) / (denominator +
// t denominator_step); the pixels in q8_8.
std::vector<q8_8> resample(const std::vector<int>& texels, const LineMapping& mapping, const FilterTable& table,
                           int pixel_count) {
  std::vector<q8_8> in(texels.size());
  for (std::size_t t = 0; t < texels.size(); ++t) {
    in[t] = texels[t] << 8;
  }
  std::vector<q16_16> borders(texels.size() + 1);
  const std::string error = step_borders(mapping, static_cast<int>(texels.size()), "line", borders.data());
  EXPECT_EQ(error, "");
  std::vector<q8_8> out(static_cast<std::size_t>(pixel_count), -1);
  resample_line({in.data(), static_cast<int>(in.size()), 1}, borders.data(), table, {out.data(), pixel_count, 1});
  return out;
}

TEST(BorderDivision, QuotientsTruncateTowardZero) {
  q16_16 border = 0;
  ASSERT_TRUE(divide_border(3 * XY_ONE, 2 * (W_ONE / 2), border));  // 3 / 1
  EXPECT_EQ(border, 3 << 16);
  ASSERT_TRUE(divide_border(3 * XY_ONE, W_ONE / 2, border));  // 3 / 0.5
  EXPECT_EQ(border, 6 << 16);
  ASSERT_TRUE(divide_border(XY_ONE, 3 * (W_ONE / 4), border));  // 1 / 0.75 = 1.3333..
  EXPECT_EQ(border, 87381);                                     // floor(65536 * 4 / 3)
  ASSERT_TRUE(divide_border(-XY_ONE, 3 * (W_ONE / 4), border));
  EXPECT_EQ(border, -87381);
  ASSERT_TRUE(divide_border(2047 * XY_ONE, W_ONE / 16, border));  // 2047 * 16 = 32752
  EXPECT_EQ(border, 32752 << 16);
}

TEST(BorderDivision, OverflowAndBadDenominatorsAreRefused) {
  q16_16 border = 0;
  EXPECT_FALSE(divide_border(2047 * XY_ONE, W_ONE / 64, border));  // 131008 pixels
  EXPECT_FALSE(divide_border(XY_ONE, 0, border));
  EXPECT_FALSE(divide_border(XY_ONE, -W_ONE, border));
}

TEST(FilterTable, BoxAndTentValuesByHand) {
  const FilterTable box1 = make_filter_table(FilterKind::box, 1);
  EXPECT_EQ(box1.at(0, 0), 0);
  EXPECT_EQ(box1.at(128, 0), 16384);  // H(0) = 1/2
  EXPECT_EQ(box1.at(64, 0), 8192);
  const FilterTable box2 = make_filter_table(FilterKind::box, 2);
  // Row phase: H(phase + 1 - 1 - j) for a support of [-1, 1): H(z) = (z + 1) / 2.
  EXPECT_EQ(box2.at(0, 0), 16384);   // H(0)
  EXPECT_EQ(box2.at(0, 1), 0);       // H(-1)
  EXPECT_EQ(box2.at(128, 1), 8192);  // H(-1/2)
  const FilterTable tent2 = make_filter_table(FilterKind::tent, 2);
  EXPECT_EQ(tent2.at(128, 0), 28672);  // H(1/2) = 7/8
  EXPECT_EQ(tent2.at(128, 1), 4096);   // H(-1/2) = 1/8
  EXPECT_EQ(tent2.at(0, 0), 16384);    // H(0) = 1/2
  const FilterTable tent3 = make_filter_table(FilterKind::tent, 3);
  // H(phase + 1/2 - j); phase 0, j = 0: H(1/2) with support [-3/2, 3/2]:
  // w = 2/3, 1 - 2 (1/3)^2 = 7/9 = 25486.2 -> 25486.
  EXPECT_EQ(tent3.at(0, 0), 25486);
}

TEST(FilterTable, EveryRowIsMonotoneAndWithinZeroAndOne) {
  for (const FilterKind kind : {FilterKind::box, FilterKind::tent}) {
    for (int width = 1; width <= MAX_FILTER_WIDTH; ++width) {
      const FilterTable table = make_filter_table(kind, width);
      ASSERT_EQ(table.values.size(), static_cast<std::size_t>(PHASES) * width);
      for (int phase = 0; phase < PHASES; ++phase) {
        for (int j = 0; j + 1 < width; ++j) {
          EXPECT_GE(table.at(phase, j), table.at(phase, j + 1)) << filter_name(kind) << width;
        }
        EXPECT_LE(table.at(phase, 0), UQ1_15_ONE);
      }
    }
  }
}

TEST(ResampleLine, IdentityWithTheBoxCopies) {
  const std::vector<int> texels = {0, 255, 17, 200, 3, 128, 99, 1};
  const LineMapping identity{0, XY_ONE, W_ONE, 0};
  const std::vector<q8_8> out = resample(texels, identity, make_filter_table(FilterKind::box, 1), 10);
  for (std::size_t p = 0; p < texels.size(); ++p) {
    EXPECT_EQ(out[p], texels[p] << 8) << p;
  }
  EXPECT_EQ(out[8], 0);
  EXPECT_EQ(out[9], 0);
}

TEST(ResampleLine, HalvingWithTheBoxAveragesPairs) {
  const std::vector<int> texels = {10, 20, 255, 0, 7, 8, 100, 101};
  const LineMapping half{0, XY_ONE / 2, W_ONE, 0};
  const std::vector<q8_8> out = resample(texels, half, make_filter_table(FilterKind::box, 1), 5);
  EXPECT_EQ(out[0], 15 << 8);
  EXPECT_EQ(out[1], (255 << 8) / 2);  // 127.5
  EXPECT_EQ(out[2], (15 << 8) / 2);   // 7.5
  EXPECT_EQ(out[3], (201 << 8) / 2);  // 100.5
  EXPECT_EQ(out[4], 0);
}

TEST(ResampleLine, IdentityWithTheTentBlursOneEighthEachSide) {
  // Borders at the pixels' edges; the tent of width 2 gives a pixel 3/4 of
  // its own texel and 1/8 of each neighbour.
  const std::vector<int> texels = {0, 0, 64, 0, 0};
  const LineMapping identity{0, XY_ONE, W_ONE, 0};
  const std::vector<q8_8> out = resample(texels, identity, make_filter_table(FilterKind::tent, 2), 5);
  EXPECT_EQ(out[1], 8 << 8);
  EXPECT_EQ(out[2], 48 << 8);
  EXPECT_EQ(out[3], 8 << 8);
  EXPECT_EQ(out[0], 0);
}

TEST(ResampleLine, AConstantLineStaysConstantInside) {
  const std::vector<int> texels(40, 77);
  // x = (0.37 u + 1.25) / (1 + u / 256): from 1.25 to about 12.
  const LineMapping mapping{to_fixed(1.25, 20), to_fixed(0.37, 20), W_ONE, W_ONE / 256};
  for (const FilterKind kind : {FilterKind::box, FilterKind::tent}) {
    for (int width = 1; width <= 4; ++width) {
      const std::vector<q8_8> out = resample(texels, mapping, make_filter_table(kind, width), 16);
      // Pixels whose whole support lies inside [1.25, 11.9]: 1 + F/2 .. 11 - F/2.
      for (int p = 2 + width / 2; p + 1 + width / 2 <= 11; ++p) {
        EXPECT_NEAR(out[static_cast<std::size_t>(p)], 77 << 8, 2) << filter_name(kind) << width << " pixel " << p;
      }
    }
  }
}

TEST(ResampleLine, MirroredLineIsTheReversedLine) {
  const std::vector<int> texels = {5, 50, 250, 60, 90, 1};
  const std::vector<int> reversed(texels.rbegin(), texels.rend());
  // x = 9 - 0.8 u (decreasing) against x = 4.2 + 0.8 u on the reversed texels.
  const LineMapping mirrored{to_fixed(9.0, 20), to_fixed(-0.8, 20), W_ONE, 0};
  const LineMapping forward{to_fixed(4.2, 20), to_fixed(0.8, 20), W_ONE, 0};
  const FilterTable tent = make_filter_table(FilterKind::tent, 2);
  EXPECT_EQ(resample(texels, mirrored, tent, 12), resample(reversed, forward, tent, 12));
}

TEST(ResampleLine, Eq6InFixedPointAgreesWithEq3WithinTheBound) {
  std::mt19937 random(20021);
  std::uniform_int_distribution<int> texel_value(0, 255);
  std::uniform_int_distribution<int> texel_count(4, 40);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int lines = 0;
  double worst_ratio = 0.0;
  for (int attempt = 0; attempt < 400; ++attempt) {
    const int n = texel_count(random);
    std::vector<int> texels(static_cast<std::size_t>(n));
    for (int& texel : texels) {
      texel = texel_value(random);
    }
    const double scale = (0.15 + 0.8 * unit(random)) * (unit(random) < 0.5 ? -1.0 : 1.0);
    const double denominator = 0.6 + 0.8 * unit(random);
    const double perspective = (unit(random) - 0.5) * 0.4 / n;
    const double start = scale > 0 ? 1.0 + 4 * unit(random) : 40.0 - 4 * unit(random);
    const LineMapping mapping{to_fixed(start * denominator, 20), to_fixed(scale, 20), to_fixed(denominator, 30),
                              to_fixed(perspective, 30)};
    std::vector<q16_16> fixed_borders(static_cast<std::size_t>(n) + 1);
    if (!step_borders(mapping, n, "line", fixed_borders.data()).empty()) {
      continue;  // magnification at this draw
    }
    std::vector<double> borders(static_cast<std::size_t>(n) + 1);
    for (int t = 0; t <= n; ++t) {
      borders[static_cast<std::size_t>(t)] =
          (mapping.numerator / 1048576.0 + t * (mapping.numerator_step / 1048576.0)) /
          (mapping.denominator / 1073741824.0 + t * (mapping.denominator_step / 1073741824.0));
    }
    const std::vector<double> exact_texels(texels.begin(), texels.end());
    const FilterKind kind = attempt % 2 == 0 ? FilterKind::box : FilterKind::tent;
    const int width = 1 + attempt % MAX_FILTER_WIDTH;
    const FilterTable table = make_filter_table(kind, width);
    const int pixel_count = 48;
    const std::vector<q8_8> fixed = resample(texels, mapping, table, pixel_count);
    const std::vector<double> exact = reference::resample_line_eq3(exact_texels, borders, kind, width, pixel_count);
    const std::vector<double> bound = eq6_error_bound(exact_texels, borders, kind, width, pixel_count, 0.0);
    for (int p = 0; p < pixel_count; ++p) {
      const double difference =
          std::abs(fixed[static_cast<std::size_t>(p)] / 256.0 - exact[static_cast<std::size_t>(p)]);
      ASSERT_LE(difference, bound[static_cast<std::size_t>(p)])
          << "attempt " << attempt << " pixel " << p << " " << filter_name(kind) << " F = " << width;
      if (bound[static_cast<std::size_t>(p)] > 0) {
        worst_ratio = std::max(worst_ratio, difference / bound[static_cast<std::size_t>(p)]);
      }
    }
    ++lines;
  }
  EXPECT_GE(lines, 300);
  // The bound is not vacuous: some pixel uses a fair part of it.
  EXPECT_GT(worst_ratio, 0.05);
}

TEST(Driver, HasNoFloatingPoint) {
  // The host has no FPU and the double reference belongs to the testbench.
  const char* source = std::getenv("TESSERA_SOURCE_DIR");
  ASSERT_NE(source, nullptr) << "run through ctest, which sets TESSERA_SOURCE_DIR";
  const std::regex floating(R"(\b(double|float|long double)\b)");
  for (const char* name : {"fixed_point.h", "fixed_point.cpp", "filter.h", "filter.cpp", "matrix.h", "matrix.cpp",
                           "resample_line.h", "resample_line.cpp", "warp.h", "warp.cpp"}) {
    std::ifstream file(std::string(source) + "/sw_driver/forward_texture/" + name);
    ASSERT_TRUE(file) << name;
    std::stringstream text;
    text << file.rdbuf();
    EXPECT_FALSE(std::regex_search(text.str(), floating)) << name;
  }
}

}  // namespace
}  // namespace tessera::forward_texture
