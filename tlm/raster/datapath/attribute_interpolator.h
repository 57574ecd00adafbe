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
#pragma once

#include <cstdint>

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

// Cuts the plane's words to 40 bits, as the input registers would.
AttributePlane attribute_plane_from_raw(AttributeKind kind, int64_t start, int64_t grad_x, int64_t grad_y);

attribute_sum attribute_at(const AttributePlane& plane, int dx, int dy);
attribute_sum attribute_step_x(const AttributePlane& plane, attribute_sum value);
attribute_sum attribute_step_y(const AttributePlane& plane, attribute_sum value);
uint32_t attribute_output(AttributeKind kind, attribute_sum value);

unorm8 attribute_to_color(attribute_sum value);
unorm24 attribute_to_depth(attribute_sum value);
q15_16 attribute_to_texcoord(attribute_sum value);

// Everything the Verilog unit attr_interp.sv computes, in one call.
AttributeEvaluation evaluate_attribute(const AttributePlane& plane, int dx, int dy);

}  // namespace tessera::raster
