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
// loop; the batch form (lod_unit_batch, batch.h) takes the scale factors of
// fragments under one unit's state. Combinational; its Verilog twin is
// rtl_models/raster/lod_unit.sv.
#pragma once

#include <algorithm>
#include <cstdint>

#include "common/fixed_function.h"
#include "raster/datapath/batch.h"

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

// lambda = log2(rho / 2^16) in 1/256, as described above. The leading one
// by a binary search and the squarings unrolled, each step a select: the
// batch form (batch.h) vectorises it.
constexpr int32_t lod_lambda(uint32_t rho) {
  unsigned e = 0;  // leading one's position, 0 .. 31
  e += (rho >> (e + 16)) != 0 ? 16 : 0;
  e += (rho >> (e + 8)) != 0 ? 8 : 0;
  e += (rho >> (e + 4)) != 0 ? 4 : 0;
  e += (rho >> (e + 2)) != 0 ? 2 : 0;
  e += (rho >> (e + 1)) != 0 ? 1 : 0;
  // Mantissa m in [1, 2) as 1.15: the leading one at bit 15.
  uint32_t m = e >= 15 ? rho >> (e - 15) : rho << (15 - e);
  uint32_t fraction = 0;
#pragma GCC unroll 10
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
  const int32_t lambda = (raw + (1 << (cut - 1))) >> cut;  // arithmetic shift: floor, so ties go up
  return rho == 0 ? LOD_LAMBDA_MIN : lambda;
}

// The flags of LodResult as bits of one word.
constexpr uint32_t LOD_MINIFIED = 1;
constexpr uint32_t LOD_LINEAR = 2;
constexpr uint32_t LOD_TWO_LEVELS = 4;

// LodResult in integers, what lod_unit and the batch form share: selects
// on values, no bool or byte array in the result, so that a batch loop
// keeps it in vector registers.
struct LodFields {
  int32_t lambda;
  uint32_t flags;  // LOD_*
  uint32_t level0, level1, weight;
};

constexpr LodFields lod_fields(uint32_t rho, TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap,
                               unsigned last_level) {
  const int32_t lambda = lod_lambda(rho);
  const bool mipmapped = mipmap == TexMipmap::nearest || mipmap == TexMipmap::linear;
  const bool half = mag_filter == TexFilter::linear && min_filter == TexFilter::nearest && mipmapped;
  const uint32_t minified = rho > (half ? LOD_RHO_SQRT2_FLOOR : LOD_RHO_ONE) ? 1u : 0u;
  const uint32_t min_linear = min_filter == TexFilter::linear ? 1u : 0u;
  const uint32_t mag_linear = mag_filter == TexFilter::linear ? 1u : 0u;
  const uint32_t linear = minified != 0 ? min_linear : mag_linear;
  const int32_t q = static_cast<int32_t>(std::min(last_level, LOD_MAX_LEVEL));
  const int32_t l = std::max(lambda, int32_t{0});
  // nearest: (L + 127) >> 8 for L > 128, else 0; at most q.
  const int32_t nearest = std::min(l > 128 ? (l + 127) >> LOD_FRACTION_BITS : 0, q);
  // linear: floor(L) and the next below q, else q alone.
  const bool below_q = l < (q << LOD_FRACTION_BITS);
  const int32_t floor_level = below_q ? l >> LOD_FRACTION_BITS : q;
  const uint32_t weight = below_q ? static_cast<uint32_t>(l & 0xff) : 0u;
  const uint32_t use_nearest = mipmap == TexMipmap::nearest ? minified : 0u;
  const uint32_t use_linear = mipmap == TexMipmap::linear ? minified : 0u;
  const int32_t level0 = use_nearest != 0 ? nearest : (use_linear != 0 ? floor_level : 0);
  const uint32_t level_weight = use_linear != 0 ? weight : 0u;
  const uint32_t two_levels = level_weight != 0 ? 1u : 0u;
  return {lambda, minified * LOD_MINIFIED | linear * LOD_LINEAR | two_levels * LOD_TWO_LEVELS,
          static_cast<uint32_t>(level0), static_cast<uint32_t>(level0) + two_levels, level_weight};
}

// Everything the Verilog unit lod_unit.sv computes, in one call.
constexpr LodResult lod_unit(uint32_t rho, TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap,
                             unsigned last_level) {
  const LodFields f = lod_fields(rho, min_filter, mag_filter, mipmap, last_level);
  LodResult r;
  r.lambda = f.lambda;
  r.minified = (f.flags & LOD_MINIFIED) != 0;
  r.linear = (f.flags & LOD_LINEAR) != 0;
  r.two_levels = (f.flags & LOD_TWO_LEVELS) != 0;
  r.level[0] = static_cast<uint8_t>(f.level0);
  r.level[1] = static_cast<uint8_t>(f.level1);
  r.weight = static_cast<uint8_t>(f.weight);
  return r;
}

// Batch form (batch.h): `count` scale factors under one texture unit's
// filters, mipmap mode and last level, every field of the results in an
// array of its own.
struct LodBatch {
  int32_t* lambda;
  uint32_t* flags;  // LOD_*
  uint32_t* level0;
  uint32_t* level1;
  uint32_t* weight;
};

struct LodKernel {
  TESSERA_BATCH_KERNEL void run(TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap, unsigned last_level,
                                const uint32_t* rho, unsigned count, const LodBatch& out) {
    loop(min_filter, mag_filter, mipmap, last_level, rho, count, out.lambda, out.flags, out.level0, out.level1,
         out.weight);
  }
  TESSERA_BATCH_KERNEL void loop(TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap, unsigned last_level,
                                 const uint32_t* __restrict rho, unsigned count, int32_t* __restrict lambda,
                                 uint32_t* __restrict flags, uint32_t* __restrict level0, uint32_t* __restrict level1,
                                 uint32_t* __restrict weight) {
    for (unsigned i = 0; i < count; ++i) {
      const LodFields r = lod_fields(rho[i], min_filter, mag_filter, mipmap, last_level);
      lambda[i] = r.lambda;
      flags[i] = r.flags;
      level0[i] = r.level0;
      level1[i] = r.level1;
      weight[i] = r.weight;
    }
  }
};

void lod_unit_batch(TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap, unsigned last_level,
                    const uint32_t* rho, unsigned count, const LodBatch& out, BatchIsa isa = best_batch_isa());

}  // namespace tessera::raster
