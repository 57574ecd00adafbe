// Divisor: exact division by a number fixed for a while (a triangle's
// doubled area, an edge's length), written for the ARM922T, which has no
// divide instruction and no FPU. Making a Divisor costs two 32-bit
// divisions (the C library's __aeabi_uidiv); dividing a 64-bit number by it
// afterwards costs four 32x32->64 multiplies (UMULL) and a few additions,
// with no 64-bit division helper (__aeabi_uldivmod) and no floating point.
//
// The method is Moller and Granlund's, "Improved division by invariant
// integers" (IEEE Trans. Computers 60(2), 2011): the divisor shifted until
// its top bit is set, d, and its reciprocal v = floor((2^64 - 1) / d) -
// 2^32; a two-word by one-word division is then a multiply by v and at most
// two corrections (their algorithm 4). v itself is one such division,
// done once with 16-bit digits as longlong.h's __udiv_qrnnd_c does (Knuth,
// TAOCP vol. 2, 4.3.1, algorithm D with base 2^16).
//
// test_divisor checks every operation against the compiler's 64-bit and
// 128-bit division on random operands of every size.
#pragma once

#include <cstdint>

namespace tessera {

class Divisor {
 public:
  struct Unsigned {
    uint64_t quotient;
    uint32_t remainder;
  };
  struct Floor {
    int64_t quotient;
    uint32_t remainder;  // in [0, divisor)
  };

  // `divisor` >= 1.
  constexpr explicit Divisor(uint32_t divisor)
      : m_divisor(divisor),
        m_shift(leading_zeros(divisor)),
        m_normalised(divisor << m_shift),
        m_reciprocal(reciprocal(m_normalised)) {}

  constexpr uint32_t value() const { return m_divisor; }

  // n / divisor and n % divisor, for any 64-bit n.
  constexpr Unsigned divide(uint64_t n) const {
    // n shifted left as the divisor was: three words n2:n1:n0, n2 < d.
    const auto high = static_cast<uint32_t>(n >> 32), low = static_cast<uint32_t>(n);
    const uint32_t n2 = m_shift == 0 ? 0 : high >> (32 - m_shift);
    const uint32_t n1 = m_shift == 0 ? high : (high << m_shift) | (low >> (32 - m_shift));
    const uint32_t n0 = low << m_shift;
    const Word upper = divide_words(n2, n1);
    const Word lower = divide_words(upper.remainder, n0);
    return {(uint64_t{upper.quotient} << 32) | lower.quotient, lower.remainder >> m_shift};
  }

  // floor(n / divisor) and the remainder n - quotient * divisor, in
  // [0, divisor), for |n| < 2^63.
  constexpr Floor floor_divide(int64_t n) const {
    if (n >= 0) {
      const Unsigned u = divide(static_cast<uint64_t>(n));
      return {static_cast<int64_t>(u.quotient), u.remainder};
    }
    const Unsigned u = divide(static_cast<uint64_t>(-n));
    if (u.remainder == 0) return {-static_cast<int64_t>(u.quotient), 0};
    return {-static_cast<int64_t>(u.quotient) - 1, m_divisor - u.remainder};
  }

  // n / divisor rounded to nearest, halves away from zero (so that
  // round(-x) = -round(x)), for |n| < 2^63 - 2^31.
  constexpr int64_t round_divide(int64_t n) const {
    const uint64_t half = m_divisor / 2;
    if (n >= 0) return static_cast<int64_t>(divide(static_cast<uint64_t>(n) + half).quotient);
    return -static_cast<int64_t>(divide(static_cast<uint64_t>(-n) + half).quotient);
  }

 private:
  struct Word {
    uint32_t quotient, remainder;
  };

  static constexpr unsigned leading_zeros(uint32_t x) {
    unsigned n = 0;
    for (uint32_t bit = 0x80000000u; bit != 0 && (x & bit) == 0; bit >>= 1) ++n;
    return n;
  }

  // (u1 * 2^32 + u0) / d for the normalised d and u1 < d: Moller and
  // Granlund's algorithm 4.
  constexpr Word divide_words(uint32_t u1, uint32_t u0) const {
    const uint64_t product = uint64_t{m_reciprocal} * u1 + ((uint64_t{u1} + 1) << 32) + u0;
    auto q = static_cast<uint32_t>(product >> 32);
    const auto q0 = static_cast<uint32_t>(product);
    uint32_t r = u0 - q * m_normalised;
    if (r > q0) {
      --q;
      r += m_normalised;
    }
    if (r >= m_normalised) {
      ++q;
      r -= m_normalised;
    }
    return {q, r};
  }

  // floor((2^64 - 1) / d) - 2^32 for d >= 2^31: the division
  // ((2^32 - 1 - d) * 2^32 + 2^32 - 1) / d in two 16-bit digits, each
  // estimated by a 32-bit division by d's upper half and corrected at most
  // twice (__udiv_qrnnd_c).
  static constexpr uint32_t reciprocal(uint32_t d) {
    const uint32_t n1 = ~d, n0 = 0xffffffffu;
    const uint32_t d1 = d >> 16, d0 = d & 0xffffu;
    uint32_t q1 = n1 / d1;
    uint32_t r1 = n1 - q1 * d1;
    uint32_t m = q1 * d0;
    r1 = (r1 << 16) | (n0 >> 16);
    if (r1 < m) {
      --q1;
      r1 += d;
      if (r1 >= d && r1 < m) {  // r1 >= d: the addition did not carry
        --q1;
        r1 += d;
      }
    }
    r1 -= m;
    uint32_t q0 = r1 / d1;
    uint32_t r0 = r1 - q0 * d1;
    m = q0 * d0;
    r0 = (r0 << 16) | (n0 & 0xffffu);
    if (r0 < m) {
      --q0;
      r0 += d;
      if (r0 >= d && r0 < m) --q0;
    }
    return (q1 << 16) | q0;
  }

  uint32_t m_divisor;
  unsigned m_shift;
  uint32_t m_normalised;
  uint32_t m_reciprocal;
};

}  // namespace tessera
