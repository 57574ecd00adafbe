// Every bad input of the forward texture mapper is refused with a message
// naming the bad value (sw_driver/forward_texture/README.md, "Bad input").
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "forward_texture/warp.h"
#include "forward_texture_test_support.h"

namespace tessera::forward_texture {
namespace {

using testing::fixed_matrix;

const Image TEXTURE{16, 8, std::vector<uint8_t>(16 * 8, 90)};
const PerspectiveMatrix HALF = fixed_matrix(0.5, 0, 1, 0, 0.5, 1, 0, 0, 1);

std::string warp_error(const Image& texture, const PerspectiveMatrix& m, const FilterTable& table, int width = 32,
                       int height = 32) {
  const WarpResult result = warp_texture(texture, m, table, width, height);
  EXPECT_TRUE(result.image.texels.empty());
  return result.error;
}

const FilterTable& box() {
  static const FilterTable table = make_filter_table(FilterKind::box, 1);
  return table;
}

TEST(BadInput, MagnificationWithoutTheUpscaleNamesTheTexelWidth) {
  const PerspectiveMatrix twice = fixed_matrix(2, 0, 0, 0, 2, 0, 0, 0, 1);
  EXPECT_EQ(warp_error(TEXTURE, twice, box()),
            "row pass, row 0: texel 0 spans 2.0000 pixels, more than 1: magnification is not supported; upscale the "
            "texture first");
  // Magnified along y only: the column pass refuses it.
  const PerspectiveMatrix tall = fixed_matrix(0.5, 0, 0, 0, 1.25, 0, 0, 0, 1);
  EXPECT_EQ(warp_error(TEXTURE, tall, box()),
            "column pass, column 0: texel 0 spans 1.2500 pixels, more than 1: magnification is not supported; upscale "
            "the texture first");
}

TEST(BadInput, AFilterWidthBeyondTheTableNamesIt) {
  EXPECT_EQ(warp_error(TEXTURE, HALF, make_filter_table(FilterKind::tent, 9)),
            "filter width F = 9 is out of range: the filter table holds widths 1 .. 8");
  EXPECT_EQ(warp_error(TEXTURE, HALF, make_filter_table(FilterKind::box, 0)),
            "filter width F = 0 is out of range: the filter table holds widths 1 .. 8");
  EXPECT_EQ(filter_width_error(MAX_FILTER_WIDTH), "");
  FilterTable truncated = make_filter_table(FilterKind::box, 2);
  truncated.values.resize(10);
  EXPECT_EQ(warp_error(TEXTURE, HALF, truncated),
            "the filter table of width 2 holds 10 values, not 256 rows of that many");
}

TEST(BadInput, ASingularMatrixNamesItsDeterminant) {
  // y = 2 x: the plane seen edge-on.
  const PerspectiveMatrix edge_on = fixed_matrix(0.5, 0.25, 1, 1, 0.5, 2, 0, 0, 1);
  EXPECT_EQ(warp_error(TEXTURE, edge_on, box()),
            "singular matrix: determinant 0.0000 (its magnitude must be at least 2^-20)");
  const PerspectiveMatrix zero{};
  EXPECT_EQ(warp_error(TEXTURE, zero, box()),
            "singular matrix: determinant 0.0000 (its magnitude must be at least 2^-20)");
}

TEST(BadInput, ADenominatorNotPositiveNamesTheCorner) {
  // w = 1 - u / 8: zero at u = 8, -1 at the far corner u = 16.
  const PerspectiveMatrix behind = fixed_matrix(0.5, 0, 0, 0, 0.5, 0, -0.125, 0, 1);
  EXPECT_EQ(warp_error(TEXTURE, behind, box()),
            "denominator w = -1.0000 at texture corner (u, v) = (16, 0) is not positive: the texture reaches behind "
            "the eye");
  const PerspectiveMatrix large = fixed_matrix(0.5, 0, 0, 0, 0.5, 0, 0, 0.0625, 1.5);
  EXPECT_EQ(warp_error(TEXTURE, large, box()),
            "denominator w = 2.0000 at texture corner (u, v) = (0, 8) is not below 2, the range of q2_30: scale the "
            "matrix down");
}

TEST(BadInput, ABorderBeyondTheRangeNamesIt) {
  // x = (0.05 u + 100) / w: with w = 1/512 the row's ends are beyond q16_16
  // (51200 pixels), with w = 1/256 its first border (25600) is beyond the
  // resampler's 16384.
  const PerspectiveMatrix beyond_q16_16 = fixed_matrix(0.05, 0, 100, 0, 0.05, 0, 0, 0, 1.0 / 512);
  EXPECT_EQ(warp_error(TEXTURE, beyond_q16_16, box()), "rows first, row 0: an end of the row maps beyond 32768 pixels");
  const PerspectiveMatrix beyond_resampler = fixed_matrix(0.05, 0, 100, 0, 0.05, 0, 0, 0, 1.0 / 256);
  EXPECT_EQ(warp_error(TEXTURE, beyond_resampler, box()),
            "row pass, row 0: border 0 = 100.0000 / 0.0039 is beyond 16384 pixels or its denominator is not positive");
}

TEST(BadInput, SizesOutOfRangeAreNamed) {
  EXPECT_EQ(warp_error(Image{0, 8, {}}, HALF, box()),
            "texture size 0 x 8 is out of range: each side must be 1 .. 1024");
  EXPECT_EQ(warp_error(TEXTURE, HALF, box(), 32, 2000),
            "output size 32 x 2000 is out of range: each side must be 1 .. 1024");
  EXPECT_EQ(warp_error(Image{4, 4, std::vector<uint8_t>(15)}, HALF, box()),
            "texture holds 15 texels, not width x height");
}

TEST(BadInput, AMatrixBeyondTheFormatsNamesTheNumerator) {
  // x w = 2047 + 1.5 u leaves q12_20 at the row's end.
  const PerspectiveMatrix shifted = fixed_matrix(1, 0, 2047, 0, 1, 0, 0, 0, 1.9);
  EXPECT_EQ(warp_error(TEXTURE, shifted, box()),
            "rows first, row pass, row 0: numerator x w = 2063.0000 leaves q12_20 (abs below 2048): the texture maps "
            "too far from the origin");
}

TEST(FormatFixed, PrintsFourRoundedPlaces) {
  EXPECT_EQ(format_fixed(3 << 15, 16), "1.5000");
  EXPECT_EQ(format_fixed(-(1 << 14), 16), "-0.2500");
  EXPECT_EQ(format_fixed(65535, 16), "1.0000");  // 0.99998 rounds up
  EXPECT_EQ(format_fixed(1, 30), "0.0000");
}

}  // namespace
}  // namespace tessera::forward_texture
