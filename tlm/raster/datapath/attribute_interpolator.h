// Attribute interpolator: linear interpolation of colour, depth and texture
// coordinates over the triangle from the plane equations of triangle setup.
//
// Source: Crisu et al., "Design Tradeoffs for an Embedded OpenGL-Compliant
// Hardware Rasterizer", Section III-B: setup computes a start value at a
// reference pixel and x/y gradients; the rasterizer then needs one addition
// per attribute and step.
//
// One datapath serves every attribute; `kind` only selects the output
// conversion. Start value and gradients are signed 40-bit words whose
// fraction depends on the kind (the value is in units of the output code so
// that the conversion is a rounding shift and a clamp):
//   color     color_attr    q23.16  one 0.8 colour code = 2^16; 16 fraction
//                                   bits keep Gouraud steps of 1/256 code
//                                   exact over a 511-pixel span
//   depth     depth_attr    q31.8   one 0.24 depth code = 2^8 (8 bits beyond
//                                   the depth buffer's LSB)
//   texcoord  texcoord_attr q15.24  s or t, 1.0 = one texture repetition;
//                                   8 bits beyond the q15.16 output
// The 40-bit range leaves room for values extrapolated outside the triangle
// (the reference pixel may be a tile corner): +-2^23 colour codes,
// +-128 depth ranges, +-32768 texture repetitions.
//
// Value at a pixel offset (dx, dy) from the reference pixel, dx and dy
// signed 10-bit (-512..511):
//     A = start + grad_x * dx + grad_y * dy
// computed exactly in a signed 51-bit accumulator (attribute_sum):
// |A| <= 2^39 + 2 * 2^39 * 2^9 < 2^50. Stepping adds grad_x (next pixel in
// x) or grad_y (next row) to the accumulator and so equals direct evaluation
// exactly; nothing is rounded before the output conversion.
//
// Output conversion (attribute_output), rounding to nearest with ties
// towards +infinity ((A + half) >> shift, arithmetic), then clamping:
//   color     (A + 2^15) >> 16, clamped to [0, 255]           -> unorm8
//   depth     (A + 2^7) >> 8,   clamped to [0, 2^24 - 1]      -> unorm24
//   texcoord  (A + 2^7) >> 8,   clamped to [-2^31, 2^31 - 1]  -> q15_16
// returned as the raw 32-bit port value (q15_16 in two's complement).
// An undefined kind code (3) gives 0, as the Verilog unit's default branch.
//
// Speed: every function is inline; the output conversion takes its shift
// and clamp bounds from a four-entry table indexed by the kind (the
// undefined kind clamps to [0, 0]), so it has no branch. The batch form
// (attribute_batch, batch.h) evaluates one plane at any set of offsets.
#pragma once

#include <cstdint>

#include "batch.h"
#include "fixed_point.h"

