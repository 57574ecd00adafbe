// The two-pass warp: hand-computed images, the column pass's borders against
// Eq. 4, the pass-order rule, and the whole warp in fixed point against the
// two passes of Eq. 3 in double on random matrices and textures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "forward_texture/eq3_reference.h"
#include "forward_texture/resample_line.h"
#include "forward_texture/warp.h"
#include "forward_texture_test_support.h"

namespace tessera::forward_texture {
namespace {

using testing::eq6_error_bound;
using testing::fixed_matrix;
namespace reference = tessera::test::forward_texture;

Image random_texture(std::mt19937& random, int width, int height) {
  std::uniform_int_distribution<int> value(0, 255);
  Image texture{width, height, std::vector<uint8_t>(static_cast<std::size_t>(width) * height)};
  for (uint8_t& texel : texture.texels) {
    texel = static_cast<uint8_t>(value(random));
  }
  return texture;
}

// Per output pixel, how far the fixed-point warp (rounded to unorm8) may be
// from the double one: the row pass's bound per intermediate pixel, carried
// into the column pass as its input error (the largest in the column), plus
// the final rounding to unorm8.
std::vector<double> rows_first_bound(const std::vector<double>& texels, int width, int height,
                                     const reference::Matrix& m, FilterKind kind, int filter_width, int output_width,
                                     int output_height) {
  std::vector<double> intermediate(static_cast<std::size_t>(output_width) * height);
  std::vector<double> intermediate_bound(intermediate.size());
  for (int row = 0; row < height; ++row) {
    const std::vector<double> line(texels.begin() + row * width, texels.begin() + (row + 1) * width);
    const std::vector<double> borders = reference::row_borders(m, row, width);
    const std::vector<double> values = reference::resample_line_eq3(line, borders, kind, filter_width, output_width);
    const std::vector<double> bound = eq6_error_bound(line, borders, kind, filter_width, output_width, 0.0);
    std::copy(values.begin(), values.end(), intermediate.begin() + row * output_width);
    std::copy(bound.begin(), bound.end(), intermediate_bound.begin() + row * output_width);
  }
  std::vector<double> output_bound(static_cast<std::size_t>(output_width) * output_height, 0.5);
  for (int column = 0; column < output_width; ++column) {
    std::vector<double> line(static_cast<std::size_t>(height));
    double input_error = 0.0;
    for (int row = 0; row < height; ++row) {
      line[static_cast<std::size_t>(row)] = intermediate[static_cast<std::size_t>(row) * output_width + column];
      input_error = std::max(input_error, intermediate_bound[static_cast<std::size_t>(row) * output_width + column]);
    }
    const std::vector<double> borders = reference::column_borders(m, column, height);
    if (borders.empty()) {
      continue;
    }
    const std::vector<double> bound = eq6_error_bound(line, borders, kind, filter_width, output_height, input_error);
    for (int y = 0; y < output_height; ++y) {
      output_bound[static_cast<std::size_t>(y) * output_width + column] += bound[static_cast<std::size_t>(y)];
    }
  }
  return output_bound;
}

std::vector<double> warp_bound(const Image& texture, const reference::Matrix& m, FilterKind kind, int filter_width,
                               int output_width, int output_height, PassOrder order) {
  std::vector<double> texels(texture.texels.begin(), texture.texels.end());
  if (order == PassOrder::rows_first) {
    return rows_first_bound(texels, texture.width, texture.height, m, kind, filter_width, output_width, output_height);
  }
  std::vector<double> transposed(texels.size());
  for (int y = 0; y < texture.height; ++y) {
    for (int x = 0; x < texture.width; ++x) {
      transposed[static_cast<std::size_t>(x) * texture.height + y] =
          texels[static_cast<std::size_t>(y) * texture.width + x];
    }
  }
  const reference::Matrix swapped{m.b, m.a, m.c, m.e, m.d, m.f, m.h, m.g, m.i};
  return rows_first_bound(transposed, texture.height, texture.width, swapped, kind, filter_width, output_width,
                          output_height);
}

// A plane seen at an angle: texture centre to (cx, cy), rotated by `angle`,
// scaled by `scale` (x) and `scale * aspect` (y), with perspective (g, h)
// per texel about the texture's centre.
PerspectiveMatrix pose(int width, int height, double angle, double scale, double aspect, double g, double h, double cx,
                       double cy) {
  const double cosine = std::cos(angle);
  const double sine = std::sin(angle);
  const double a = scale * cosine;
  const double b = -scale * aspect * sine;
  const double d = scale * sine;
  const double e = scale * aspect * cosine;
  const double uc = width / 2.0;
  const double vc = height / 2.0;
  const double i = 1.0 - g * uc - h * vc;  // w = 1 at the centre
  // x w = a (u - uc) + b (v - vc) + cx w
  return fixed_matrix(a + cx * g, b + cx * h, -a * uc - b * vc + cx * i, d + cy * g, e + cy * h,
                      -d * uc - e * vc + cy * i, g, h, i);
}

TEST(Warp, IdentityWithTheBoxCopies) {
  std::mt19937 random(1);
  const Image texture = random_texture(random, 12, 9);
  const PerspectiveMatrix identity = fixed_matrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  const WarpResult result = warp_texture(texture, identity, make_filter_table(FilterKind::box, 1), 12, 9);
  ASSERT_EQ(result.error, "");
  EXPECT_EQ(result.image.texels, texture.texels);
  EXPECT_EQ(result.pass_order.order, PassOrder::rows_first);  // a tie
}

TEST(Warp, HalvingBothWaysWithTheBoxAveragesTwoByTwo) {
  std::mt19937 random(2);
  const Image texture = random_texture(random, 8, 6);
  const PerspectiveMatrix half = fixed_matrix(0.5, 0, 0, 0, 0.5, 0, 0, 0, 1);
  const WarpResult result = warp_texture(texture, half, make_filter_table(FilterKind::box, 1), 5, 4);
  ASSERT_EQ(result.error, "");
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) {
      int expected = 0;
      if (x < 4 && y < 3) {
        const int sum = texture.at(2 * x, 2 * y) + texture.at(2 * x + 1, 2 * y) + texture.at(2 * x, 2 * y + 1) +
                        texture.at(2 * x + 1, 2 * y + 1);
        // The row pass keeps the pair's mean in q8_8 (a half at most is
        // exact), the column pass averages two of those, the output rounds
        // half up: floor((sum + 2) / 4) with the halves of q8_8 kept.
        expected = (sum * 64 + 128) >> 8;
      }
      EXPECT_EQ(result.image.at(x, y), expected) << x << ", " << y;
    }
  }
}

