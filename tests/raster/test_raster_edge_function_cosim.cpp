// Co-simulation: tlm/raster/datapath/edge_function.h against the Verilated
// rtl_models/raster/edge_function.sv, every output bit, corner cases of every
// input format plus random vectors.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "cosim_support.h"
#include "edge_function_adapter.h"
#include "raster/datapath/edge_function.h"

namespace tessera::raster {
namespace {

struct Checker : CosimTally {
  EdgeFunctionRtl rtl;

  void check(const Edge& e, unsigned px, unsigned py, q5_16 recip) {
    const EdgeEvaluation want = evaluate_edge(e, px, py, recip);
    const EdgeEvaluation got = rtl.evaluate(e, px, py, recip);
    const bool same = want.value == got.value && want.value_next_x == got.value_next_x &&
                      want.value_next_y == got.value_next_y && want.inside == got.inside &&
                      want.l1_length == got.l1_length && want.distance == got.distance && want.coverage == got.coverage;
    if (count(same)) {
      ADD_FAILURE() << "edge (" << e.x0.raw << "," << e.y0.raw << ")->(" << e.x1.raw << "," << e.y1.raw << ") pixel "
                    << px << "," << py << " recip " << recip.raw << ": value " << want.value.raw << "/" << got.value.raw
                    << " next_x " << want.value_next_x.raw << "/" << got.value_next_x.raw << " next_y "
                    << want.value_next_y.raw << "/" << got.value_next_y.raw << " inside " << want.inside << "/"
                    << got.inside << " l1 " << want.l1_length.raw << "/" << got.l1_length.raw << " distance "
                    << want.distance.raw << "/" << got.distance.raw << " coverage " << want.coverage.raw << "/"
                    << got.coverage.raw;
    }
  }
};

TEST(EdgeFunctionCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::array<uint32_t, 7> coords{0, 1, 8, 4095, 4096, 8190, 8191};
  const std::array<unsigned, 5> pixels{0, 1, 256, 510, 511};
  const std::array<uint32_t, 6> recips{0, 1, 1u << 16, 1u << 20, 0x1fffff, 0x15555};
  for (uint32_t x0 : coords)
    for (uint32_t y0 : coords)
      for (uint32_t x1 : coords)
        for (uint32_t y1 : coords)
          for (unsigned px : pixels)
            for (unsigned py : pixels)
              for (uint32_t r : recips) {
                c.check(Edge{q9_4::from_raw(x0), q9_4::from_raw(y0), q9_4::from_raw(x1), q9_4::from_raw(y1)}, px, py,
                        q5_16::from_raw(r));
              }
  const uint64_t corner_vectors = c.vectors;

  std::mt19937_64 rng(0x7e55e7a);
  for (uint64_t i = 0; i < RANDOM_VECTORS; ++i) {
    const uint64_t bits = rng();
    const uint64_t more = rng();
    const Edge e{q9_4::from_raw(static_cast<uint32_t>(bits)), q9_4::from_raw(static_cast<uint32_t>(bits >> 13)),
                 q9_4::from_raw(static_cast<uint32_t>(bits >> 26)), q9_4::from_raw(static_cast<uint32_t>(bits >> 39))};
    const unsigned px = static_cast<unsigned>(more) & 0x1ff;
    const unsigned py = static_cast<unsigned>(more >> 9) & 0x1ff;
    // Half of the vectors use a short edge near the pixel, so the distance
    // and coverage leave their clamps; the reciprocal then is the exact
    // one of |dx| + |dy|, as the reciprocal unit would roughly deliver.
    if (more >> 63) {
      const uint32_t cx = px * 16 + static_cast<uint32_t>((more >> 18) & 0x3f) - 32;
      const uint32_t cy = py * 16 + static_cast<uint32_t>((more >> 24) & 0x3f) - 32;
      const Edge near{q9_4::from_raw(cx), q9_4::from_raw(cy), q9_4::from_raw(cx + ((more >> 30) & 0x7f)),
                      q9_4::from_raw(cy + ((more >> 37) & 0x7f) - 64)};
      const uint32_t l1 = edge_l1_length(near).raw;
      const uint32_t recip = l1 == 0 ? 0 : static_cast<uint32_t>((uint64_t{1} << 20) / l1);
      c.check(near, px, py, q5_16::from_raw(recip));
    } else {
      c.check(e, px, py, q5_16::from_raw(static_cast<uint32_t>(more >> 42)));
    }
  }
  report_cosim("edge_function", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
