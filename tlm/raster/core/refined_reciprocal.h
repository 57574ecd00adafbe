// Division in triangle setup and in the per-pixel perspective division: the
// reciprocal unit's seed for the top bits of the normalised divisor, refined
// by two Newton-Raphson steps y <- y (2 - f y) to about 2^-28 whatever the
// method (README.md, "Reciprocal of the area"), and a quotient as one
// multiplication by the refined reciprocal, rounded to nearest, ties up.
// Inline: the shader divides per fragment (the leading-one detector is a
// count of leading zeros, the seed the inline Method 3).
#pragma once

#include <cstdint>

#include "raster/datapath/reciprocal.h"

namespace tessera::raster {

__extension__ typedef __int128 int128;

// 1/v = y * 2^-(30 + n), y in Q30.
struct Reciprocal {
  uint64_t y = 0;
  int n = 0;
};

namespace refined_detail {

constexpr unsigned NEWTON_STEPS = 2;

// A positive integer as f * 2^n with f in [1/2, 1), f held in Q30 (a
// leading-one detector and a shifter).
struct Normalised {
  uint64_t f_q30 = 0;
  int n = 0;
};

inline Normalised normalise(uint64_t v) {
  const int n = v == 0 ? 0 : 64 - __builtin_clzll(v);  // the bit length of v
  // Both shifts with their counts cut to 0..63, then a select: the batch
  // form's loop computes both in every lane (the one not taken is unused).
  const uint64_t up = v << ((30 - n) & 63), down = v >> ((n - 30) & 63);
  return {n <= 30 ? up : down, n};
}

// Two Newton-Raphson steps y <- y (2 - f y) in Q30 from the seed y.
inline uint64_t newton(uint64_t f_q30, uint64_t y) {
  for (unsigned step = 0; step < NEWTON_STEPS; ++step) {
    const uint64_t fy = (f_q30 * y) >> 30;
    const uint64_t two = uint64_t{1} << 31;
    y = (y * (fy >= two ? 0 : two - fy)) >> 30;
  }
  return y;
}

// The operand bits the unit gets of the normalised divisor: Method 1 is a
// fixed-point table, accurate for small operands only: it gets X in
// [8, 16); the floating-point tables get X in [512, 1024).
constexpr unsigned operand_bits(RecipMethod method) {
  return method == RecipMethod::method1 ? 8 : 14;
}

}  // namespace refined_detail

// 1/v for v > 0; false when the unit flags its operand (v = 0).
inline bool refined_reciprocal(uint64_t v, RecipMethod method, Reciprocal& out) {
  const refined_detail::Normalised norm = refined_detail::normalise(v);
  const unsigned operand_bits = refined_detail::operand_bits(method);
  const auto operand = static_cast<uint16_t>(norm.f_q30 >> (30 - operand_bits));
  const ReciprocalResult seed = reciprocal(v == 0 ? 0 : operand, method);
  if (seed.invalid_operand) return false;
  // The seed as Q30 of 1/f, refined.
  out = {refined_detail::newton(norm.f_q30, uint64_t{seed.q5_16} << (10 + operand_bits)), norm.n};
  return true;
}

namespace refined_detail {

// The quotients whose product, rounding and shift fit in 64 bits (|p| <
// 2^62, half < 2^61) and so give the same bits as the 128-bit path: the
// per-fragment ones (colour, fog and texture words over q) have such small
// numerators.
inline bool small_quotient(int128 numerator, uint64_t y, int shift) {
  constexpr int64_t SMALL = int64_t{1} << 30;
  return numerator > -SMALL && numerator < SMALL && y < (uint64_t{1} << 32) && shift >= 1 && shift <= 62;
}

}  // namespace refined_detail

// numerator / v, with r = 1/v and v's sign given apart, scaled by
// 2^-extra_shift.
inline int128 divide(int128 numerator, const Reciprocal& r, bool negative_divisor, int extra_shift = 0) {
  const int shift = 30 + r.n + extra_shift;
  // The per-fragment quotients (colour and texture words over q) have small
  // numerators: then the product, its rounding and the shift fit in 64 bits
  // (|p| < 2^62, half < 2^61) and give the same bits as the 128-bit path.
  if (refined_detail::small_quotient(numerator, r.y, shift)) {
    int64_t p = int64_t(numerator) * int64_t(r.y);
    if (negative_divisor) p = -p;
    return (p + (int64_t{1} << (shift - 1))) >> shift;
  }
  int128 p = numerator * int128(r.y);
  if (negative_divisor) p = -p;
  return (p + (int128{1} << (shift - 1))) >> shift;
}

}  // namespace tessera::raster