TEST(Warp, AConstantTextureStaysConstantInside) {
  const Image texture{24, 24, std::vector<uint8_t>(24 * 24, 201)};
  const PerspectiveMatrix m = pose(24, 24, 0.4, 0.6, 0.8, 0.004, -0.006, 16, 16);
  for (const FilterKind kind : {FilterKind::box, FilterKind::tent}) {
    const WarpResult result = warp_texture(texture, m, make_filter_table(kind, 2), 32, 32);
    ASSERT_EQ(result.error, "");
    // The quad (about 14 x 11 pixels, turned by 23 degrees) covers the
    // filter's support around these pixels at its centre.
    for (int y = 14; y < 18; ++y) {
      for (int x = 14; x < 18; ++x) {
        EXPECT_NEAR(result.image.at(x, y), 201, 1) << filter_name(kind) << " " << x << ", " << y;
      }
    }
    EXPECT_EQ(result.image.at(0, 0), 0);
  }
}

TEST(PassOrder, AQuarterTurnMapsColumnsFirstAndIsATranspose) {
  // x = v + 2, y = u + 3: every texture row lands on one column.
  std::mt19937 random(3);
  const Image texture = random_texture(random, 7, 5);
  const PerspectiveMatrix quarter = fixed_matrix(0, 1, 2, 1, 0, 3, 0, 0, 1);
  PassOrderChoice choice;
  ASSERT_EQ(choose_pass_order(quarter, 7, 5, choice), "");
  EXPECT_EQ(choice.rows_first_scale, 0);
  EXPECT_EQ(choice.columns_first_scale, Q16_16_ONE);
  EXPECT_EQ(choice.order, PassOrder::columns_first);
  const FilterTable box = make_filter_table(FilterKind::box, 1);
  const WarpResult result = warp_texture(texture, quarter, box, 9, 12);
  ASSERT_EQ(result.error, "");
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 9; ++x) {
      const int u = y - 3;
      const int v = x - 2;
      const int expected = (u >= 0 && u < 7 && v >= 0 && v < 5) ? texture.at(u, v) : 0;
      EXPECT_EQ(result.image.at(x, y), expected) << x << ", " << y;
    }
  }
  // The reason: rows first, the intermediate image holds one pixel per
  // row and the column pass cannot spread it again.
  const WarpResult rows = warp_texture_in_order(texture, quarter, box, 9, 12, PassOrder::rows_first);
  EXPECT_NE(rows.error.find("collapses a row"), std::string::npos) << rows.error;
}

