// Co-simulation: tlm/raster/datapath/fog_unit.h against the Verilated
// rtl_models/raster/fog_unit.sv, every output bit. Exhaustive over every
// fog argument where a mode's factor is not constant (linear 0..1.0, exp
// 0..16.0, exp2 0..4.0, in 16.16 steps, each with a colour pair that moves
// with it), the corners around them, then a million random vectors over the
// whole 32-bit argument, every mode and the code without an entry.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>

#include "cosim_support.h"
#include "fog_unit_adapter.h"
#include "raster/datapath/fog_unit.h"

namespace tessera::raster {
namespace {

constexpr std::array<FogMode, 4> ALL_MODES{FogMode::linear, FogMode::exp, FogMode::exp2, static_cast<FogMode>(3)};

struct Checker : CosimTally {
  FogUnitRtl rtl;

  void check(FogMode mode, int32_t argument, Rgba8 fragment, Rgba8 fog) {
    const FogUnitResult want = fog_unit(mode, argument, fragment, fog);
    const FogUnitResult got = rtl.run(mode, argument, fragment, fog);
    if (count(want.factor == got.factor && want.color == got.color)) {
      ADD_FAILURE() << std::hex << "mode " << static_cast<unsigned>(mode) << " argument " << argument << " fragment "
                    << fragment.pack() << " fog " << fog.pack() << ": factor " << unsigned(want.factor) << "/"
                    << unsigned(got.factor) << " colour " << want.color.pack() << "/" << got.color.pack();
    }
  }
};

TEST(FogUnitCosim, ExhaustiveArgumentsAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::array<std::pair<FogMode, int32_t>, 3> ranges{
      {{FogMode::linear, 1 << 16}, {FogMode::exp, 16 << 16}, {FogMode::exp2, 4 << 16}}};
  for (const auto& [mode, last] : ranges)
    for (int32_t a = 0; a <= last + 1; ++a)
      c.check(mode, a, Rgba8::unpack(0x80000000u | uint32_t(a) * 2654435761u >> 8),
              Rgba8::unpack(~uint32_t(a) * 40503u));
  const std::array<int32_t, 9> corners{INT32_MIN, -65536, -1, 0, 1, 65535, 65536, 1 << 20, INT32_MAX};
  const std::array<uint32_t, 4> colours{0x00000000, 0xffffffff, 0x80ff7f01, 0x01807fff};
  for (FogMode mode : ALL_MODES)
    for (int32_t a : corners)
      for (uint32_t f : colours)
        for (uint32_t g : colours) c.check(mode, a, Rgba8::unpack(f), Rgba8::unpack(g));
  const uint64_t corner_vectors = c.vectors;

  std::mt19937_64 rng(0xf06);
  for (uint64_t i = 0; i < RANDOM_VECTORS; ++i) {
    const uint64_t a = rng(), b = rng();
    c.check(ALL_MODES[b & 3], static_cast<int32_t>(a), Rgba8::unpack(static_cast<uint32_t>(a >> 32)),
            Rgba8::unpack(static_cast<uint32_t>(b >> 32)));
  }
  report_cosim("fog_unit", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
