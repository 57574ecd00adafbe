// Co-simulation: tlm/raster/datapath/lod_unit.h against the Verilated
// rtl_models/raster/lod_unit.sv, every output. Exhaustive over every rho
// below 2^21 (lambda up to 5) with the state cycling through every filter
// pair, mipmap code and last level, the powers of two and their neighbours
// with every state, then a million random vectors over the whole 32-bit rho.
// Every vector goes through the scalar form (lod_unit) and through the batch
// form (lod_unit_batch) in every variant this machine runs, with the other
// scale factors of its state (up to 64 a batch, the 99 corners).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "cosim_support.h"
#include "lod_unit_adapter.h"
#include "raster/datapath/lod_unit.h"

namespace tessera::raster {
namespace {

// One state's scale factors, checked together: the batch form takes them as
// one batch.
struct Checker : CosimTally {
  LodUnitRtl rtl;

  // `state` is LodState's 8-bit code (raster_vectors.h).
  void check(const std::vector<uint32_t>& rho, unsigned state) {
    const LodState s = LodState::from_code(state);
    const TexFilter min = s.min, mag = s.mag;
    const TexMipmap mipmap = s.mipmap;
    const unsigned last = s.last_level;
    const size_t n = rho.size();
    struct Outputs {
      std::vector<int32_t> lambda;
      std::vector<uint32_t> flags, level0, level1, weight;
    };
    std::vector<Outputs> outs;
    for (BatchIsa isa : batch_isas()) {
      outs.push_back({std::vector<int32_t>(n), std::vector<uint32_t>(n), std::vector<uint32_t>(n),
                      std::vector<uint32_t>(n), std::vector<uint32_t>(n)});
      Outputs& o = outs.back();
      lod_unit_batch(min, mag, mipmap, last, rho.data(), static_cast<unsigned>(n),
                     {o.lambda.data(), o.flags.data(), o.level0.data(), o.level1.data(), o.weight.data()}, isa);
    }
    for (size_t i = 0; i < n; ++i) {
      const LodResult want = lod_unit(rho[i], min, mag, mipmap, last);
      const LodResult got = rtl.run(rho[i], min, mag, mipmap, last);
      const uint32_t got_flags =
          (got.minified ? LOD_MINIFIED : 0) | (got.linear ? LOD_LINEAR : 0) | (got.two_levels ? LOD_TWO_LEVELS : 0);
      bool same = want.lambda == got.lambda && want.minified == got.minified && want.linear == got.linear &&
                  want.level[0] == got.level[0] && want.level[1] == got.level[1] && want.two_levels == got.two_levels &&
                  want.weight == got.weight;
      for (const Outputs& o : outs)
        same = same && o.lambda[i] == got.lambda && o.flags[i] == got_flags && o.level0[i] == got.level[0] &&
               o.level1[i] == got.level[1] && o.weight[i] == got.weight;
      if (count(same)) {
        ADD_FAILURE() << std::hex << "rho " << rho[i] << " state " << state << std::dec << ": lambda " << want.lambda
                      << "/" << got.lambda << " minified " << want.minified << "/" << got.minified << " linear "
                      << want.linear << "/" << got.linear << " levels " << unsigned(want.level[0]) << ","
                      << unsigned(want.level[1]) << "/" << unsigned(got.level[0]) << "," << unsigned(got.level[1])
                      << " two " << want.two_levels << "/" << got.two_levels << " weight " << unsigned(want.weight)
                      << "/" << unsigned(got.weight) << " (or a batch variant)";
      }
    }
  }
};

TEST(LodUnitCosim, ExhaustiveLowRhoAndRandomVectorsMatchBitForBit) {
  Checker c;
  // Every rho below 2^21 in batches of 64 consecutive ones, each batch with
  // a state of its own.
  for (uint32_t first = 0; first < (1u << 21); first += 64) {
    std::vector<uint32_t> rho(64);
    for (uint32_t i = 0; i < 64; ++i) rho[i] = first + i;
    c.check(rho, (first * 2654435761u) >> 24);
  }
  // Every power of two and its neighbours, and the switch points, in every state.
  std::vector<uint32_t> corners{0xffffffffu, LOD_RHO_SQRT2_FLOOR, LOD_RHO_SQRT2_FLOOR + 1};
  for (unsigned b = 0; b < 32; ++b)
    for (const uint32_t rho : {(1u << b) - 1, 1u << b, (1u << b) + 1}) corners.push_back(rho);
  for (unsigned state = 0; state < LOD_STATES; ++state) c.check(corners, state);
  const uint64_t corner_vectors = c.vectors;

  // States at random, each with a batch of 1 to 64 random scale factors of
  // every magnitude (raster_vectors.h).
  VectorRng rng(0x10d);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const auto state = static_cast<unsigned>(rng() % LOD_STATES);
    std::vector<uint32_t> rho(random_batch_length(rng()));
    for (uint32_t& r : rho) r = random_lod_rho(rng);
    c.check(rho, state);
  }
  report_cosim("lod_unit", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