TEST(PassOrder, TheFirstPassThatCompressesLessIsChosen) {
  // Rotated by 70 degrees: a row spans 0.6 cos 70 = 0.21 pixels per texel,
  // a column 0.6 sin 70 = 0.56.
  const PerspectiveMatrix steep = pose(16, 16, 70 * M_PI / 180, 0.6, 1.0, 0, 0, 16, 16);
  PassOrderChoice choice;
  ASSERT_EQ(choose_pass_order(steep, 16, 16, choice), "");
  EXPECT_NEAR(choice.rows_first_scale / 65536.0, 0.6 * std::cos(70 * M_PI / 180), 1e-3);
  EXPECT_NEAR(choice.columns_first_scale / 65536.0, 0.6 * std::sin(70 * M_PI / 180), 1e-3);
  EXPECT_EQ(choice.order, PassOrder::columns_first);
  const PerspectiveMatrix shallow = pose(16, 16, 20 * M_PI / 180, 0.6, 1.0, 0, 0, 16, 16);
  ASSERT_EQ(choose_pass_order(shallow, 16, 16, choice), "");
  EXPECT_EQ(choice.order, PassOrder::rows_first);
  // The reason: rows first, the row pass squeezes a row into 0.21 pixels
  // per texel, so the column pass has to stretch the intermediate columns
  // back out, which is magnification.
  Image texture{16, 16, std::vector<uint8_t>(256, 100)};
  const FilterTable box = make_filter_table(FilterKind::box, 1);
  EXPECT_EQ(warp_texture_in_order(texture, steep, box, 32, 32, PassOrder::columns_first).error, "");
  const std::string error = warp_texture_in_order(texture, steep, box, 32, 32, PassOrder::rows_first).error;
  EXPECT_NE(error.find("column pass"), std::string::npos) << error;
  EXPECT_NE(error.find("magnification"), std::string::npos) << error;
}

TEST(ColumnPass, BordersFollowEq4) {
  std::mt19937 random(44);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int attempt = 0; attempt < 200; ++attempt) {
    const int size = 8 + attempt % 25;
    const PerspectiveMatrix m =
        pose(size, size, unit(random) * 6.28, 0.3 + 0.5 * unit(random), 0.6 + 0.8 * unit(random),
             (unit(random) - 0.5) * 0.5 / size, (unit(random) - 0.5) * 0.5 / size, 16, 16);
    ColumnPassSetup setup;
    ASSERT_EQ(column_pass_setup(m, setup), "");
    const reference::Matrix exact = reference::to_double(m);
    for (int column = 4; column < 28; ++column) {
      LineMapping line;
      if (!column_pass_line(setup, column, size, line).empty()) {
        continue;
      }
      std::vector<q16_16> borders(static_cast<std::size_t>(size) + 1);
      if (!step_borders(line, size, "column", borders.data()).empty()) {
        continue;
      }
      const std::vector<double> expected = reference::column_borders(exact, column, size);
      for (int t = 0; t <= size; ++t) {
        worst = std::max(
            worst, std::abs(borders[static_cast<std::size_t>(t)] / 65536.0 - expected[static_cast<std::size_t>(t)]));
      }
    }
  }
  EXPECT_LE(worst, 1.0 / 1024);
  std::cout << "largest column-pass border error: " << worst << " pixel\n";
}

TEST(Warp, Eq6InFixedPointAgreesWithEq3WithinTheBound) {
  std::mt19937 random(2002);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int warps = 0;
  int columns_first = 0;
  double worst_ratio = 0.0;
  for (int attempt = 0; attempt < 60; ++attempt) {
    const int width = 8 + static_cast<int>(unit(random) * 17);
    const int height = 8 + static_cast<int>(unit(random) * 17);
    const Image texture = random_texture(random, width, height);
    const PerspectiveMatrix m =
        pose(width, height, unit(random) * 6.28, 0.35 + 0.45 * unit(random), 0.6 + 0.8 * unit(random),
             (unit(random) - 0.5) * 0.5 / width, (unit(random) - 0.5) * 0.5 / height, 16, 16);
    const FilterKind kind = attempt % 2 == 0 ? FilterKind::box : FilterKind::tent;
    const int filter_width = 1 + attempt % 4;
    const WarpResult result = warp_texture(texture, m, make_filter_table(kind, filter_width), 32, 32);
    if (result.error.find("magnification") != std::string::npos) {
      continue;
    }
    ASSERT_EQ(result.error, "") << "attempt " << attempt;
    const reference::Matrix exact = reference::to_double(m);
    const std::vector<double> expected =
        reference::warp_eq3(texture, exact, kind, filter_width, 32, 32, result.pass_order.order);
    const std::vector<double> bound = warp_bound(texture, exact, kind, filter_width, 32, 32, result.pass_order.order);
    for (std::size_t k = 0; k < expected.size(); ++k) {
      const double difference = std::abs(result.image.texels[k] - expected[k]);
      worst_ratio = std::max(worst_ratio, difference / bound[k]);
      ASSERT_LE(difference, bound[k]) << "attempt " << attempt << " pixel " << k % 32 << ", " << k / 32 << " "
                                      << filter_name(kind) << " F = " << filter_width << " "
                                      << pass_order_name(result.pass_order.order);
    }
    ++warps;
    columns_first += result.pass_order.order == PassOrder::columns_first ? 1 : 0;
  }
  EXPECT_GE(warps, 40);
  EXPECT_GE(columns_first, 10);
  // The bound is not vacuous: some pixel uses a fair part of it.
  EXPECT_GT(worst_ratio, 0.1);
  std::cout << warps << " warps, " << columns_first << " columns first; the largest error is " << worst_ratio
            << " of its bound\n";
}

}  // namespace
}  // namespace tessera::forward_texture
