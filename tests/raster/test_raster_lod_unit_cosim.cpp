// Co-simulation: tlm/raster/datapath/lod_unit.h against the Verilated
// rtl_models/raster/lod_unit.sv, every output. Exhaustive over every rho
// below 2^21 (lambda up to 5) with the state cycling through every filter
// pair, mipmap code and last level, the powers of two and their neighbours
// with every state, then a million random vectors over the whole 32-bit rho.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "cosim_support.h"
#include "lod_unit_adapter.h"
#include "raster/datapath/lod_unit.h"

namespace tessera::raster {
namespace {

// Filters (2 x 2), mipmap codes (4) and last levels (16): 256 states.
constexpr unsigned STATES = 256;

struct Checker : CosimTally {
  LodUnitRtl rtl;

  void check(uint32_t rho, unsigned state) {
    const TexFilter min = from_code<TexFilter>(state), mag = from_code<TexFilter>(state >> 1);
    const TexMipmap mipmap = from_code<TexMipmap>(state >> 2);
    const unsigned last = (state >> 4) & 15;
    const LodResult want = lod_unit(rho, min, mag, mipmap, last);
    const LodResult got = rtl.run(rho, min, mag, mipmap, last);
    const bool same = want.lambda == got.lambda && want.minified == got.minified && want.linear == got.linear &&
                      want.level[0] == got.level[0] && want.level[1] == got.level[1] &&
                      want.two_levels == got.two_levels && want.weight == got.weight;
    if (count(same)) {
      ADD_FAILURE() << std::hex << "rho " << rho << " state " << state << std::dec << ": lambda " << want.lambda << "/"
                    << got.lambda << " minified " << want.minified << "/" << got.minified << " linear " << want.linear
                    << "/" << got.linear << " levels " << unsigned(want.level[0]) << "," << unsigned(want.level[1])
                    << "/" << unsigned(got.level[0]) << "," << unsigned(got.level[1]) << " two " << want.two_levels
                    << "/" << got.two_levels << " weight " << unsigned(want.weight) << "/" << unsigned(got.weight);
    }
  }
};

TEST(LodUnitCosim, ExhaustiveLowRhoAndRandomVectorsMatchBitForBit) {
  Checker c;
  for (uint32_t rho = 0; rho < (1u << 21); ++rho) c.check(rho, (rho * 2654435761u) >> 24);
  for (unsigned b = 0; b < 32; ++b)
    for (const uint32_t rho : {(1u << b) - 1, 1u << b, (1u << b) + 1})
      for (unsigned state = 0; state < STATES; ++state) c.check(rho, state);
  for (unsigned state = 0; state < STATES; ++state) {
    c.check(0xffffffffu, state);
    c.check(LOD_RHO_SQRT2_FLOOR, state);
    c.check(LOD_RHO_SQRT2_FLOOR + 1, state);
  }
  const uint64_t corner_vectors = c.vectors;

  std::mt19937_64 rng(0x10d);
  for (uint64_t i = 0; i < RANDOM_VECTORS; ++i) {
    const uint64_t a = rng();
    // Every magnitude equally often: a random rho shifted right by 0..31.
    c.check(static_cast<uint32_t>(a) >> ((a >> 32) & 31), static_cast<unsigned>(a >> 40) & 0xff);
  }
  report_cosim("lod_unit", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
