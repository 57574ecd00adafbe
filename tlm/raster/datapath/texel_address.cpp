// See texel_address.h for the GL rules, formats and rounding.
#include "texel_address.h"

namespace tessera::raster {

namespace {

constexpr int64_t HALF_TEXEL = int64_t{1} << 15;

unsigned saturate_log2(unsigned log2_size) {
  return log2_size > TEXTURE_MAX_LOG2 ? TEXTURE_MAX_LOG2 : log2_size;
}

}  // namespace

TexelAxis texel_axis_for(q15_16 coord, unsigned log2_size, TexWrap wrap, TexFilter filter) {
  const unsigned log2n = saturate_log2(log2_size);
  const int64_t size = int64_t{1} << log2n;
  const bool clamp = wrap == TexWrap::clamp_to_edge;
  const bool linear = filter == TexFilter::linear;

  int64_t u = coord.raw * size;  // exact: |s| < 2^31, size <= 2^8
  if (clamp) {
    u = clamp_i64(u, HALF_TEXEL, (size << 16) - HALF_TEXEL);
  }
  const int64_t v = linear ? u - HALF_TEXEL : u;
  int64_t i0 = v >> 16;  // floor
  int64_t i1 = linear ? i0 + 1 : i0;
  if (clamp) {
    i1 = std::min(i1, size - 1);
  } else {
    i0 &= size - 1;
    i1 &= size - 1;
  }
  TexelAxis axis;
  axis.index0 = static_cast<uint8_t>(i0);
  axis.index1 = static_cast<uint8_t>(i1);
  axis.weight = linear ? static_cast<uint8_t>((v >> 8) & 0xff) : 0;
  return axis;
}

uint32_t texel_address(uint32_t base, unsigned log2_width, uint8_t i, uint8_t j) {
  const uint32_t texel = (uint32_t{j} << saturate_log2(log2_width)) + i;
  return base + texel * 4;
}

TexelFootprint texel_lookup(const TextureState& state, q15_16 s, q15_16 t) {
  TexelFootprint f;
  f.s = texel_axis_for(s, state.log2_width, state.wrap_s, state.filter);
  f.t = texel_axis_for(t, state.log2_height, state.wrap_t, state.filter);
  f.address = {texel_address(state.base, state.log2_width, f.s.index0, f.t.index0),
               texel_address(state.base, state.log2_width, f.s.index1, f.t.index0),
               texel_address(state.base, state.log2_width, f.s.index0, f.t.index1),
               texel_address(state.base, state.log2_width, f.s.index1, f.t.index1)};
  return f;
}

}  // namespace tessera::raster
