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
//
// Speed: inline and branch-free on packed RGBA words (Rgba8::pack). The
// factor of a code is picked among the candidates by masks (select_code); a
// logic op is its GL truth table (code bit 0: s & d, bit 1: s & ~d, bit 2:
// ~s & d, bit 3: ~s & ~d, checked at compile time), applied to the whole
// word; the write mask is a constexpr table of byte masks. The batch form
// (blend_logic_op_batch, batch.h) takes fragments under one state.
#pragma once

#include <algorithm>
#include <cstdint>

#include "batch.h"
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

// round(a * b / 255) of two 0.8 codes.
constexpr uint32_t mul_unorm8_raw(uint32_t a, uint32_t b) {
  const uint32_t t = a * b + 128;
  return (t + (t >> 8)) >> 8;
}

constexpr unorm8 mul_unorm8(unorm8 a, unorm8 b) {
  return unorm8::from_raw(mul_unorm8_raw(a.raw, b.raw));
}

namespace blend_detail {

constexpr uint32_t broadcast(uint32_t byte) {
  return byte * 0x01010101u;
}

// The byte lanes a colour write mask opens, bit c -> byte c.
struct WriteMasks {
  uint32_t word[16];
};
constexpr WriteMasks make_write_masks() {
  WriteMasks m{};
  for (unsigned mask = 0; mask < 16; ++mask)
    for (unsigned c = 0; c < 4; ++c)
      if ((mask >> c) & 1) m.word[mask] |= 0xffu << (8 * c);
  return m;
}
inline constexpr WriteMasks WRITE_MASKS = make_write_masks();

// All four factors of `factor` as a packed word; codes without an entry
// (11 and above) give ZERO.
constexpr uint32_t factor_word(BlendFactor factor, uint32_t src, uint32_t dst) {
  const uint32_t sa = src >> 24, da = dst >> 24;
  const uint32_t saturate = std::min(sa, 255 - da);
  return select_code<uint32_t>(static_cast<unsigned>(factor), 0, 0, 0xffffffffu, src, ~src, broadcast(sa),
                               ~broadcast(sa), broadcast(da), ~broadcast(da), dst, ~dst,
                               broadcast(saturate) | 0xff000000u);
}

// The GL truth table of `op` on every bit of two words; codes above 15 give 0.
constexpr uint32_t logic_word(LogicOp op, uint32_t s, uint32_t d) {
  const uint32_t code = static_cast<uint32_t>(op) < 16 ? static_cast<uint32_t>(op) : 0;
  const auto term = [code](unsigned bit) { return 0u - ((code >> bit) & 1u); };
  return (term(0) & s & d) | (term(1) & s & ~d) | (term(2) & ~s & d) | (term(3) & ~s & ~d);
}

}  // namespace blend_detail

// The factor for `channel` (0 R, 1 G, 2 B, 3 A).
constexpr unorm8 blend_factor_value(BlendFactor factor, unsigned channel, Rgba8 src, Rgba8 dst) {
  return unorm8::from_raw(blend_detail::factor_word(factor, src.pack(), dst.pack()) >> (8 * channel));
}

constexpr unorm8 apply_logic_op(LogicOp op, unorm8 src, unorm8 dst) {
  return unorm8::from_raw(blend_detail::logic_word(op, src.raw, dst.raw));
}

// Blending on packed words: min(255, mul(S, Fs) + mul(D, Fd)) per channel.
constexpr uint32_t blend_word(BlendFactor src_factor, BlendFactor dst_factor, uint32_t src, uint32_t dst) {
  const uint32_t fs = blend_detail::factor_word(src_factor, src, dst);
  const uint32_t fd = blend_detail::factor_word(dst_factor, src, dst);
  uint32_t out = 0;
  for (unsigned c = 0; c < 32; c += 8) {
    const uint32_t sum =
        mul_unorm8_raw((src >> c) & 0xff, (fs >> c) & 0xff) + mul_unorm8_raw((dst >> c) & 0xff, (fd >> c) & 0xff);
    out |= std::min<uint32_t>(sum, 255) << c;
  }
  return out;
}

constexpr Rgba8 blend_colors(BlendFactor src_factor, BlendFactor dst_factor, Rgba8 src, Rgba8 dst) {
  return Rgba8::unpack(blend_word(src_factor, dst_factor, src.pack(), dst.pack()));
}

// blend_logic_op on packed words.
constexpr uint32_t blend_logic_op_word(const BlendState& state, uint32_t src, uint32_t dst) {
  const uint32_t logic = blend_detail::logic_word(state.op, src, dst);
  const uint32_t blended = blend_word(state.src_factor, state.dst_factor, src, dst);
  // Masks rather than a choice between the words: in a batch the state is
  // the same for every fragment, and the vectoriser takes masks from it,
  // not a select on a scalar condition.
  const uint32_t logic_mask = state.logic_op_enable ? ~0u : 0u;
  const uint32_t blend_mask = state.blend_enable && !state.logic_op_enable ? ~0u : 0u;
  const uint32_t result = (logic & logic_mask) | (blended & blend_mask) | (src & ~(logic_mask | blend_mask));
  const uint32_t write = blend_detail::WRITE_MASKS.word[state.color_mask & COLOR_MASK_ALL];
  return (result & write) | (dst & ~write);
}

// Everything the Verilog unit blend_logic_op.sv computes, in one call.
constexpr Rgba8 blend_logic_op(const BlendState& state, Rgba8 src, Rgba8 dst) {
  return Rgba8::unpack(blend_logic_op_word(state, src.pack(), dst.pack()));
}

// Batch form (batch.h): `count` fragments under one state, colours as
// packed words (Rgba8::pack).
struct BlendKernel {
  TESSERA_BATCH_KERNEL void run(const BlendState& state, const uint32_t* src, const uint32_t* dst, unsigned count,
                                uint32_t* out) {
    loop(state, src, dst, count, out);
  }
  TESSERA_BATCH_KERNEL void loop(const BlendState state, const uint32_t* __restrict src, const uint32_t* __restrict dst,
                                 unsigned count, uint32_t* __restrict out) {
    for (unsigned i = 0; i < count; ++i) out[i] = blend_logic_op_word(state, src[i], dst[i]);
  }
};

void blend_logic_op_batch(const BlendState& state, const uint32_t* src, const uint32_t* dst, unsigned count,
                          uint32_t* out, BatchIsa isa = best_batch_isa());

namespace blend_detail {
constexpr bool logic_ops_match_gl() {
  // clear, and, copy, noop, xor, nand, set on one pair of bytes.
  const uint32_t s = 0xcc, d = 0xaa;
  return (logic_word(LogicOp::clear, s, d) & 0xff) == 0 && (logic_word(LogicOp::and_, s, d) & 0xff) == (s & d) &&
         (logic_word(LogicOp::copy, s, d) & 0xff) == s && (logic_word(LogicOp::noop, s, d) & 0xff) == d &&
         (logic_word(LogicOp::xor_, s, d) & 0xff) == (s ^ d) &&
         (logic_word(LogicOp::nand, s, d) & 0xff) == (~(s & d) & 0xff) &&
         (logic_word(LogicOp::set, s, d) & 0xff) == 0xff;
}
static_assert(logic_ops_match_gl(), "the logic op codes are no longer GL's truth tables");
}  // namespace blend_detail

}  // namespace tessera::raster
