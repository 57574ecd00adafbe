// Int128: a signed 128-bit integer for the host's set-up arithmetic, whose
// exact products (2^46 edge values times 2^24 depths, 2^23 coordinates
// times 2^46 areas) do not fit 64 bits. GCC and clang have __int128 on
// 64-bit targets, and there Int128 is that type; a 32-bit target (the
// ARM922T, when the driver is cross-compiled for the ISS) has none, and
// there Int128 is SoftInt128, two 64-bit halves with the operations the
// set-up code uses. Both wrap modulo 2^128 and divide truncating towards
// zero, as C++ integers do; test_wide_int checks SoftInt128 against
// __int128 on random operands.
#pragma once

#include <cstdint>

namespace tessera {

class SoftInt128 {
 public:
  constexpr SoftInt128() = default;
  // Implicit, as an integer's widening is: the set-up code mixes 64-bit and
  // 128-bit operands.
  constexpr SoftInt128(int64_t value)  // NOLINT(google-explicit-constructor)
      : m_high(value < 0 ? ~uint64_t{0} : 0), m_low(static_cast<uint64_t>(value)) {}

  constexpr explicit operator int64_t() const { return static_cast<int64_t>(m_low); }

  friend constexpr SoftInt128 operator+(const SoftInt128& a, const SoftInt128& b) {
    const uint64_t low = a.m_low + b.m_low;
    return from_halves(a.m_high + b.m_high + (low < a.m_low ? 1 : 0), low);
  }
  friend constexpr SoftInt128 operator-(const SoftInt128& a) { return SoftInt128() - a; }
  friend constexpr SoftInt128 operator-(const SoftInt128& a, const SoftInt128& b) {
    return from_halves(a.m_high - b.m_high - (a.m_low < b.m_low ? 1 : 0), a.m_low - b.m_low);
  }
  friend constexpr SoftInt128 operator*(const SoftInt128& a, const SoftInt128& b) {
    // The low 128 bits of the product: the full product of the low halves,
    // plus the cross terms shifted up by 64 (their upper halves and the
    // product of the high halves fall off).
    const uint64_t a0 = a.m_low & 0xffffffffu, a1 = a.m_low >> 32;
    const uint64_t b0 = b.m_low & 0xffffffffu, b1 = b.m_low >> 32;
    const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    const uint64_t middle = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
    const uint64_t low = (middle << 32) | (p00 & 0xffffffffu);
    const uint64_t high = p11 + (p01 >> 32) + (p10 >> 32) + (middle >> 32);
    return from_halves(high + a.m_high * b.m_low + a.m_low * b.m_high, low);
  }
  friend constexpr SoftInt128 operator/(const SoftInt128& a, const SoftInt128& b) {
    const bool negative = a.negative() != b.negative();
    const SoftInt128 quotient = divide_magnitudes(a.magnitude(), b.magnitude());
    return negative ? -quotient : quotient;
  }
  friend constexpr SoftInt128 operator<<(const SoftInt128& a, unsigned shift) {
    if (shift == 0) return a;
    if (shift >= 128) return {};
    if (shift >= 64) return from_halves(a.m_low << (shift - 64), 0);
    return from_halves((a.m_high << shift) | (a.m_low >> (64 - shift)), a.m_low << shift);
  }
  SoftInt128& operator+=(const SoftInt128& b) { return *this = *this + b; }
  SoftInt128& operator-=(const SoftInt128& b) { return *this = *this - b; }

  friend constexpr bool operator==(const SoftInt128& a, const SoftInt128& b) {
    return a.m_high == b.m_high && a.m_low == b.m_low;
  }
  friend constexpr bool operator!=(const SoftInt128& a, const SoftInt128& b) { return !(a == b); }
  friend constexpr bool operator<(const SoftInt128& a, const SoftInt128& b) {
    if (a.m_high != b.m_high) return static_cast<int64_t>(a.m_high) < static_cast<int64_t>(b.m_high);
    return a.m_low < b.m_low;
  }
  friend constexpr bool operator>(const SoftInt128& a, const SoftInt128& b) { return b < a; }
  friend constexpr bool operator<=(const SoftInt128& a, const SoftInt128& b) { return !(b < a); }
  friend constexpr bool operator>=(const SoftInt128& a, const SoftInt128& b) { return !(a < b); }

  constexpr uint64_t high_bits() const { return m_high; }
  constexpr uint64_t low_bits() const { return m_low; }
  static constexpr SoftInt128 from_halves(uint64_t high, uint64_t low) {
    SoftInt128 value;
    value.m_high = high;
    value.m_low = low;
    return value;
  }

 private:
  constexpr bool negative() const { return static_cast<int64_t>(m_high) < 0; }
  // |value| as an unsigned 128-bit pattern (-2^127 stays itself, as its
  // magnitude read unsigned).
  constexpr SoftInt128 magnitude() const { return negative() ? -*this : *this; }
  static constexpr bool unsigned_less(const SoftInt128& a, const SoftInt128& b) {
    return a.m_high != b.m_high ? a.m_high < b.m_high : a.m_low < b.m_low;
  }
  // Unsigned long division, a bit at a time from the top. Division by zero
  // is undefined for integers; here it gives all ones, as restoring
  // division does, rather than trapping.
  static constexpr SoftInt128 divide_magnitudes(const SoftInt128& n, const SoftInt128& d) {
    SoftInt128 quotient, remainder;
    for (int bit = 127; bit >= 0; --bit) {
      remainder = remainder << 1;
      const uint64_t word = bit >= 64 ? n.m_high : n.m_low;
      remainder.m_low |= (word >> (bit & 63)) & 1;
      if (!unsigned_less(remainder, d)) {
        remainder = remainder - d;
        if (bit >= 64)
          quotient.m_high |= uint64_t{1} << (bit - 64);
        else
          quotient.m_low |= uint64_t{1} << bit;
      }
    }
    return quotient;
  }

  uint64_t m_high = 0;
  uint64_t m_low = 0;
};

#if defined(__SIZEOF_INT128__)
__extension__ typedef __int128 Int128;  // GCC and clang on 64-bit targets
#else
using Int128 = SoftInt128;
#endif

}  // namespace tessera
