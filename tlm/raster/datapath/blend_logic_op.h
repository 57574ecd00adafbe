// Blending, logical operation and colour write mask of OpenGL 1.2 /
// OpenGL ES 1.1 (GL 1.2 "Blending", "Logical Operation", "Fine Control of
// Buffer Updates") on RGBA8 (0.8) colour.
//
// Blend factors (GL enum values): ZERO 0, ONE 1, SRC_COLOR 0x0300,
// ONE_MINUS_SRC_COLOR 0x0301, SRC_ALPHA 0x0302, ONE_MINUS_SRC_ALPHA 0x0303,
// DST_ALPHA 0x0304, ONE_MINUS_DST_ALPHA 0x0305, DST_COLOR 0x0306,
// ONE_MINUS_DST_COLOR 0x0307, SRC_ALPHA_SATURATE 0x0308. Either factor may
// be any of them (GL 1.2 restricts SRC_COLOR to the destination factor and
// SRC_ALPHA_SATURATE to the source factor; the driver enforces that, the
// datapath defines every combination). SRC_ALPHA_SATURATE is
// (f, f, f, 1) with f = min(As, 1 - Ad). "1 - x" on a 0.8 code is 255 - x.
// Hardware code of a factor: ZERO 0, ONE 1, then the enum minus 0x0300 plus
// 2 (2..10); codes 11..15 are undefined and act as ZERO (an unknown enum
// gets code 15).
//
// Equation ADD only: result = min(255, mul(S, Fs) + mul(D, Fd)) per channel,
// where mul(a, b) = round(a * b / 255) exactly (255 is odd, so there is no
// tie), computed as t = a * b + 128, (t + (t >> 8)) >> 8. Multiplying by ONE
// or by 255 therefore returns the operand unchanged.
//
// Logic op (GL enum CLEAR 0x1500 .. SET 0x150F, hardware code = enum -
// 0x1500) on each 8-bit channel, s = source, d = destination:
//   CLEAR 0, AND s&d, AND_REVERSE s&~d, COPY s, AND_INVERTED ~s&d, NOOP d,
//   XOR s^d, OR s|d, NOR ~(s|d), EQUIV ~(s^d), INVERT ~d, OR_REVERSE s|~d,
//   COPY_INVERTED ~s, OR_INVERTED ~s|d, NAND ~(s&d), SET all ones.
// With the logic op enabled, blending is bypassed (in GL 1.1 and later an
// enabled RGBA logic op takes the place of blending); with neither, the
// source passes.
//
// Colour write mask: bit 0 R, 1 G, 2 B, 3 A (glColorMask); a masked-off
// channel keeps the destination value. The result is the value to store.
#pragma once

#include <cstdint>

#include "fixed_point.h"

namespace tessera::raster {

enum class BlendFactor : uint16_t {
  ZERO = 0x0000,
  ONE = 0x0001,
  SRC_COLOR = 0x0300,
  ONE_MINUS_SRC_COLOR = 0x0301,
  SRC_ALPHA = 0x0302,
  ONE_MINUS_SRC_ALPHA = 0x0303,
  DST_ALPHA = 0x0304,
  ONE_MINUS_DST_ALPHA = 0x0305,
  DST_COLOR = 0x0306,
  ONE_MINUS_DST_COLOR = 0x0307,
  SRC_ALPHA_SATURATE = 0x0308,
};

enum class LogicOp : uint16_t {
  CLEAR = 0x1500,
  AND = 0x1501,
  AND_REVERSE = 0x1502,
  COPY = 0x1503,
  AND_INVERTED = 0x1504,
  NOOP = 0x1505,
  XOR = 0x1506,
  OR = 0x1507,
  NOR = 0x1508,
  EQUIV = 0x1509,
  INVERT = 0x150A,
  OR_REVERSE = 0x150B,
  COPY_INVERTED = 0x150C,
  OR_INVERTED = 0x150D,
  NAND = 0x150E,
  SET = 0x150F,
};

constexpr uint8_t COLOR_MASK_R = 1;
constexpr uint8_t COLOR_MASK_G = 2;
constexpr uint8_t COLOR_MASK_B = 4;
constexpr uint8_t COLOR_MASK_A = 8;
constexpr uint8_t COLOR_MASK_ALL = 15;

struct BlendState {
  bool blend_enable = false;
  BlendFactor src_factor = BlendFactor::ONE;
  BlendFactor dst_factor = BlendFactor::ZERO;
  bool logic_op_enable = false;
  LogicOp op = LogicOp::COPY;
  uint8_t color_mask = COLOR_MASK_ALL;
};

// Hardware encodings (the Verilog unit's 4-bit fields).
uint8_t blend_factor_code(BlendFactor factor);
uint8_t logic_op_code(LogicOp op);

// round(a * b / 255).
unorm8 mul_unorm8(unorm8 a, unorm8 b);
// The factor for `channel` (0 R, 1 G, 2 B, 3 A).
unorm8 blend_factor_value(BlendFactor factor, unsigned channel, Rgba8 src, Rgba8 dst);
unorm8 apply_logic_op(LogicOp op, unorm8 src, unorm8 dst);
Rgba8 blend(BlendFactor src_factor, BlendFactor dst_factor, Rgba8 src, Rgba8 dst);

// Everything the Verilog unit blend_logic_op.sv computes, in one call.
Rgba8 blend_logic_op(const BlendState& state, Rgba8 src, Rgba8 dst);

}  // namespace tessera::raster
