// The level-of-detail unit (raster/datapath/lod_unit.h): lambda against the
// exact log2 (every rho below 2^22 and 2^22 random others), and the
// minification switch and level choice at values worked out by hand from
// OpenGL ES 1.1 sections 3.8.8 and 3.8.9.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "raster/datapath/lod_unit.h"

namespace {

using namespace tessera;
using namespace tessera::raster;

uint32_t rho_of(double texels_per_pixel) {
  return static_cast<uint32_t>(std::llround(texels_per_pixel * 65536.0));
}

double lambda_error(uint32_t rho) {
  return std::fabs(lod_lambda(rho) / 256.0 - std::log2(rho / 65536.0));
}

TEST(LodUnit, LambdaIsLog2WithinStatedError) {
  double worst = 0;
  uint32_t worst_rho = 0;
  const auto check = [&](uint32_t rho) {
    const double e = lambda_error(rho);
    if (e > worst) worst = e, worst_rho = rho;
  };
  for (uint32_t rho = 1; rho < (1u << 22); ++rho) check(rho);
  std::mt19937 random(17);
  for (unsigned k = 0; k < (1u << 22); ++k) check(std::max<uint32_t>(random() >> (random() % 32), 1));
  check(0xffffffffu);
  std::printf("lod_lambda: largest error %.6f (%.3f of 1/256) at rho 0x%08x\n", worst, worst * 256, worst_rho);
  EXPECT_LE(worst, 0.52 / 256) << "rho " << worst_rho;
}

TEST(LodUnit, LambdaAtPowersOfTwoIsExact) {
  EXPECT_EQ(lod_lambda(0), LOD_LAMBDA_MIN);
  for (int k = -16; k < 16; ++k) EXPECT_EQ(lod_lambda(uint32_t{1} << (k + 16)), k * 256) << k;
  // log2 3 = 1.58496: 405.75 / 256, rounded 406.
  EXPECT_EQ(lod_lambda(rho_of(3.0)), 406);
  // Monotonic: a larger rho never gives a smaller lambda.
  int32_t previous = LOD_LAMBDA_MIN;
  for (uint32_t rho = 1; rho < (1u << 20); rho += 7) {
    EXPECT_GE(lod_lambda(rho), previous) << rho;
    previous = lod_lambda(rho);
  }
}

// GL: minified when lambda > c; c = 1/2 only for mag LINEAR with a
// NEAREST_MIPMAP_* minification filter.
TEST(LodUnit, SwitchPointFollowsSection389) {
  const TexFilter nearest = TexFilter::nearest, linear = TexFilter::linear;
  // lambda = 0 exactly: magnified with any c.
  EXPECT_FALSE(lod_unit(LOD_RHO_ONE, linear, nearest, TexMipmap::linear, 8).minified);
  EXPECT_TRUE(lod_unit(LOD_RHO_ONE + 1, linear, nearest, TexMipmap::linear, 8).minified);
  // rho 1.3 (lambda 0.38): c = 1/2 for mag LINEAR, min NEAREST_MIPMAP_*.
  const uint32_t rho = rho_of(1.3);
  EXPECT_FALSE(lod_unit(rho, nearest, linear, TexMipmap::nearest, 8).minified);
  EXPECT_FALSE(lod_unit(rho, nearest, linear, TexMipmap::linear, 8).minified);
  EXPECT_TRUE(lod_unit(rho, linear, linear, TexMipmap::nearest, 8).minified);    // LINEAR_MIPMAP_NEAREST: c = 0
  EXPECT_TRUE(lod_unit(rho, nearest, linear, TexMipmap::none, 8).minified);      // GL_NEAREST: c = 0
  EXPECT_TRUE(lod_unit(rho, nearest, nearest, TexMipmap::nearest, 8).minified);  // mag NEAREST: c = 0
  // c = 1/2 is log2(rho) > 1/2: rho > sqrt 2 = 1.414214 (92681.9 / 2^16).
  EXPECT_FALSE(lod_unit(92681, nearest, linear, TexMipmap::nearest, 8).minified);
  EXPECT_TRUE(lod_unit(92682, nearest, linear, TexMipmap::nearest, 8).minified);
  // The within-level filter follows the decision.
  EXPECT_TRUE(lod_unit(rho_of(0.5), nearest, linear, TexMipmap::none, 8).linear);
  EXPECT_FALSE(lod_unit(rho_of(2.0), nearest, linear, TexMipmap::none, 8).linear);
  EXPECT_TRUE(lod_unit(rho_of(2.0), linear, nearest, TexMipmap::none, 8).linear);
}

// NEAREST_MIPMAP_NEAREST: d = ceil(lambda + 1/2) - 1 for lambda > 1/2, else
// 0, at most q.
TEST(LodUnit, NearestLevelRoundsHalfDown) {
  const auto level = [](double rho, unsigned q = 8) {
    const LodResult r = lod_unit(rho_of(rho), TexFilter::nearest, TexFilter::nearest, TexMipmap::nearest, q);
    EXPECT_FALSE(r.two_levels);
    EXPECT_EQ(r.weight, 0);
    return int(r.level[0]);
  };
  EXPECT_EQ(level(0.25), 0);            // magnified
  EXPECT_EQ(level(1.2), 0);             // lambda 0.26
  EXPECT_EQ(level(std::sqrt(2.0)), 0);  // lambda 0.5: d = 0
  EXPECT_EQ(level(1.45), 1);            // lambda 0.536
  EXPECT_EQ(level(2.0), 1);             // lambda 1: ceil(1.5) - 1
  EXPECT_EQ(level(std::sqrt(8.0)), 1);  // lambda 1.5: ceil(2) - 1 = 1
  EXPECT_EQ(level(2.9), 2);             // lambda 1.536
  EXPECT_EQ(level(3.0), 2);             // lambda 1.585
  EXPECT_EQ(level(4.0), 2);             // lambda 2
  EXPECT_EQ(level(100.0), 7);           // lambda 6.64
  EXPECT_EQ(level(1000.0), 8);          // lambda 9.97: q
  EXPECT_EQ(level(1000.0, 3), 3);       // a shorter chain
  EXPECT_EQ(level(65535.0, 15), 15);    // the largest lambda, q = 15
  EXPECT_EQ(level(6.0, 0), 0);          // q = 0: level 0 alone
}

// *_MIPMAP_LINEAR: levels floor(lambda) and the next, weight frac(lambda).
TEST(LodUnit, LinearLevelsBlendByFraction) {
  const auto choice = [](double rho, unsigned q = 8) {
    return lod_unit(rho_of(rho), TexFilter::linear, TexFilter::linear, TexMipmap::linear, q);
  };
  LodResult r = choice(3.0);  // lambda 1.585: 406 / 256
  EXPECT_TRUE(r.minified);
  EXPECT_TRUE(r.two_levels);
  EXPECT_EQ(r.level[0], 1);
  EXPECT_EQ(r.level[1], 2);
  EXPECT_EQ(r.weight, 406 - 256);
  r = choice(std::sqrt(2.0) * 4);  // lambda 2.5
  EXPECT_EQ(r.level[0], 2);
  EXPECT_EQ(r.level[1], 3);
  EXPECT_EQ(r.weight, 128);
  r = choice(4.0);  // lambda 2: level 2 alone
  EXPECT_FALSE(r.two_levels);
  EXPECT_EQ(r.level[0], 2);
  EXPECT_EQ(r.level[1], 2);
  r = choice(1.1);  // lambda 0.1375: 35 / 256 of level 1
  EXPECT_EQ(r.level[0], 0);
  EXPECT_EQ(r.level[1], 1);
  EXPECT_EQ(r.weight, 35);
  r = choice(3.0, 1);  // lambda >= q: level q alone
  EXPECT_FALSE(r.two_levels);
  EXPECT_EQ(r.level[0], 1);
  r = choice(std::sqrt(2.0), 0);  // q = 0
  EXPECT_FALSE(r.two_levels);
  EXPECT_EQ(r.level[0], 0);
  r = choice(0.5);  // magnified: level 0
  EXPECT_FALSE(r.minified);
  EXPECT_FALSE(r.two_levels);
  EXPECT_EQ(r.level[0], 0);
}

TEST(LodUnit, NoMipmapAndUnknownCodeSampleLevelZero) {
  for (const TexMipmap mipmap : {TexMipmap::none, from_code<TexMipmap>(3)}) {
    const LodResult r = lod_unit(rho_of(16.0), TexFilter::linear, TexFilter::nearest, mipmap, 8);
    EXPECT_TRUE(r.minified);
    EXPECT_TRUE(r.linear);
    EXPECT_EQ(r.level[0], 0);
    EXPECT_FALSE(r.two_levels);
  }
}

}  // namespace
