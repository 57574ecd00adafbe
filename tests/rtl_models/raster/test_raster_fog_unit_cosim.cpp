// Co-simulation: tlm/raster/datapath/fog_unit.h against the Verilated
// rtl_models/raster/fog_unit.sv, every output bit. Exhaustive over every
// fog argument where a mode's factor is not constant (linear 0..1.0, exp
// 0..16.0, exp2 0..4.0, in 16.16 steps, each with a colour pair that moves
// with it), the corners around them, then a million random vectors
// (testbench/cosim/raster_vectors.h: half over the whole 32-bit argument,
// half within the table's reach), every mode and the code without an entry. Every
// vector goes through the scalar form (fog_unit) and through the batch form
// (fog_unit_batch) in every variant this machine runs, with the other
// fragments of its mode and fog colour (up to 64 a batch).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "cosim_support.h"
#include "fog_unit_adapter.h"
#include "raster/datapath/fog_unit.h"

namespace tessera::raster {
namespace {

// One mode's and fog colour's fragments, checked together: the batch form
// takes them as one batch.
struct Checker : CosimTally {
  FogUnitRtl rtl;

  void check(FogMode mode, Rgba8 fog, const std::vector<int32_t>& argument, const std::vector<uint32_t>& fragment) {
    const size_t n = argument.size();
    std::vector<std::vector<uint32_t>> factor, color;
    for (BatchIsa isa : batch_isas()) {
      factor.emplace_back(n);
      color.emplace_back(n);
      fog_unit_batch(mode, fog, argument.data(), fragment.data(), static_cast<unsigned>(n),
                     {factor.back().data(), color.back().data()}, isa);
    }
    for (size_t i = 0; i < n; ++i) {
      const FogUnitResult want = fog_unit(mode, argument[i], Rgba8::unpack(fragment[i]), fog);
      const FogUnitResult got = rtl.run(mode, argument[i], Rgba8::unpack(fragment[i]), fog);
      bool same = want.factor == got.factor && want.color == got.color;
      for (size_t k = 0; k < factor.size(); ++k)
        same = same && factor[k][i] == got.factor && color[k][i] == got.color.pack();
      if (count(same)) {
        ADD_FAILURE() << std::hex << "mode " << static_cast<unsigned>(mode) << " argument " << argument[i]
                      << " fragment " << fragment[i] << " fog " << fog.pack() << ": factor " << unsigned(want.factor)
                      << "/" << unsigned(got.factor) << " colour " << want.color.pack() << "/" << got.color.pack()
                      << " (or a batch variant)";
      }
    }
  }
};

TEST(FogUnitCosim, ExhaustiveArgumentsAndRandomVectorsMatchBitForBit) {
  Checker c;
  // Every argument of each mode's range, in batches of 64 consecutive ones,
  // each fragment colour moving with its argument, each batch with a fog
  // colour of its own.
  const std::array<std::pair<FogMode, int32_t>, 3> ranges{
      {{FogMode::linear, 1 << 16}, {FogMode::exp, 16 << 16}, {FogMode::exp2, 4 << 16}}};
  for (const auto& [mode, last] : ranges)
    for (int32_t first = 0; first <= last + 1; first += 64) {
      std::vector<int32_t> arguments;
      std::vector<uint32_t> fragments;
      for (int32_t a = first; a < first + 64 && a <= last + 1; ++a) {
        arguments.push_back(a);
        fragments.push_back(0x80000000u | uint32_t(a) * 2654435761u >> 8);
      }
      c.check(mode, Rgba8::unpack(~uint32_t(first) * 40503u), arguments, fragments);
    }
  const std::vector<int32_t> corners{INT32_MIN, -65536, -1, 0, 1, 65535, 65536, 1 << 20, INT32_MAX};
  const std::array<uint32_t, 4> colours{0x00000000, 0xffffffff, 0x80ff7f01, 0x01807fff};
  for (FogMode mode : ALL_FOG_MODES)
    for (uint32_t g : colours) {
      std::vector<int32_t> arguments;
      std::vector<uint32_t> fragments;
      for (int32_t a : corners)
        for (uint32_t f : colours) {
          arguments.push_back(a);
          fragments.push_back(f);
        }
      c.check(mode, Rgba8::unpack(g), arguments, fragments);
    }
  const uint64_t corner_vectors = c.vectors;

  // Modes and fog colours at random, each with a batch of 1 to 64 random
  // fragments.
  VectorRng rng(0xf06);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const FogUnitState state = random_fog_state(rng);
    std::vector<int32_t> arguments(random_batch_length(rng()));
    std::vector<uint32_t> fragments(arguments.size());
    for (size_t i = 0; i < arguments.size(); ++i) {
      const FogLane lane = random_fog_lane(rng);
      arguments[i] = lane.argument;
      fragments[i] = lane.fragment;
    }
    c.check(state.mode, state.colour, arguments, fragments);
  }
  report_cosim("fog_unit", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
