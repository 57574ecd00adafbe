// See blend_logic_op.h for the factors, the rounding and the GL rules.
#include "blend_logic_op.h"

#include <array>

namespace tessera::raster {

namespace {

std::array<unorm8, 4> channels(Rgba8 c) {
  return {c.r, c.g, c.b, c.a};
}

unorm8 one_minus(unorm8 v) {
  return unorm8::from_raw(255 - v.raw);
}

}  // namespace

unorm8 mul_unorm8(unorm8 a, unorm8 b) {
  const uint32_t t = a.raw * b.raw + 128;
  return unorm8::from_raw((t + (t >> 8)) >> 8);
}

unorm8 blend_factor_value(BlendFactor factor, unsigned channel, Rgba8 src, Rgba8 dst) {
  const unorm8 s = channels(src)[channel];
  const unorm8 d = channels(dst)[channel];
  switch (factor) {
    case BlendFactor::zero: return unorm8{0};
    case BlendFactor::one: return unorm8{255};
    case BlendFactor::src_color: return s;
    case BlendFactor::one_minus_src_color: return one_minus(s);
    case BlendFactor::src_alpha: return src.a;
    case BlendFactor::one_minus_src_alpha: return one_minus(src.a);
    case BlendFactor::dst_alpha: return dst.a;
    case BlendFactor::one_minus_dst_alpha: return one_minus(dst.a);
    case BlendFactor::dst_color: return d;
    case BlendFactor::one_minus_dst_color: return one_minus(d);
    case BlendFactor::src_alpha_saturate:
      return channel == 3 ? unorm8{255} : unorm8{std::min(src.a.raw, one_minus(dst.a).raw)};
  }
  return unorm8{0};  // a code without an entry acts as ZERO
}

unorm8 apply_logic_op(LogicOp op, unorm8 src, unorm8 dst) {
  const uint32_t s = src.raw;
  const uint32_t d = dst.raw;
  uint32_t r = 0;
  switch (op) {
    case LogicOp::clear: r = 0; break;
    case LogicOp::and_: r = s & d; break;
    case LogicOp::and_reverse: r = s & ~d; break;
    case LogicOp::copy: r = s; break;
    case LogicOp::and_inverted: r = ~s & d; break;
    case LogicOp::noop: r = d; break;
    case LogicOp::xor_: r = s ^ d; break;
    case LogicOp::or_: r = s | d; break;
    case LogicOp::nor: r = ~(s | d); break;
    case LogicOp::equiv: r = ~(s ^ d); break;
    case LogicOp::invert: r = ~d; break;
    case LogicOp::or_reverse: r = s | ~d; break;
    case LogicOp::copy_inverted: r = ~s; break;
    case LogicOp::or_inverted: r = ~s | d; break;
    case LogicOp::nand: r = ~(s & d); break;
    case LogicOp::set: r = 0xff; break;
  }
  return unorm8::from_raw(r);
}

Rgba8 blend(BlendFactor src_factor, BlendFactor dst_factor, Rgba8 src, Rgba8 dst) {
  const auto s = channels(src);
  const auto d = channels(dst);
  std::array<unorm8, 4> out{};
  for (unsigned c = 0; c < 4; ++c) {
    const uint32_t sum = mul_unorm8(s[c], blend_factor_value(src_factor, c, src, dst)).raw +
                         mul_unorm8(d[c], blend_factor_value(dst_factor, c, src, dst)).raw;
    out[c] = unorm8::from_raw(std::min<uint32_t>(sum, 255));
  }
  return {out[0], out[1], out[2], out[3]};
}

Rgba8 blend_logic_op(const BlendState& state, Rgba8 src, Rgba8 dst) {
  std::array<unorm8, 4> result = channels(src);
  if (state.logic_op_enable) {
    const auto s = channels(src);
    const auto d = channels(dst);
    for (unsigned c = 0; c < 4; ++c) {
      result[c] = apply_logic_op(state.op, s[c], d[c]);
    }
  } else if (state.blend_enable) {
    result = channels(blend(state.src_factor, state.dst_factor, src, dst));
  }
  const auto d = channels(dst);
  for (unsigned c = 0; c < 4; ++c) {
    if (((state.color_mask >> c) & 1) == 0) {
      result[c] = d[c];
    }
  }
  return {result[0], result[1], result[2], result[3]};
}

}  // namespace tessera::raster
