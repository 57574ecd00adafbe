// Level-of-detail unit of the texture sampler: from the scale factor rho of
// a fragment to lambda = log2(rho), the choice between minification and
// magnification, and the mipmap level(s) to sample (OpenGL ES 1.1 sections
// 3.8.8 and 3.8.9, which are GL 1.5's "Texture Minification").
//
// Formats and rules:
//   rho       unsigned 16.16, level 0's texels per pixel along the screen
//             axis that moves fastest (the sampler's max(|du/dx|, |dv/dx|,
//             |du/dy|, |dv/dy|), saturated to 2^16 - 2^-16 by the caller)
//   lambda    signed, 8 fraction bits (1/256), -16 .. 16 (14 bits); rho = 0
//             gives -16 (it is magnified whatever lambda says). Computed as
//             e + log2(m) with e the position of rho's leading one (less 16)
//             and m in [1, 2) its mantissa cut to 16 bits; log2(m) bit by
//             bit by repeated squaring (m^2 >= 2: the bit is 1 and m^2 / 2
//             goes on), 10 bits with each square truncated to 16 bits, then
//             rounded to 8 bits (ties up). Largest error against the exact
//             log2(rho): 0.00202 (0.517 of an 8-bit step: the rounding's 0.5
//             and 0.017 from the cut mantissa and squares), measured over
//             every rho below 2^22 and 2^22 random others
//             (test_raster_lod_unit). No table.
//   c         the switch point (3.8.9): 1/2 when the magnification filter
//             is LINEAR and the minification filter NEAREST_MIPMAP_NEAREST or
//             NEAREST_MIPMAP_LINEAR (within-level NEAREST with a mipmap
//             choice), else 0. Minified when lambda > c, decided exactly on
//             rho: rho > 1 (rho > 2^16) for c = 0, rho > sqrt 2 (rho >= 92682,
//             sqrt 2 * 2^16 = 92681.9) for c = 1/2.
//   filter    the within-level filter: the minification one when minified,
//             else the magnification one.
//   levels    q = last_level. Magnified, or TexMipmap none (or the unknown
//             code 3): level 0. nearest: d = ceil(lambda + 1/2) - 1 for
//             lambda > 1/2, else 0 (in 1/256: (L + 127) >> 8 for L > 128),
//             at most q. linear: q alone for lambda >= q, else levels
//             floor(lambda) and the next with the 8-bit weight frac(lambda)
//             of the second (lambda below 0 taken as 0); a weight of 0
//             samples the first level alone.
// The sampler blends the two levels' filtered texels with texture_env.h's
// bilinear filter (weights w and 0): ((256 - w) a + w b + 128) >> 8.
//
// Speed: inline; the logarithm is a fixed chain of ten 16 x 16 squarings and
// the level choice selects between values, so there is no data-dependent
// loop. Combinational; its Verilog twin is rtl_models/raster/lod_unit.sv.
#pragma once

#include <algorithm>
#include <cstdint>

#include "common/fixed_function.h"

namespace tessera::raster {

constexpr unsigned LOD_FRACTION_BITS = 8;
constexpr int32_t LOD_LAMBDA_MIN = -16 * 256;    // rho = 0 and rho = 2^-16
constexpr uint32_t LOD_RHO_ONE = 1u << 16;       // lambda = 0
constexpr uint32_t LOD_RHO_SQRT2_FLOOR = 92681;  // floor(sqrt 2 * 2^16): lambda = 1/2 lies just above
constexpr unsigned LOD_LOG2_ITERATIONS = 10;     // fraction bits of log2(m) before rounding
constexpr unsigned LOD_MAX_LEVEL = 15;           // the 4-bit last level port

struct LodResult {
  int32_t lambda = LOD_LAMBDA_MIN;  // 1/256
  bool minified = false;
  bool linear = false;        // within-level filter: TexFilter::linear
  uint8_t level[2] = {0, 0};  // level[1] = level[0] + 1 with two levels, else level[0]
  bool two_levels = false;
  uint8_t weight = 0;  // of level[1], 1/256; 0 with one level
};

// lambda = log2(rho / 2^16) in 1/256, as described above.
constexpr int32_t lod_lambda(uint32_t rho) {
  if (rho == 0) return LOD_LAMBDA_MIN;
  unsigned e = 0;  // leading one's position, 0 .. 31
  for (unsigned b = 16; b > 0; b >>= 1)
    if ((rho >> (e + b)) != 0) e += b;
  // Mantissa m in [1, 2) as 1.15: the leading one at bit 15.
  uint32_t m = e >= 15 ? rho >> (e - 15) : rho << (15 - e);
  uint32_t fraction = 0;
  for (unsigned i = 0; i < LOD_LOG2_ITERATIONS; ++i) {
    const uint32_t square = m * m;  // 2.30, below 2^32
    const uint32_t bit = square >> 31;
    fraction = (fraction << 1) | bit;
    m = square >> (15 + bit);  // m^2 or m^2 / 2 as 1.15
  }
  // The integer part times 2^10 plus the fraction (a multiplication: the
  // integer part is negative below rho = 1, and shifting a negative value
  // left is undefined in C++17; the bits are those of the Verilog's
  // concatenation).
  const int32_t raw = (static_cast<int32_t>(e) - 16) * (1 << LOD_LOG2_ITERATIONS) + static_cast<int32_t>(fraction);
  const unsigned cut = LOD_LOG2_ITERATIONS - LOD_FRACTION_BITS;
  return (raw + (1 << (cut - 1))) >> cut;  // arithmetic shift: floor, so ties go up
}

// Everything the Verilog unit lod_unit.sv computes, in one call.
constexpr LodResult lod_unit(uint32_t rho, TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap,
                             unsigned last_level) {
  LodResult r;
  r.lambda = lod_lambda(rho);
  const bool mipmapped = mipmap == TexMipmap::nearest || mipmap == TexMipmap::linear;
  const bool half = mag_filter == TexFilter::linear && min_filter == TexFilter::nearest && mipmapped;
  r.minified = rho > (half ? LOD_RHO_SQRT2_FLOOR : LOD_RHO_ONE);
  r.linear = (r.minified ? min_filter : mag_filter) == TexFilter::linear;
  const int32_t q = static_cast<int32_t>(std::min(last_level, LOD_MAX_LEVEL));
  const int32_t l = std::max(r.lambda, int32_t{0});
  // nearest: (L + 127) >> 8 for L > 128, else 0; at most q.
  const int32_t nearest = std::min(l > 128 ? (l + 127) >> LOD_FRACTION_BITS : 0, q);
  // linear: floor(L) and the next below q, else q alone.
  const bool below_q = l < (q << LOD_FRACTION_BITS);
  const int32_t floor_level = below_q ? l >> LOD_FRACTION_BITS : q;
  const uint8_t weight = below_q ? static_cast<uint8_t>(l & 0xff) : 0;
  const bool use_nearest = r.minified && mipmap == TexMipmap::nearest;
  const bool use_linear = r.minified && mipmap == TexMipmap::linear;
  const int32_t level0 = use_nearest ? nearest : use_linear ? floor_level : 0;
  r.weight = use_linear ? weight : 0;
  r.two_levels = r.weight != 0;
  r.level[0] = static_cast<uint8_t>(level0);
  r.level[1] = static_cast<uint8_t>(level0 + (r.two_levels ? 1 : 0));
  return r;
}

}  // namespace tessera::raster
