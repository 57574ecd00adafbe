// Co-simulation: tlm/raster/datapath/edge_function.h against the Verilated
// rtl_models/raster/edge_function.sv, every output bit, corner cases of every
// input format plus random vectors. Every vector goes through the scalar
// form (evaluate_edge) and through the batch form (edge_span) in every
// variant this machine runs: a corner vector as a span of one pixel, the
// random vectors as spans of 1 to 64 pixels along a row.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "cosim_support.h"
#include "edge_function_adapter.h"
#include "raster/datapath/edge_function.h"

namespace tessera::raster {
namespace {

constexpr unsigned MAX_SPAN = 64;

struct SpanBuffers {
  std::array<int32_t, MAX_SPAN + 1> value{};
  std::array<int32_t, MAX_SPAN> value_next_y{}, distance{};
  std::array<uint32_t, MAX_SPAN> inside{}, coverage{};
  q10_4 l1_length;
  EdgeSpan view() { return {value.data(), value_next_y.data(), inside.data(), distance.data(), coverage.data()}; }
};

struct Checker : CosimTally {
  EdgeFunctionRtl rtl;

  // The pixels px .. px + count - 1 of row py.
  void check_span(const Edge& e, unsigned px, unsigned py, unsigned pixels, q5_16 recip) {
    std::vector<SpanBuffers> spans(batch_isas().size());
    for (size_t k = 0; k < spans.size(); ++k)
      spans[k].l1_length = edge_span(e, px, py, pixels, recip, spans[k].view(), batch_isas()[k]);
    for (unsigned i = 0; i < pixels; ++i) {
      const EdgeEvaluation got = rtl.evaluate(e, px + i, py, recip);
      const EdgeEvaluation want = evaluate_edge(e, px + i, py, recip);
      bool same = want.value == got.value && want.value_next_x == got.value_next_x &&
                  want.value_next_y == got.value_next_y && want.inside == got.inside &&
                  want.l1_length == got.l1_length && want.distance == got.distance && want.coverage == got.coverage;
      for (const SpanBuffers& s : spans)
        same = same && s.value[i] == got.value.raw && s.value[i + 1] == got.value_next_x.raw &&
               s.value_next_y[i] == got.value_next_y.raw && s.inside[i] == uint32_t{got.inside} &&
               s.l1_length == got.l1_length && s.distance[i] == got.distance.raw && s.coverage[i] == got.coverage.raw;
      if (count(same)) {
        ADD_FAILURE() << "edge (" << e.x0.raw << "," << e.y0.raw << ")->(" << e.x1.raw << "," << e.y1.raw << ") pixel "
                      << px + i << "," << py << " (span from " << px << ", " << pixels << " pixels) recip " << recip.raw
                      << ": value " << want.value.raw << "/" << got.value.raw << " next_x " << want.value_next_x.raw
                      << "/" << got.value_next_x.raw << " next_y " << want.value_next_y.raw << "/"
                      << got.value_next_y.raw << " inside " << want.inside << "/" << got.inside << " l1 "
                      << want.l1_length.raw << "/" << got.l1_length.raw << " distance " << want.distance.raw << "/"
                      << got.distance.raw << " coverage " << want.coverage.raw << "/" << got.coverage.raw
                      << " (or a batch variant)";
      }
    }
  }
};

TEST(EdgeFunctionCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::array<uint32_t, 7> coords{0, 1, 8, 4095, 4096, 8190, 8191};
  const std::array<unsigned, 5> corner_pixels{0, 1, 256, 510, 511};
  const std::array<uint32_t, 6> recips{0, 1, 1u << 16, 1u << 20, 0x1fffff, 0x15555};
  for (uint32_t x0 : coords)
    for (uint32_t y0 : coords)
      for (uint32_t x1 : coords)
        for (uint32_t y1 : coords)
          for (unsigned px : corner_pixels)
            for (unsigned py : corner_pixels)
              for (uint32_t r : recips) {
                c.check_span(Edge{q9_4::from_raw(x0), q9_4::from_raw(y0), q9_4::from_raw(x1), q9_4::from_raw(y1)}, px,
                             py, 1, q5_16::from_raw(r));
              }
  const uint64_t corner_vectors = c.vectors;

  // Spans of 1 to 64 pixels at random (raster_vectors.h: half of them of a
  // short edge near their first pixel).
  VectorRng rng(0x7e55e7a);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const unsigned pixels = random_batch_length(rng());
    const EdgeSpanVector span = random_edge_span(rng, pixels);
    c.check_span(span.edge, span.px, span.py, pixels, span.recip);
  }
  report_cosim("edge_function", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
