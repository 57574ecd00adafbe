// See interpolation.h.
#include "raster/core/interpolation.h"

#include <algorithm>

#include "raster/datapath/attribute_interpolator.h"
#include "raster/datapath/batch.h"

namespace tessera::raster {

namespace {

// The plane's exact sums at the fragments into scratch.value (its output
// conversion into scratch.output).
void plane_values(const AttributePlane& plane, const int32_t* dx, const int32_t* dy, unsigned count,
                  InterpolationScratch& scratch) {
  attribute_batch(plane, dx, dy, count, {scratch.value.data(), nullptr, nullptr, scratch.output.data()});
}

// Batch kernels (raster/datapath/batch.h) of the perspective division.

// refined_reciprocal of max(q, 1) with Method 3's seed, whose operand (the
// top 14 bits of the normalised q) is never 0.
struct InverseQKernel {
  TESSERA_BATCH_KERNEL void run(const int64_t* q, unsigned count, uint64_t* y, int64_t* n) { loop(q, count, y, n); }
  TESSERA_BATCH_KERNEL void loop(const int64_t* __restrict q, unsigned count, uint64_t* __restrict y,
                                 int64_t* __restrict n) {
    constexpr unsigned BITS = refined_detail::operand_bits(RecipMethod::method3);
    for (unsigned i = 0; i < count; ++i) {
      const refined_detail::Normalised norm = refined_detail::normalise(uint64_t(std::max<int64_t>(q[i], 1)));
      const uint32_t seed = method3_fields(uint32_t(norm.f_q30 >> (30 - BITS))).q5_16;
      y[i] = refined_detail::newton(norm.f_q30, uint64_t{seed} << (10 + BITS));
      n[i] = norm.n;
    }
  }
};

// Channel `channel` of the perspective colours: divide(value, 1/q, false,
// -24) and the interpolator's output rule, in 64 bits (a lane whose
// quotient needs 128 bits, refined_detail::small_quotient, is done again
// by divide itself after the loop).
struct PerspectiveChannelKernel {
  TESSERA_BATCH_KERNEL void run(const int64_t* value, const uint64_t* y, const int64_t* n, unsigned count,
                                unsigned channel, uint32_t* rgba, uint32_t* large) {
    *large = loop(value, y, n, count, channel, rgba);
  }
  // Returns nonzero when a lane's quotient is not small.
  TESSERA_BATCH_KERNEL uint32_t loop(const int64_t* __restrict value, const uint64_t* __restrict y,
                                     const int64_t* __restrict n, unsigned count, unsigned channel,
                                     uint32_t* __restrict rgba) {
    constexpr int64_t SMALL = int64_t{1} << 30;
    uint32_t large = 0;
    for (unsigned i = 0; i < count; ++i) {
      const int64_t shift = 30 + n[i] - int64_t{TEXCOORD_FRACTION_BITS};
      // refined_detail::small_quotient, without int128.
      large |= (value[i] <= -SMALL) | (value[i] >= SMALL) | (y[i] >= (uint64_t{1} << 32)) | (shift < 1) | (shift > 62);
      // Wraps where the quotient is not small; that lane is redone after.
      const auto p = int64_t(uint64_t(value[i]) * y[i]);
      // (p + 2^(shift-1)) >> shift, the same floor without a shifted constant.
      const int64_t c = ((p >> (shift - 1)) + 1) >> 1;
      rgba[i] |= attribute_to_color(attribute_sum{saturate_word(c)}).raw << (8 * channel);
    }
    return large;
  }
};

// 1/q at the fragments into scratch.inv_y and inv_n. 1/w is positive
// inside the triangle; the few pixels just outside an antialiased edge may
// extrapolate it to zero or below, which counts as the smallest positive q.
void inverse_q(const TriangleSetup& ts, const int32_t* dx, const int32_t* dy, unsigned count, RecipMethod method,
               InterpolationScratch& scratch) {
  plane_values(ts.q, dx, dy, count, scratch);
  if (method == RecipMethod::method3) {
    batch_detail::dispatch<InverseQKernel>(best_batch_isa(), static_cast<const int64_t*>(scratch.value.data()), count,
                                           scratch.inv_y.data(), scratch.inv_n.data());
    return;
  }
  for (unsigned i = 0; i < count; ++i) {
    Reciprocal r;
    refined_reciprocal(uint64_t(std::max<int64_t>(scratch.value[i], 1)), method, r);
    scratch.inv_y[i] = r.y;
    scratch.inv_n[i] = r.n;
  }
}

Reciprocal inverse(const InterpolationScratch& scratch, unsigned i) {
  return {scratch.inv_y[i], int(scratch.inv_n[i])};
}

}  // namespace

void interpolated_colors(const TriangleSetup& ts, const int32_t* dx, const int32_t* dy, unsigned count,
                         RecipMethod method, InterpolationScratch& scratch, uint32_t* rgba) {
  if (ts.flat) {  // never in perspective (triangle_setup.cpp)
    std::fill(rgba, rgba + count, ts.flat_color.pack());
    return;
  }
  std::fill(rgba, rgba + count, 0u);
  if (ts.perspective_color) {
    // c = (c/w) / (1/w) per channel, the c/w sum in colour words (16
    // fraction bits, scaled by the normalised q) and q with 24 fraction
    // bits, divided by the refined reciprocal of q into colour words and
    // converted by the interpolator's output rule.
    inverse_q(ts, dx, dy, count, method, scratch);
    for (unsigned ch = 0; ch < 4; ++ch) {
      plane_values(ts.color[ch], dx, dy, count, scratch);
      uint32_t large = 0;
      batch_detail::dispatch<PerspectiveChannelKernel>(
          best_batch_isa(), static_cast<const int64_t*>(scratch.value.data()),
          static_cast<const uint64_t*>(scratch.inv_y.data()), static_cast<const int64_t*>(scratch.inv_n.data()), count,
          ch, rgba, &large);
      for (unsigned i = 0; i < count && large != 0; ++i) {
        const Reciprocal r = inverse(scratch, i);
        if (refined_detail::small_quotient(scratch.value[i], r.y, 30 + r.n - int(TEXCOORD_FRACTION_BITS))) continue;
        const int128 c = divide(scratch.value[i], r, false, -int(TEXCOORD_FRACTION_BITS));
        rgba[i] = (rgba[i] & ~(0xffu << (8 * ch))) | attribute_to_color(attribute_sum{saturate_word(c)}).raw
                                                         << (8 * ch);
      }
    }
    return;
  }
  for (unsigned ch = 0; ch < 4; ++ch) {
    plane_values(ts.color[ch], dx, dy, count, scratch);
    for (unsigned i = 0; i < count; ++i) rgba[i] |= scratch.output[i] << (8 * ch);
  }
}

void interpolated_depths(const TriangleSetup& ts, const int32_t* dx, const int32_t* dy, unsigned count,
                         InterpolationScratch& scratch, uint32_t* depth) {
  attribute_batch(ts.depth, dx, dy, count, {scratch.value.data(), nullptr, nullptr, depth});
}

void interpolated_fogs(const TriangleSetup& ts, const int32_t* dx, const int32_t* dy, unsigned count,
                       RecipMethod method, InterpolationScratch& scratch, int32_t* argument) {
  if (ts.perspective_fog) inverse_q(ts, dx, dy, count, method, scratch);
  plane_values(ts.fog, dx, dy, count, scratch);
  for (unsigned i = 0; i < count; ++i) {
    int128 a = scratch.value[i];
    if (ts.perspective_fog) a = divide(a, inverse(scratch, i), false, -int(TEXCOORD_FRACTION_BITS));
    argument[i] = int32_t(std::clamp<int128>(a, INT32_MIN, INT32_MAX));
  }
}

}  // namespace tessera::raster
