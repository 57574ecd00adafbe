// Co-simulation: tlm/raster/datapath/attribute_interpolator.h against the
// Verilated rtl_models/raster/attr_interp.sv, every output bit.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "attr_interp_adapter.h"
#include "cosim_support.h"
#include "raster/datapath/attribute_interpolator.h"

namespace tessera::raster {
namespace {

struct Checker : CosimTally {
  AttrInterpRtl rtl;

  void check(const AttributePlane& p, int dx, int dy) {
    const AttributeEvaluation want = evaluate_attribute(p, dx, dy);
    const AttributeEvaluation got = rtl.evaluate(p, dx, dy);
    const bool same = want.value == got.value && want.value_next_x == got.value_next_x &&
                      want.value_next_y == got.value_next_y && want.output == got.output;
    if (count(same)) {
      ADD_FAILURE() << "kind " << int(p.kind) << " start " << p.start << " gx " << p.grad_x << " gy " << p.grad_y
                    << " offset " << dx << "," << dy << ": value " << want.value.raw << "/" << got.value.raw
                    << " next_x " << want.value_next_x.raw << "/" << got.value_next_x.raw << " next_y "
                    << want.value_next_y.raw << "/" << got.value_next_y.raw << " output " << want.output << "/"
                    << got.output;
    }
  }
};

TEST(AttrInterpCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const int64_t lo = -(int64_t{1} << 39), hi = (int64_t{1} << 39) - 1;
  const std::array<int64_t, 10> words{0, 1, -1, lo, hi, 1 << 15, 255 << 16, (255 << 16) + (1 << 15), 127, 0xffffff80};
  const std::array<int, 6> offsets{-512, -1, 0, 1, 2, 511};
  for (int kind = 0; kind < 4; ++kind)
    for (int64_t s : words)
      for (int64_t gx : words)
        for (int64_t gy : words)
          for (int dx : offsets)
            for (int dy : offsets) {
              c.check(AttributePlane{static_cast<AttributeKind>(kind), s, gx, gy}, dx, dy);
            }
  const uint64_t corner_vectors = c.vectors;

  // Random words at random magnitudes, so that the conversions are seen
  // inside their range as well as clamped.
  std::mt19937_64 rng(0xa77a1);
  auto word = [&rng]() {
    const unsigned bits = 1 + static_cast<unsigned>(rng() % 40);
    return sign_extend(rng(), bits);
  };
  for (uint64_t i = 0; i < RANDOM_VECTORS; ++i) {
    const auto kind = static_cast<AttributeKind>(rng() & 3);
    const int64_t s = word(), gx = word(), gy = word();
    const uint64_t o = rng();
    c.check(AttributePlane{kind, s, gx, gy}, static_cast<int>(o & 0x3ff) - 512,
            static_cast<int>((o >> 10) & 0x3ff) - 512);
  }
  report_cosim("attr_interp", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
