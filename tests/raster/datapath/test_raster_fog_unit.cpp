// The fog unit against GL's fog equations (OpenGL ES 1.1, 3.8) computed
// anew in double precision: C = f Cf + (1 - f) Cfog on R, G, B, alpha kept.
#include "raster/datapath/fog_unit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace tessera::raster {
namespace {

TEST(FogUnit, BlendsTowardsTheFogColourByTheModesFactor) {
  const Rgba8 fragment = Rgba8::unpack(0x3c10f0c8u), fog = Rgba8::unpack(0xff204080u);
  for (double c = 0; c < 20; c += 0.37) {
    const double density = 0.3, start = 2, end = 15;
    const struct {
      FogMode mode;
      double argument, factor;
    } cases[] = {
        {FogMode::linear, (end - c) / (end - start), std::clamp((end - c) / (end - start), 0.0, 1.0)},
        {FogMode::exp, density * c / std::log(2.0), std::exp(-density * c)},
        {FogMode::exp2, density * c / std::sqrt(std::log(2.0)), std::exp(-density * c * density * c)},
    };
    for (const auto& k : cases) {
      const FogUnitResult r = fog_unit(k.mode, int32_t(std::llround(k.argument * 65536)), fragment, fog);
      EXPECT_NEAR(r.factor, 255 * k.factor, 0.9) << int(k.mode) << " c=" << c;
      const uint32_t in = fragment.pack(), f = fog.pack(), out = r.color.pack();
      for (int ch = 0; ch < 3; ++ch) {
        const double cf = (in >> (8 * ch)) & 0xff, cfog = (f >> (8 * ch)) & 0xff;
        const double expected = k.factor * cf + (1 - k.factor) * cfog;
        // 0.9 of a code from the factor, scaled by |Cf - Cfog| / 255, and the rounding.
        EXPECT_NEAR(double((out >> (8 * ch)) & 0xff), expected, 0.9 * std::fabs(cf - cfog) / 255 + 0.5)
            << int(k.mode) << " c=" << c << " channel " << ch;
      }
      EXPECT_EQ(out >> 24, in >> 24);
    }
  }
}

TEST(FogUnit, CodeWithoutAnEntryAppliesNoFog) {
  const Rgba8 fragment = Rgba8::unpack(0x12345678u);
  const FogUnitResult r = fog_unit(static_cast<FogMode>(3), 12345, fragment, Rgba8::unpack(0xffffffffu));
  EXPECT_EQ(r.factor, 255);
  EXPECT_EQ(r.color, fragment);
}

}  // namespace
}  // namespace tessera::raster
