// See blend_logic_op.h for the factors, the rounding and the GL rules.
#include "blend_logic_op.h"

#include <array>

namespace tessera::raster {

namespace {

std::array<unorm8, 4> channels(rgba8 c) { return {c.r, c.g, c.b, c.a}; }

unorm8 one_minus(unorm8 v) { return unorm8::from_raw(255 - v.raw); }

} // namespace

uint8_t blend_factor_code(blend_factor factor) {
    const auto v = static_cast<uint16_t>(factor);
    if (v <= 1) {
        return static_cast<uint8_t>(v);
    }
    if (v >= 0x0300 && v <= 0x0308) {
        return static_cast<uint8_t>(v - 0x0300 + 2);
    }
    return 15;
}

uint8_t logic_op_code(logic_op op) { return static_cast<uint8_t>(static_cast<uint16_t>(op) - 0x1500) & 15; }

unorm8 mul_unorm8(unorm8 a, unorm8 b) {
    const uint32_t t = a.raw * b.raw + 128;
    return unorm8::from_raw((t + (t >> 8)) >> 8);
}

unorm8 blend_factor_value(blend_factor factor, unsigned channel, rgba8 src, rgba8 dst) {
    const unorm8 s = channels(src)[channel];
    const unorm8 d = channels(dst)[channel];
    switch (factor) {
    case blend_factor::ZERO:
        return unorm8{0};
    case blend_factor::ONE:
        return unorm8{255};
    case blend_factor::SRC_COLOR:
        return s;
    case blend_factor::ONE_MINUS_SRC_COLOR:
        return one_minus(s);
    case blend_factor::SRC_ALPHA:
        return src.a;
    case blend_factor::ONE_MINUS_SRC_ALPHA:
        return one_minus(src.a);
    case blend_factor::DST_ALPHA:
        return dst.a;
    case blend_factor::ONE_MINUS_DST_ALPHA:
        return one_minus(dst.a);
    case blend_factor::DST_COLOR:
        return d;
    case blend_factor::ONE_MINUS_DST_COLOR:
        return one_minus(d);
    case blend_factor::SRC_ALPHA_SATURATE:
        return channel == 3 ? unorm8{255} : unorm8{std::min(src.a.raw, one_minus(dst.a).raw)};
    }
    return unorm8{0};
}

unorm8 apply_logic_op(logic_op op, unorm8 src, unorm8 dst) {
    const uint32_t s = src.raw;
    const uint32_t d = dst.raw;
    uint32_t r = 0;
    switch (op) {
    case logic_op::CLEAR:
        r = 0;
        break;
    case logic_op::AND:
        r = s & d;
        break;
    case logic_op::AND_REVERSE:
        r = s & ~d;
        break;
    case logic_op::COPY:
        r = s;
        break;
    case logic_op::AND_INVERTED:
        r = ~s & d;
        break;
    case logic_op::NOOP:
        r = d;
        break;
    case logic_op::XOR:
        r = s ^ d;
        break;
    case logic_op::OR:
        r = s | d;
        break;
    case logic_op::NOR:
        r = ~(s | d);
        break;
    case logic_op::EQUIV:
        r = ~(s ^ d);
        break;
    case logic_op::INVERT:
        r = ~d;
        break;
    case logic_op::OR_REVERSE:
        r = s | ~d;
        break;
    case logic_op::COPY_INVERTED:
        r = ~s;
        break;
    case logic_op::OR_INVERTED:
        r = ~s | d;
        break;
    case logic_op::NAND:
        r = ~(s & d);
        break;
    case logic_op::SET:
        r = 0xff;
        break;
    }
    return unorm8::from_raw(r);
}

rgba8 blend(blend_factor src_factor, blend_factor dst_factor, rgba8 src, rgba8 dst) {
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

rgba8 blend_logic_op(const blend_state& state, rgba8 src, rgba8 dst) {
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

} // namespace tessera::raster