namespace tessera::raster {

enum class AttributeKind : uint8_t { color = 0, depth = 1, texcoord = 2 };

using color_attr = SFixed<40, 16>;
using depth_attr = SFixed<40, 8>;
using texcoord_attr = SFixed<40, 24>;
using attribute_sum = SFixed<51, 0>;  // the kind's fraction, wider integer part

// Raw 40-bit words in the fraction of `kind` (see above).
struct AttributePlane {
  AttributeKind kind = AttributeKind::color;
  int64_t start = 0;
  int64_t grad_x = 0;
  int64_t grad_y = 0;
};

struct AttributeEvaluation {
  attribute_sum value;         // at (dx, dy)
  attribute_sum value_next_x;  // at (dx + 1, dy), by adding grad_x
  attribute_sum value_next_y;  // at (dx, dy + 1), by adding grad_y
  uint32_t output = 0;         // attribute_output(kind, value)
};

constexpr int ATTRIBUTE_OFFSET_MIN = -512;
constexpr int ATTRIBUTE_OFFSET_MAX = 511;

constexpr int64_t attribute_word40(int64_t v) {
  return sign_extend(static_cast<uint64_t>(v), 40);
}

// Cuts the plane's words to 40 bits, as the input registers would.
constexpr AttributePlane attribute_plane_from_raw(AttributeKind kind, int64_t start, int64_t grad_x, int64_t grad_y) {
  return AttributePlane{kind, attribute_word40(start), attribute_word40(grad_x), attribute_word40(grad_y)};
}

constexpr attribute_sum attribute_at(const AttributePlane& plane, int dx, int dy) {
  return attribute_sum::from_raw(attribute_word40(plane.start) + attribute_word40(plane.grad_x) * dx +
                                 attribute_word40(plane.grad_y) * dy);
}

constexpr attribute_sum attribute_step_x(const AttributePlane& plane, attribute_sum value) {
  return attribute_sum::from_raw(value.raw + attribute_word40(plane.grad_x));
}

constexpr attribute_sum attribute_step_y(const AttributePlane& plane, attribute_sum value) {
  return attribute_sum::from_raw(value.raw + attribute_word40(plane.grad_y));
}

constexpr unorm8 attribute_to_color(attribute_sum value) {
  return unorm8::from_raw(static_cast<uint32_t>(clamp_i64(round_shift_right(value.raw, 16), 0, 255)));
}

constexpr unorm24 attribute_to_depth(attribute_sum value) {
  return unorm24::from_raw(static_cast<uint32_t>(clamp_i64(round_shift_right(value.raw, 8), 0, 0xffffff)));
}

constexpr q15_16 attribute_to_texcoord(attribute_sum value) {
  return q15_16{clamp_i64(round_shift_right(value.raw, 8), q15_16::MIN_RAW, q15_16::MAX_RAW)};
}

// The output conversion of each kind code: the rounding shift and the clamp.
struct AttributeOutputRule {
  unsigned shift;
  int64_t min, max;
};
inline constexpr AttributeOutputRule ATTRIBUTE_OUTPUT_RULES[4] = {
    {16, 0, 255},                           // color
    {8, 0, 0xffffff},                       // depth
    {8, q15_16::MIN_RAW, q15_16::MAX_RAW},  // texcoord
    {8, 0, 0},                              // undefined: 0
};

constexpr uint32_t attribute_output(AttributeKind kind, attribute_sum value) {
  const AttributeOutputRule& rule = ATTRIBUTE_OUTPUT_RULES[static_cast<unsigned>(kind) & 3];
  const bool defined = static_cast<unsigned>(kind) < 3;
  return static_cast<uint32_t>(clamp_i64(round_shift_right(value.raw, rule.shift), rule.min, rule.max)) &
         (defined ? ~uint32_t{0} : 0);
}

// Everything the Verilog unit attr_interp.sv computes, in one call.
constexpr AttributeEvaluation evaluate_attribute(const AttributePlane& plane, int dx, int dy) {
  AttributeEvaluation r;
  r.value = attribute_at(plane, dx, dy);
  r.value_next_x = attribute_step_x(plane, r.value);
  r.value_next_y = attribute_step_y(plane, r.value);
  r.output = attribute_output(plane.kind, r.value);
  return r;
}

// Batch form (batch.h): `count` offsets (dx[i], dy[i]), each in
// -512..511, on one plane, everything evaluate_attribute gives, each field
// in an array of its own; value_next_x and value_next_y may be null when
// not wanted. Each offset is evaluated directly, as the unit does (equal to
// stepping, above), so a batch may hold any set of fragments: the rows of a
// triangle, or only those that passed the tests.
struct AttributeBatch {
  int64_t* value;
  int64_t* value_next_x;  // null: not computed
  int64_t* value_next_y;  // null: not computed
  uint32_t* output;       // attribute_output(kind, value)
};

struct AttributeKernel {
  TESSERA_BATCH_KERNEL void run(const AttributePlane& plane, const int32_t* dx, const int32_t* dy, unsigned count,
                                const AttributeBatch& out) {
    loop(plane.kind, attribute_word40(plane.start), attribute_word40(plane.grad_x), attribute_word40(plane.grad_y), dx,
         dy, count, out.value, out.value_next_x, out.value_next_y, out.output);
  }
  TESSERA_BATCH_KERNEL void loop(AttributeKind kind, int64_t start, int64_t grad_x, int64_t grad_y,
                                 const int32_t* __restrict dx, const int32_t* __restrict dy, unsigned count,
                                 int64_t* __restrict value, int64_t* __restrict value_next_x,
                                 int64_t* __restrict value_next_y, uint32_t* __restrict output) {
    const AttributePlane plane{kind, start, grad_x, grad_y};
    for (unsigned i = 0; i < count; ++i) {
      const attribute_sum v = attribute_at(plane, dx[i], dy[i]);
      value[i] = v.raw;
      output[i] = attribute_output(kind, v);
    }
    if (value_next_x != nullptr)
      for (unsigned i = 0; i < count; ++i) value_next_x[i] = attribute_step_x(plane, attribute_sum{value[i]}).raw;
    if (value_next_y != nullptr)
      for (unsigned i = 0; i < count; ++i) value_next_y[i] = attribute_step_y(plane, attribute_sum{value[i]}).raw;
  }
};

void attribute_batch(const AttributePlane& plane, const int32_t* dx, const int32_t* dy, unsigned count,
                     const AttributeBatch& out, BatchIsa isa = best_batch_isa());

}  // namespace tessera::raster
