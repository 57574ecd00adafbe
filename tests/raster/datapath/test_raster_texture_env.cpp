// Unit tests of the texel filter and texture environment
// (tlm/raster/datapath/texture_env.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raster/datapath/texture_env.h"

namespace tessera::raster {
namespace {

Rgba8 colour(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return {unorm8{r}, unorm8{g}, unorm8{b}, unorm8{a}};
}

TEST(TextureEnv, Div255IsExactlyRoundedOverItsDomain) {
  for (uint32_t x = 0; x <= 255 * 255; ++x) {
    ASSERT_EQ(div255_round(x), (2 * x + 255) / 510) << x;
  }
}

TEST(TextureEnv, NearestWeightsReturnTheFirstTexel) {
  const std::array<Rgba8, 4> t{colour(1, 2, 3, 4), colour(255, 255, 255, 255), colour(9, 9, 9, 9), colour(0, 0, 0, 0)};
  EXPECT_EQ(bilinear_filter(t, 0, 0), t[0]);
}

TEST(TextureEnv, BilinearByHand) {
  const std::array<Rgba8, 4> t{colour(0, 0, 0, 0), colour(255, 0, 100, 10), colour(0, 255, 100, 20),
                               colour(255, 255, 100, 30)};
  // Halfway on both axes: the mean. R = (255 + 255) / 4 = 127.5 -> 128 (ties up).
  const Rgba8 m = bilinear_filter(t, 128, 128);
  EXPECT_EQ(m, colour(128, 128, 75, 15));
  // Only s: a = 64 (1/4) between texel 0 and 1: R = 63.75 -> 64, A = 2.5 -> 3.
  EXPECT_EQ(bilinear_filter(t, 64, 0), colour(64, 0, 25, 3));
}

TEST(TextureEnv, BilinearMatchesRealArithmetic) {
  std::mt19937_64 rng(11);
  for (int n = 0; n < 20000; ++n) {
    std::array<Rgba8, 4> t{};
    for (auto& x : t) {
      x = Rgba8::unpack(static_cast<uint32_t>(rng()));
    }
    const auto a = static_cast<uint8_t>(rng());
    const auto b = static_cast<uint8_t>(rng());
    const double fa = a / 256.0, fb = b / 256.0;
    const Rgba8 got = bilinear_filter(t, a, b);
    const double r = (1 - fa) * (1 - fb) * t[0].r.raw + fa * (1 - fb) * t[1].r.raw + (1 - fa) * fb * t[2].r.raw +
                     fa * fb * t[3].r.raw;
    ASSERT_EQ(got.r.raw, static_cast<uint32_t>(std::floor(r + 0.5)));
  }
}

TEST(TextureEnv, EnvironmentsFollowGlTable) {
  const Rgba8 f = colour(200, 100, 50, 128);
  const Rgba8 t = colour(255, 128, 0, 64);
  EXPECT_EQ(texture_environment(TexEnv::replace, f, t), t);
  // MODULATE: 200, round(100*128/255 = 50.196) = 50, 0, round(128*64/255 = 32.125) = 32.
  EXPECT_EQ(texture_environment(TexEnv::modulate, f, t), colour(200, 50, 0, 32));
  // DECAL: C = (Cf (255 - 64) + Ct 64) / 255; A = Af.
  // R: (200*191 + 255*64)/255 = 213.80 -> 214; G: (100*191 + 128*64)/255 = 107.02 -> 107;
  // B: 50*191/255 = 37.45 -> 37.
  EXPECT_EQ(texture_environment(TexEnv::decal, f, t), colour(214, 107, 37, 128));
  // A code this unit does not draw (3: BLEND, the combiner's): fragment unchanged.
  EXPECT_EQ(texture_environment(static_cast<TexEnv>(3), f, t), f);
  EXPECT_EQ(code_of(static_cast<TexEnv>(3)), 3u);
  // MODULATE with white is the identity.
  EXPECT_EQ(texture_environment(TexEnv::modulate, f, colour(255, 255, 255, 255)), f);
}

}  // namespace
}  // namespace tessera::raster
