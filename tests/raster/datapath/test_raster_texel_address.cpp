// Unit tests of texel addressing (tlm/raster/datapath/texel_address.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raster/datapath/texel_address.h"

namespace tessera::raster {
namespace {

q15_16 coord(double v) {
  return q15_16{static_cast<int64_t>(std::llround(v * 65536.0))};
}

TEST(TexelAddress, RepeatWrapsNegativeCoordinates) {
  // s = -0.25 on a 4-texel texture wraps to s = 0.75: texel 3 (NEAREST),
  // texels 2 and 3 half and half (LINEAR: u - 1/2 = 2.5).
  const TexelAxis n = texel_axis_for(coord(-0.25), 2, TexWrap::repeat, TexFilter::nearest);
  const TexelAxis n_ref = texel_axis_for(coord(0.75), 2, TexWrap::repeat, TexFilter::nearest);
  EXPECT_EQ(n.index0, 3);
  EXPECT_EQ(n.index1, 3);
  EXPECT_EQ(n.weight, 0);
  EXPECT_EQ(n_ref.index0, 3);
  const TexelAxis l = texel_axis_for(coord(-0.25), 2, TexWrap::repeat, TexFilter::linear);
  EXPECT_EQ(l.index0, 2);
  EXPECT_EQ(l.index1, 3);
  EXPECT_EQ(l.weight, 128);
  // Across the seam: s = 0 with LINEAR mixes the last and the first texel.
  const TexelAxis seam = texel_axis_for(coord(0.0), 3, TexWrap::repeat, TexFilter::linear);
  EXPECT_EQ(seam.index0, 7);
  EXPECT_EQ(seam.index1, 0);
  EXPECT_EQ(seam.weight, 128);
  // Many repetitions away gives the same texel.
  EXPECT_EQ(texel_axis_for(coord(-1000.25), 2, TexWrap::repeat, TexFilter::nearest).index0, 3);
  EXPECT_EQ(texel_axis_for(coord(32767.75), 8, TexWrap::repeat, TexFilter::nearest).index0, 192);
}

TEST(TexelAddress, ClampToEdgeUsesOnlyEdgeTexels) {
  for (double s : {-5.0, -0.01, 0.0, 0.03}) {  // u <= 1/2
    const TexelAxis a = texel_axis_for(coord(s), 4, TexWrap::clamp_to_edge, TexFilter::linear);
    EXPECT_EQ(a.index0, 0) << s;
    EXPECT_EQ(a.weight, 0) << s;  // clamped to the centre of texel 0
  }
  for (double s : {1.0, 0.99, 7.5}) {
    const TexelAxis a = texel_axis_for(coord(s), 4, TexWrap::clamp_to_edge, TexFilter::linear);
    EXPECT_EQ(a.index0, 15) << s;
    EXPECT_EQ(a.index1, 15) << s;
    const TexelAxis n = texel_axis_for(coord(s), 4, TexWrap::clamp_to_edge, TexFilter::nearest);
    EXPECT_EQ(n.index0, 15) << s;
  }
  // Inside: s = 0.5 on 16 texels, u = 8: LINEAR between texels 7 and 8.
  const TexelAxis mid = texel_axis_for(coord(0.5), 4, TexWrap::clamp_to_edge, TexFilter::linear);
  EXPECT_EQ(mid.index0, 7);
  EXPECT_EQ(mid.index1, 8);
  EXPECT_EQ(mid.weight, 128);
}

TEST(TexelAddress, LinearWeightsAndFloor) {
  // u = 5.75 on 8 texels (s = 5.75/8): u - 1/2 = 5.25, texels 5 and 6, weight 64/256.
  const TexelAxis a = texel_axis_for(coord(5.75 / 8), 3, TexWrap::repeat, TexFilter::linear);
  EXPECT_EQ(a.index0, 5);
  EXPECT_EQ(a.index1, 6);
  EXPECT_EQ(a.weight, 64);
  // Weight is truncated: frac = 0.25 + 2^-16 still gives 64.
  const TexelAxis b = texel_axis_for(q15_16{coord(5.75 / 8).raw + 1}, 3, TexWrap::repeat, TexFilter::linear);
  EXPECT_EQ(b.weight, 64);
}

TEST(TexelAddress, OneTexelTextureAndOversizedLog2) {
  for (double s : {-3.3, 0.0, 0.7, 12.0}) {
    for (TexWrap w : {TexWrap::repeat, TexWrap::clamp_to_edge}) {
      const TexelAxis a = texel_axis_for(coord(s), 0, w, TexFilter::linear);
      EXPECT_EQ(a.index0, 0);
      EXPECT_EQ(a.index1, 0);
    }
  }
  EXPECT_EQ(texel_axis_for(coord(0.999), 15, TexWrap::repeat, TexFilter::nearest).index0, 255);
}

TEST(TexelAddress, AddressesOfTheFourTexels) {
  TextureState st;
  st.base = 0x8000'0000;
  st.log2_width = 6;
  st.log2_height = 5;
  st.filter = TexFilter::linear;
  // Texel space (10.5 + 0.5, 3.25 + 0.5): i0 = 10, j0 = 3.
  const TexelFootprint f = texel_lookup(st, coord(11.0 / 64), coord(3.75 / 32));
  EXPECT_EQ(f.s.index0, 10);
  EXPECT_EQ(f.t.index0, 3);
  EXPECT_EQ(f.t.weight, 64);
  EXPECT_EQ(f.address[0], 0x8000'0000u + (3 * 64 + 10) * 4);
  EXPECT_EQ(f.address[1], 0x8000'0000u + (3 * 64 + 11) * 4);
  EXPECT_EQ(f.address[2], 0x8000'0000u + (4 * 64 + 10) * 4);
  EXPECT_EQ(f.address[3], 0x8000'0000u + (4 * 64 + 11) * 4);
  // Wraps modulo 2^32.
  EXPECT_EQ(texel_address(0xffff'fffc, 8, 1, 0), 0u);
  EXPECT_EQ(texel_address(0, 8, 255, 255), (255u * 256 + 255) * 4);
}

TEST(TexelAddress, NearestMatchesFloatingPointReference) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> dist(-4.0, 4.0);
  for (int n = 0; n < 100000; ++n) {
    const q15_16 s = coord(dist(rng));
    const unsigned log2n = static_cast<unsigned>(rng() % 9);
    const double size = double(1u << log2n);
    const double u = s.to_double() * size;
    const auto repeat = static_cast<uint8_t>(static_cast<int64_t>(std::floor(u)) & ((1 << log2n) - 1));
    const auto clamp = static_cast<uint8_t>(std::clamp(std::floor(u), 0.0, size - 1));
    ASSERT_EQ(texel_axis_for(s, log2n, TexWrap::repeat, TexFilter::nearest).index0, repeat);
    ASSERT_EQ(texel_axis_for(s, log2n, TexWrap::clamp_to_edge, TexFilter::nearest).index0, clamp);
  }
}

// fixed_function.def: wrap codes 2 and 3 have no entry and act as REPEAT.
TEST(TexelAddress, UnknownWrapCodesActAsRepeat) {
  for (uint32_t code = 2; code < 4; ++code) {
    for (double s : {-1.3, -0.25, 0.0, 0.4, 0.99, 1.7, 5.5}) {
      for (TexFilter f : {TexFilter::nearest, TexFilter::linear}) {
        const TexelAxis unknown = texel_axis_for(coord(s), 3, from_code<TexWrap>(code), f);
        const TexelAxis repeat = texel_axis_for(coord(s), 3, TexWrap::repeat, f);
        EXPECT_EQ(unknown.index0, repeat.index0) << code << " " << s;
        EXPECT_EQ(unknown.index1, repeat.index1) << code << " " << s;
        EXPECT_EQ(unknown.weight, repeat.weight) << code << " " << s;
      }
    }
  }
}

}  // namespace
}  // namespace tessera::raster
