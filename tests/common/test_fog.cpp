// The fixed-point fog arithmetic of common/fog.h against the GL formulas
// computed anew in double precision: the table entry by entry, the factor of
// every exponential argument up to where it is 0, linear fog, the blend.
#include "common/fog.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>

namespace {

using tessera::fog_blend;
using tessera::fog_exp2_negative;
using tessera::FOG_EXP2_TABLE;
using tessera::fog_factor;
using tessera::FOG_ONE;
using tessera::FogMode;

TEST(Fog, TableHoldsTwoToTheMinusMidpoint) {
  for (unsigned i = 0; i < 256; ++i) {
    const double expected = std::round(65536.0 * std::exp2(-(i + 0.5) / 256.0));
    EXPECT_EQ(FOG_EXP2_TABLE[i], expected) << "entry " << i;
  }
}

// Every 16.16 argument from 0 to 16.0: the 8-bit factor stays within the
// stated 0.84 of 255 * 2^-x, and it never rises as x grows.
TEST(Fog, ExponentialWithinStatedErrorEverywhere) {
  double worst = 0;
  uint32_t worst_x = 0;
  uint8_t previous = 255;
  for (uint32_t x = 0; x <= 16u * FOG_ONE; ++x) {
    const uint8_t f = fog_exp2_negative(x);
    const double exact = 255.0 * std::exp2(-double(x) / FOG_ONE);
    const double error = std::fabs(f - exact);
    if (error > worst) worst = error, worst_x = x;
    ASSERT_LE(f, previous) << "x = " << x;
    previous = f;
  }
  std::cout << "largest error of the 8-bit factor: " << worst << " at x = " << double(worst_x) / FOG_ONE << "\n";
  EXPECT_LE(worst, 0.84);
  EXPECT_EQ(fog_exp2_negative(0), 255);
  EXPECT_EQ(fog_exp2_negative(9u * FOG_ONE), 0);
  EXPECT_EQ(fog_exp2_negative(UINT32_MAX), 0);
}

TEST(Fog, ModesFollowTheGlFormulas) {
  // exp: a = d c / ln 2 gives e^-dc; exp2: a = d c / sqrt(ln 2) gives e^-(dc)^2.
  for (double dc = 0; dc < 4; dc += 0.01) {
    const auto exp_a = int32_t(std::llround(dc / std::log(2.0) * FOG_ONE));
    EXPECT_NEAR(fog_factor(FogMode::exp, exp_a), 255 * std::exp(-dc), 0.9) << dc;
    const auto exp2_a = int32_t(std::llround(dc / std::sqrt(std::log(2.0)) * FOG_ONE));
    EXPECT_NEAR(fog_factor(FogMode::exp2, exp2_a), 255 * std::exp(-dc * dc), 0.9) << dc;
  }
  EXPECT_EQ(fog_factor(FogMode::exp, -FOG_ONE), 255);  // negative arguments act as 0
  EXPECT_EQ(fog_factor(FogMode::exp2, INT32_MAX), 0);
  EXPECT_EQ(fog_factor(FogMode::linear, -5), 0);
  EXPECT_EQ(fog_factor(FogMode::linear, FOG_ONE / 2), 128);  // 127.5 rounds up
  EXPECT_EQ(fog_factor(FogMode::linear, FOG_ONE), 255);
  EXPECT_EQ(fog_factor(FogMode::linear, INT32_MAX), 255);
  EXPECT_EQ(fog_factor(static_cast<FogMode>(3), 0), 255);  // the table's unknown code: no fog
}

TEST(Fog, BlendKeepsAlphaAndRoundsToNearest) {
  const uint32_t white = 0x80ffffffu, fog = 0x00402010u;
  EXPECT_EQ(fog_blend(255, white, fog), white);
  EXPECT_EQ(fog_blend(0, white, fog), 0x80402010u);
  for (uint32_t f = 0; f < 256; ++f) {
    for (uint32_t c = 0; c < 256; c += 5) {
      const uint32_t out = fog_blend(uint8_t(f), c | 0x11000000u, 200);
      const double exact = (f * c + (255.0 - f) * 200) / 255.0;
      EXPECT_NEAR(double(out & 0xff), exact, 0.5) << f << " " << c;
      EXPECT_EQ(out >> 24, 0x11u);
    }
  }
}

}  // namespace
