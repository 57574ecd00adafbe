// Co-simulation: tlm/raster/datapath/attribute_interpolator.h against the
// Verilated rtl_models/raster/attr_interp.sv, every output bit. Every vector
// goes through the scalar form (evaluate_attribute) and through the batch
// form (attribute_span) in every variant this machine runs: a corner vector
// as a span of one offset, the random vectors as spans of 1 to 64 offsets
// along a row.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "attr_interp_adapter.h"
#include "cosim_support.h"
#include "raster/datapath/attribute_interpolator.h"

namespace tessera::raster {
namespace {

constexpr unsigned MAX_SPAN = 64;

struct SpanBuffers {
  std::array<int64_t, MAX_SPAN + 1> value{};
  std::array<int64_t, MAX_SPAN> value_next_y{};
  std::array<uint32_t, MAX_SPAN> output{};
  AttributeSpan view() { return {value.data(), value_next_y.data(), output.data()}; }
};

struct Checker : CosimTally {
  AttrInterpRtl rtl;

  // The offsets (dx .. dx + offsets - 1, dy).
  void check_span(const AttributePlane& p, int dx, int dy, unsigned offsets) {
    std::vector<SpanBuffers> spans(batch_isas().size());
    for (size_t k = 0; k < spans.size(); ++k) attribute_span(p, dx, dy, offsets, spans[k].view(), batch_isas()[k]);
    for (unsigned i = 0; i < offsets; ++i) {
      const int x = dx + static_cast<int>(i);
      const AttributeEvaluation want = evaluate_attribute(p, x, dy);
      const AttributeEvaluation got = rtl.evaluate(p, x, dy);
      bool same = want.value == got.value && want.value_next_x == got.value_next_x &&
                  want.value_next_y == got.value_next_y && want.output == got.output;
      for (const SpanBuffers& s : spans)
        same = same && s.value[i] == got.value.raw && s.value[i + 1] == got.value_next_x.raw &&
               s.value_next_y[i] == got.value_next_y.raw && s.output[i] == got.output;
      if (count(same)) {
        ADD_FAILURE() << "kind " << int(p.kind) << " start " << p.start << " gx " << p.grad_x << " gy " << p.grad_y
                      << " offset " << x << "," << dy << " (span from " << dx << ", " << offsets << "): value "
                      << want.value.raw << "/" << got.value.raw << " next_x " << want.value_next_x.raw << "/"
                      << got.value_next_x.raw << " next_y " << want.value_next_y.raw << "/" << got.value_next_y.raw
                      << " output " << want.output << "/" << got.output << " (or a batch variant)";
      }
    }
  }
};

TEST(AttrInterpCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const int64_t lo = -(int64_t{1} << 39), hi = (int64_t{1} << 39) - 1;
  const std::array<int64_t, 10> words{0, 1, -1, lo, hi, 1 << 15, 255 << 16, (255 << 16) + (1 << 15), 127, 0xffffff80};
  const std::array<int, 6> corner_offsets{-512, -1, 0, 1, 2, 511};
  for (int kind = 0; kind < 4; ++kind)
    for (int64_t s : words)
      for (int64_t gx : words)
        for (int64_t gy : words)
          for (int dx : corner_offsets)
            for (int dy : corner_offsets) {
              c.check_span(AttributePlane{static_cast<AttributeKind>(kind), s, gx, gy}, dx, dy, 1);
            }
  const uint64_t corner_vectors = c.vectors;

  // Random words at random magnitudes, so that the conversions are seen
  // inside their range as well as clamped.
  std::mt19937_64 rng(0xa77a1);
  auto word = [&rng]() {
    const unsigned bits = 1 + static_cast<unsigned>(rng() % 40);
    return sign_extend(rng(), bits);
  };
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const auto kind = static_cast<AttributeKind>(rng() & 3);
    const int64_t s = word(), gx = word(), gy = word();
    const uint64_t o = rng();
    const int dx = static_cast<int>(o & 0x3ff) - 512;
    // Within the RTL's 10-bit offset port: the span ends at offset 511 at most.
    const unsigned offsets = std::min(random_batch_length(o >> 20), static_cast<unsigned>(512 - dx));
    c.check_span(AttributePlane{kind, s, gx, gy}, dx, static_cast<int>((o >> 10) & 0x3ff) - 512, offsets);
  }
  report_cosim("attr_interp", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
