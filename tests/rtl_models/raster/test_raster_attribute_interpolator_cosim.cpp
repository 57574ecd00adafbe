// Co-simulation: tlm/raster/datapath/attribute_interpolator.h against the
// Verilated rtl_models/raster/attribute_interpolator.sv, every output bit. Every vector
// goes through the scalar form (evaluate_attribute) and through the batch
// form (attribute_batch) in every variant this machine runs, with the other
// offsets of its plane: the 36 corner offsets, or 1 to 64 random ones.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "attribute_interpolator_adapter.h"
#include "cosim_support.h"
#include "raster/datapath/attribute_interpolator.h"

namespace tessera::raster {
namespace {

// One plane's offsets, checked together: the batch form takes them as one
// batch.
struct Checker : CosimTally {
  AttributeInterpolatorRtl rtl;

  void check(const AttributePlane& p, const std::vector<int32_t>& dx, const std::vector<int32_t>& dy) {
    const size_t n = dx.size();
    struct Outputs {
      std::vector<int64_t> value, next_x, next_y;
      std::vector<uint32_t> output;
    };
    std::vector<Outputs> outs;
    for (BatchIsa isa : batch_isas()) {
      outs.push_back(
          {std::vector<int64_t>(n), std::vector<int64_t>(n), std::vector<int64_t>(n), std::vector<uint32_t>(n)});
      Outputs& o = outs.back();
      attribute_batch(p, dx.data(), dy.data(), static_cast<unsigned>(n),
                      {o.value.data(), o.next_x.data(), o.next_y.data(), o.output.data()}, isa);
    }
    for (size_t i = 0; i < n; ++i) {
      const AttributeEvaluation want = evaluate_attribute(p, dx[i], dy[i]);
      const AttributeEvaluation got = rtl.evaluate(p, dx[i], dy[i]);
      bool same = want.value == got.value && want.value_next_x == got.value_next_x &&
                  want.value_next_y == got.value_next_y && want.output == got.output;
      for (const Outputs& o : outs)
        same = same && o.value[i] == got.value.raw && o.next_x[i] == got.value_next_x.raw &&
               o.next_y[i] == got.value_next_y.raw && o.output[i] == got.output;
      if (count(same)) {
        ADD_FAILURE() << "kind " << int(p.kind) << " start " << p.start << " gx " << p.grad_x << " gy " << p.grad_y
                      << " offset " << dx[i] << "," << dy[i] << ": value " << want.value.raw << "/" << got.value.raw
                      << " next_x " << want.value_next_x.raw << "/" << got.value_next_x.raw << " next_y "
                      << want.value_next_y.raw << "/" << got.value_next_y.raw << " output " << want.output << "/"
                      << got.output << " (or a batch variant)";
      }
    }
  }
};

TEST(AttributeInterpolatorCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const int64_t lo = -(int64_t{1} << 39), hi = (int64_t{1} << 39) - 1;
  const std::array<int64_t, 10> words{0, 1, -1, lo, hi, 1 << 15, 255 << 16, (255 << 16) + (1 << 15), 127, 0xffffff80};
  const std::array<int32_t, 6> offsets{-512, -1, 0, 1, 2, 511};
  std::vector<int32_t> corner_dx, corner_dy;
  for (int32_t dx : offsets)
    for (int32_t dy : offsets) {
      corner_dx.push_back(dx);
      corner_dy.push_back(dy);
    }
  for (int kind = 0; kind < 4; ++kind)
    for (int64_t s : words)
      for (int64_t gx : words)
        for (int64_t gy : words)
          c.check(AttributePlane{static_cast<AttributeKind>(kind), s, gx, gy}, corner_dx, corner_dy);
  const uint64_t corner_vectors = c.vectors;

  // Planes at random (raster_vectors.h), each with a batch of 1 to 64
  // random offsets.
  VectorRng rng(0xa77a1);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const AttributePlane plane = random_attribute_plane(rng);
    std::vector<int32_t> dx(random_batch_length(rng())), dy(dx.size());
    for (size_t i = 0; i < dx.size(); ++i) {
      const PixelOffset o = random_pixel_offset(rng);
      dx[i] = o.dx;
      dy[i] = o.dy;
    }
    c.check(plane, dx, dy);
  }
  report_cosim("attribute_interpolator", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
