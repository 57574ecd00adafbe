// Blending, logical operation and colour write mask of OpenGL 1.2 /
// OpenGL ES 1.1 (GL 1.2 "Blending", "Logical Operation", "Fine Control of
// Buffer Updates") on RGBA8 (0.8) colour.
//
// Blend factors and logic ops are the codes of common/fixed_function.def
// (BlendFactor, LogicOp), the numbers the Verilog unit's 4-bit fields take;
// the table states each factor and operation. Either factor may be any of
// them (GL restricts SRC_COLOR to the destination factor and DST_COLOR and
// SRC_ALPHA_SATURATE to the source factor; the driver enforces that, the
// datapath defines every combination); a factor code without an entry
// (11..15) acts as ZERO. "1 - x" on a 0.8 code is 255 - x.
//
// Equation ADD only: result = min(255, mul(S, Fs) + mul(D, Fd)) per channel,
// where mul(a, b) = round(a * b / 255) exactly (255 is odd, so there is no
// tie), computed as t = a * b + 128, (t + (t >> 8)) >> 8. Multiplying by ONE
// or by 255 therefore returns the operand unchanged.
//
// Logic ops work on each 8-bit channel.
// With the logic op enabled, blending is bypassed (in GL 1.1 and later an
// enabled RGBA logic op takes the place of blending); with neither, the
// source passes.
//
// Colour write mask: bit 0 R, 1 G, 2 B, 3 A (glColorMask); a masked-off
// channel keeps the destination value. The result is the value to store.
#pragma once

#include <cstdint>

#include "common/fixed_function.h"
#include "fixed_point.h"

namespace tessera::raster {

constexpr uint8_t COLOR_MASK_R = 1;
constexpr uint8_t COLOR_MASK_G = 2;
constexpr uint8_t COLOR_MASK_B = 4;
constexpr uint8_t COLOR_MASK_A = 8;
constexpr uint8_t COLOR_MASK_ALL = 15;

struct BlendState {
  bool blend_enable = false;
  BlendFactor src_factor = BlendFactor::one;
  BlendFactor dst_factor = BlendFactor::zero;
  bool logic_op_enable = false;
  LogicOp op = LogicOp::copy;
  uint8_t color_mask = COLOR_MASK_ALL;
};

// round(a * b / 255).
unorm8 mul_unorm8(unorm8 a, unorm8 b);
// The factor for `channel` (0 R, 1 G, 2 B, 3 A).
unorm8 blend_factor_value(BlendFactor factor, unsigned channel, Rgba8 src, Rgba8 dst);
unorm8 apply_logic_op(LogicOp op, unorm8 src, unorm8 dst);
Rgba8 blend(BlendFactor src_factor, BlendFactor dst_factor, Rgba8 src, Rgba8 dst);

// Everything the Verilog unit blend_logic_op.sv computes, in one call.
Rgba8 blend_logic_op(const BlendState& state, Rgba8 src, Rgba8 dst);

}  // namespace tessera::raster
