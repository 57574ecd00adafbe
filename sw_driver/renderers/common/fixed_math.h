// Integer arithmetic for the software back ends' set-up and span code,
// written for the ARM922T (ARMv4T: no FPU, no divide instruction, no CLZ):
// 32-bit values, 32x32->64 products (one UMULL/SMULL), 64-bit adds and
// shifts, at most one 32-bit division (the library's __aeabi_uidiv) per
// reciprocal. No floating point, no 64-bit division, no 128-bit product.
//
// - bit_length: the position of the highest set bit plus one (0 for 0).
// - Reciprocal: 1/d for 1 <= d < 2^62 as a 30-bit mantissa r and a shift,
//   1/d ~ r / 2^shift. d is normalised to m in [2^29, 2^30) (truncating its
//   low bits when it is longer); r = floor(2^59 / m) exactly, from a 16-bit
//   quotient (one 32-bit division), one Newton step and a final correction
//   by the remainder. For d < 2^30, r / 2^shift is floor(2^59 / m) / 2^shift
//   with m = d * 2^k, so it is within 2^-29 (relative) of 1/d and never
//   above it; for longer d, the truncation of d adds at most 2^-29.
// - scaled_quotient(x, R, k): about floor(x * 2^k / d) for a signed 64-bit
//   x. x is cut to its top 31 bits (relative error 2^-30) and multiplied by
//   r (< 2^61), then shifted; the result is within 2^-28 (relative) plus
//   one of the exact quotient, saturated to +-2^62.
// - log2_q16: log2(x) for x >= 1 in 16.16: the leading one's position, then
//   the next 8 bits through a 257-entry table of log2(1 + i/256) and a
//   linear interpolation in the 16 bits after them: within 1 unit of 2^-16 of log2(x)
//   (the table's rounding 0.5 unit, the interpolation at most 0.18).
#pragma once

#include <cstdint>

