// Texture coordinates as the array back ends' set-up takes them: the
// floats s x width (or t x height) of a triangle's three vertices as
// integers in 1/4096 texel, for the 32-bit integer planes of ap-tile's and
// ap-pixel's set-up (tile_setup.cpp, pixel_setup.cpp).
//
// The set-up's codes wrap every 2^period_log2 units (ap-tile's 8.8 texels
// every 256 texels, 2^20 here; ap-pixel's 16.8 every 2^16 texels, 2^28), so
// vertex 0's whole periods are taken from all three: vertex 0 lands in
// [0, 2^period_log2] and the plane moves by whole periods, which the codes
// do not see. A vertex more than 2^29 units (2^17 texels) from there is
// moved to it: every value then stays within +-2^29 and the differences
// within 2^30, so their products with the set-up's 2^30 barycentric
// numerators stay below 2^60.
//
// The scale (the texture's size times 4096) is a power of two for the
// textures the arrays wrap, so the float product is exact; it is rounded to
// a whole number (nearest, halves away from zero) and split into whole
// periods and the rest. Single-precision float only (soft float on the
// ARM922T: a few multiplies, adds, floorf and 32-bit conversions per
// vertex), no double and no 64-bit conversion.
#pragma once

#include <cmath>
#include <cstdint>

namespace tessera::renderers {

// values[i] x scale, in 1/4096 texel when scale is the texture's size x
// 4096, into out[3] as described above. A value that is not finite counts
// as the most negative one kept (2^40 units).
inline void texel_fixed(const float values[3], float scale, unsigned period_log2, int32_t out[3]) {
  constexpr float LIMIT = 1099511627776.0f;  // 2^40: whole periods fit 32 bits
  const auto period = static_cast<float>(uint32_t{1} << period_log2);
  const int32_t max_whole = (int32_t{1} << (29 - period_log2)) - 1;
  int32_t first_whole = 0;
  for (unsigned i = 0; i < 3; ++i) {
    float value = values[i] * scale;
    if (!(value > -LIMIT)) value = -LIMIT;  // also NaN
    if (value > LIMIT) value = LIMIT;
    // |value| as whole periods and the rest, both exact (the rest is at
    // most |value|, a multiple of its last place), the rest rounded to a
    // whole number: from 2^23 up a float is one already, below its last
    // place is at most 1/2, so adding 1/2 is exact. Only 32-bit
    // conversions (__aeabi_f2iz): libgcc's float to 64-bit conversion
    // goes through double.
    const float magnitude = value < 0 ? -value : value;
    const float whole = std::floor(magnitude * (1.0f / period));  // a power of two: exact
    const float rest = magnitude - whole * period;
    const auto rest_rounded = static_cast<int32_t>(rest >= 8388608.0f ? rest : std::floor(rest + 0.5f));
    auto periods = static_cast<int32_t>(whole);
    int32_t part = rest_rounded;
    if (value < 0 && part > 0) {  // -(whole P + part) = -(whole + 1) P + (P - part)
      periods = -periods - 1;
      part = static_cast<int32_t>(period) - part;
    } else if (value < 0) {
      periods = -periods;
    }
    if (i == 0) first_whole = periods;
    int32_t relative = periods - first_whole;
    if (relative > max_whole) relative = max_whole;
    if (relative < -max_whole) relative = -max_whole;
    out[i] = relative * static_cast<int32_t>(period) + part;
  }
}

}  // namespace tessera::renderers
