// See refined_reciprocal.h.
#include "raster/core/refined_reciprocal.h"

namespace tessera::raster {

namespace {

constexpr unsigned NEWTON_STEPS = 2;

// A positive integer as f * 2^n with f in [1/2, 1), f held in Q30 (a
// leading-one detector and a shifter).
struct Normalised {
  uint64_t f_q30 = 0;
  int n = 0;
};

Normalised normalise(uint64_t v) {
  int n = 0;
  while (n < 64 && (v >> n) != 0) ++n;
  return {n <= 30 ? v << (30 - n) : v >> (n - 30), n};
}

}  // namespace

bool refined_reciprocal(uint64_t v, RecipMethod method, Reciprocal& out) {
  const Normalised norm = normalise(v);
  // Method 1 is a fixed-point table, accurate for small operands only: it
  // gets X in [8, 16); the floating-point tables get X in [512, 1024).
  const unsigned operand_bits = method == RecipMethod::method1 ? 8 : 14;
  const auto operand = static_cast<uint16_t>(norm.f_q30 >> (30 - operand_bits));
  const ReciprocalResult seed = reciprocal(v == 0 ? 0 : operand, method);
  if (seed.invalid_operand) return false;
  uint64_t y = uint64_t{seed.q5_16} << (10 + operand_bits);  // Q30 of 1/f
  for (unsigned step = 0; step < NEWTON_STEPS; ++step) {
    const uint64_t fy = (norm.f_q30 * y) >> 30;
    const uint64_t two = uint64_t{1} << 31;
    y = (y * (fy >= two ? 0 : two - fy)) >> 30;
  }
  out = {y, norm.n};
  return true;
}

int128 divide(int128 numerator, const Reciprocal& r, bool negative_divisor, int extra_shift) {
  const int shift = 30 + r.n + extra_shift;
  int128 p = numerator * int128(r.y);
  if (negative_divisor) p = -p;
  return (p + (int128{1} << (shift - 1))) >> shift;
}

}  // namespace tessera::raster