namespace tessera::renderers {

inline unsigned bit_length(uint32_t x) {
  return x == 0 ? 0u : 32u - static_cast<unsigned>(__builtin_clz(x));
}
inline unsigned bit_length64(uint64_t x) {
  const uint32_t high = static_cast<uint32_t>(x >> 32);
  return high != 0 ? 32u + bit_length(high) : bit_length(static_cast<uint32_t>(x));
}

// floor(2^59 / m) for m in [2^29, 2^30]: at most 2^30.
inline uint32_t reciprocal_2_59(uint32_t m) {
  // 2^45 / ((m >> 14) + 1), an underestimate within 2^-14, scaled to 2^59 / m.
  const uint32_t y0 = (uint32_t{1} << 31) / ((m >> 14) + 1);
  uint32_t x = y0 << 14;  // <= 2^30
  // One Newton step: x += x (2^59 - m x) / 2^59; the error term is below
  // 2^46 (x underestimates), kept to its top 31 bits.
  const int64_t e = (int64_t{1} << 59) - static_cast<int64_t>(uint64_t{m} * x);
  x += static_cast<uint32_t>((uint64_t{x} * static_cast<uint64_t>(e >> 15)) >> 44);
  // Exact by the remainder: 0 <= 2^59 - m x < m.
  int64_t remainder = (int64_t{1} << 59) - static_cast<int64_t>(uint64_t{m} * x);
  while (remainder < 0) {
    --x;
    remainder += m;
  }
  while (remainder >= static_cast<int64_t>(m)) {
    ++x;
    remainder -= m;
  }
  return x;
}

struct Reciprocal {
  uint32_t r = 0;  // in (2^29, 2^30]
  int shift = 0;   // 1/d ~ r / 2^shift
};

// 1 <= d < 2^62.
inline Reciprocal make_reciprocal(uint64_t d) {
  const int n = static_cast<int>(bit_length64(d));
  const uint32_t m = n <= 30 ? static_cast<uint32_t>(d << (30 - n)) : static_cast<uint32_t>(d >> (n - 30));
  return {reciprocal_2_59(m), 29 + n};
}

// About floor(x * 2^k / d), d the divisor of `inverse`; saturated to +-2^62.
inline int64_t scaled_quotient(int64_t x, const Reciprocal& inverse, int k) {
  if (x == 0) return 0;
  const uint64_t magnitude = x < 0 ? uint64_t{0} - static_cast<uint64_t>(x) : static_cast<uint64_t>(x);
  const int length = static_cast<int>(bit_length64(magnitude));
  const int cut = length > 31 ? length - 31 : 0;
  const int64_t top = x >> cut;                                   // |top| < 2^31
  const int64_t product = top * static_cast<int64_t>(inverse.r);  // |product| < 2^61
  const int exponent = k + cut - inverse.shift;
  if (exponent >= 0) {
    const int64_t limit = int64_t{1} << 62;
    if (exponent >= 62 || product >= (limit >> exponent) || product <= -(limit >> exponent))
      return product < 0 ? -limit : limit;
    return product * (int64_t{1} << exponent);
  }
  if (exponent <= -63) return product < 0 ? -1 : 0;
  return product >> -exponent;
}

// log2(x) in 16.16 for x >= 1 (x = 0 gives 0; callers treat it apart).
inline int32_t log2_q16(uint64_t x) {
  static constexpr uint32_t TABLE[257] = {
      0,     369,   736,   1102,  1466,  1829,  2190,  2551,  2909,  3267,  3623,  3978,  4331,  4683,  5034,  5384,
      5732,  6079,  6425,  6769,  7112,  7454,  7795,  8134,  8473,  8810,  9146,  9480,  9814,  10146, 10477, 10807,
      11136, 11464, 11791, 12116, 12440, 12764, 13086, 13407, 13727, 14046, 14363, 14680, 14996, 15310, 15624, 15937,
      16248, 16559, 16868, 17177, 17484, 17791, 18096, 18401, 18704, 19007, 19308, 19609, 19909, 20207, 20505, 20802,
      21098, 21393, 21687, 21980, 22272, 22564, 22854, 23144, 23433, 23720, 24007, 24293, 24579, 24863, 25146, 25429,
      25711, 25992, 26272, 26551, 26830, 27108, 27384, 27660, 27936, 28210, 28484, 28757, 29029, 29300, 29571, 29840,
      30109, 30378, 30645, 30912, 31178, 31443, 31707, 31971, 32234, 32496, 32758, 33019, 33279, 33538, 33797, 34055,
      34312, 34569, 34825, 35080, 35334, 35588, 35841, 36094, 36346, 36597, 36847, 37097, 37346, 37595, 37842, 38090,
      38336, 38582, 38827, 39072, 39316, 39559, 39802, 40044, 40286, 40527, 40767, 41006, 41246, 41484, 41722, 41959,
      42196, 42432, 42667, 42902, 43137, 43370, 43603, 43836, 44068, 44300, 44530, 44761, 44990, 45220, 45448, 45676,
      45904, 46131, 46357, 46583, 46809, 47034, 47258, 47482, 47705, 47928, 48150, 48372, 48593, 48813, 49034, 49253,
      49472, 49691, 49909, 50127, 50344, 50560, 50776, 50992, 51207, 51422, 51636, 51850, 52063, 52276, 52488, 52700,
      52911, 53122, 53332, 53542, 53751, 53960, 54169, 54377, 54584, 54791, 54998, 55204, 55410, 55615, 55820, 56025,
      56229, 56432, 56635, 56838, 57040, 57242, 57443, 57644, 57845, 58045, 58245, 58444, 58643, 58841, 59039, 59237,
      59434, 59631, 59827, 60023, 60219, 60414, 60609, 60803, 60997, 61190, 61384, 61576, 61769, 61961, 62152, 62343,
      62534, 62725, 62915, 63104, 63294, 63483, 63671, 63859, 64047, 64234, 64421, 64608, 64794, 64980, 65166, 65351,
      65536};
  if (x == 0) return 0;
  const int n = static_cast<int>(bit_length64(x)) - 1;
  const uint32_t m = n >= 31 ? static_cast<uint32_t>(x >> (n - 31)) : static_cast<uint32_t>(x << (31 - n));
  const uint32_t index = (m >> 23) & 255, fraction = (m >> 7) & 0xffff;
  const uint32_t t0 = TABLE[index], t1 = TABLE[index + 1];
  return n * 65536 + static_cast<int32_t>(t0 + (((t1 - t0) * fraction + 32768) >> 16));
}

}  // namespace tessera::renderers
