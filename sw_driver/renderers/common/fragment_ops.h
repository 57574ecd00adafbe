// Per-fragment operations on RGBA8 and packed pixel words that the software
// back ends share (arm in its span loop, ap-pixel and ap-object when they
// write the pixels the array shaded or walked): blending with 0.8 factors
// rounded to nearest exactly, and logic ops; and a pixel's colour written
// through them and the colour mask (ap-pixel and ap-object, pixel by pixel).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>

#include "common/pixel_format.h"
#include "costs/host_cost.h"
#include "gl/renderer.h"
#include "host/host_api.h"
#include "renderers/common/texturing.h"

namespace tessera::renderers {

using gl::BlendFactor;
using gl::LogicOp;

// On packed pixel words; the caller masks the result to the format's bits.
inline uint32_t logic_op(LogicOp op, uint32_t s, uint32_t d) {
  switch (op) {
    case LogicOp::clear: return 0;
    case LogicOp::and_: return s & d;
    case LogicOp::and_reverse: return s & ~d;
    case LogicOp::copy: return s;
    case LogicOp::and_inverted: return ~s & d;
    case LogicOp::noop: return d;
    case LogicOp::xor_: return s ^ d;
    case LogicOp::or_: return s | d;
    case LogicOp::nor: return ~(s | d);
    case LogicOp::equiv: return ~(s ^ d);
    case LogicOp::invert: return ~d;
    case LogicOp::or_reverse: return s | ~d;
    case LogicOp::copy_inverted: return ~s;
    case LogicOp::or_inverted: return ~s | d;
    case LogicOp::nand: return ~(s & d);
    case LogicOp::set: return ~0u;
  }
  return 0;  // not reached: every 4-bit code is an operation (fixed_function.def)
}

inline bool logic_op_reads_destination(LogicOp op) {
  return op != LogicOp::clear && op != LogicOp::copy && op != LogicOp::copy_inverted && op != LogicOp::set;
}

inline bool factor_reads_destination(BlendFactor f) {
  return f == BlendFactor::dst_color || f == BlendFactor::one_minus_dst_color || f == BlendFactor::dst_alpha ||
         f == BlendFactor::one_minus_dst_alpha || f == BlendFactor::src_alpha_saturate;
}

// Blend factor for channel c (0..3 = r, g, b, a) as a 0.8 code.
inline uint32_t blend_factor(BlendFactor f, const uint32_t s[4], const uint32_t d[4], int c) {
  switch (f) {
    case BlendFactor::zero: return 0;
    case BlendFactor::one: return 255;
    case BlendFactor::src_color: return s[c];
    case BlendFactor::one_minus_src_color: return 255 - s[c];
    case BlendFactor::dst_color: return d[c];
    case BlendFactor::one_minus_dst_color: return 255 - d[c];
    case BlendFactor::src_alpha: return s[3];
    case BlendFactor::one_minus_src_alpha: return 255 - s[3];
    case BlendFactor::dst_alpha: return d[3];
    case BlendFactor::one_minus_dst_alpha: return 255 - d[3];
    case BlendFactor::src_alpha_saturate: return c == 3 ? 255 : std::min(s[3], 255 - d[3]);
  }
  return 0;
}

inline uint32_t blend(BlendFactor src_factor, BlendFactor dst_factor, uint32_t src, uint32_t dst) {
  const uint32_t s[4] = {src & 0xff, (src >> 8) & 0xff, (src >> 16) & 0xff, src >> 24};
  const uint32_t d[4] = {dst & 0xff, (dst >> 8) & 0xff, (dst >> 16) & 0xff, dst >> 24};
  uint32_t out = 0;
  for (int c = 0; c < 4; ++c) {
    const uint32_t v = mul8(s[c], blend_factor(src_factor, s, d, c)) + mul8(d[c], blend_factor(dst_factor, s, d, c));
    out |= std::min<uint32_t>(v, 255) << (8 * c);
  }
  return out;
}

// The host-cost rows a pixel's colour write charges: `read_back` when it
// reads the destination (blending, a logic op or a partial mask), `blend`
// (if any) when it blends.
struct ColorWriteCosts {
  costs::HostCost read_back;
  std::optional<costs::HostCost> blend;
};

// Writes `rgba` into pixel `offset` of the colour buffer at `color_address`
// (`format`) through the state's colour mask, blending and logic op, as
// GL's per-fragment operations do; nothing when the mask is empty.
inline void write_color(HostApi& host, const gl::RasterState& state, PixelFormat format, uint32_t color_address,
                        uint32_t offset, uint32_t rgba, const ColorWriteCosts& charges) {
  unsigned mask4 = 0;
  for (unsigned ch = 0; ch < 4; ++ch) mask4 |= state.color_mask[ch] ? 1u << ch : 0u;
  const uint32_t write_mask = channel_bits(format, mask4), all = channel_bits(format, 0xf);
  if (write_mask == 0) return;
  const unsigned bpp = bytes_per_pixel(format);
  const uint32_t address = color_address + offset * bpp;
  uint32_t out;
  if (state.blend || state.logic_op || write_mask != all) {
    const uint32_t dst = load_pixel(format, host.load_span(address, bpp, 1));
    costs::charge(host, charges.read_back);
    uint32_t src = rgba;
    if (state.blend) {
      src = blend(state.blend_src, state.blend_dst, src, unpack_pixel(format, dst));
      if (charges.blend) costs::charge(host, *charges.blend);
    }
    out = pack_pixel(format, src);
    if (state.logic_op) out = logic_op(state.logic_op_mode, out, dst) & all;
    out = (out & write_mask) | (dst & ~write_mask);
  } else {
    out = pack_pixel(format, rgba);
  }
  store_pixel(format, host.store_span(address, bpp, 1), out);
}

}  // namespace tessera::renderers
