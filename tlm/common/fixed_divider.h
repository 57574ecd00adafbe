// Exact division by a divisor fixed at construction (a clock period in
// ticks, a bus width in bytes), without a division instruction: the bus
// aligns every request to a clock edge and converts every latency to
// cycles, and a 64-bit division costs more than the rest of a transaction's
// arithmetic.
//
// The reciprocal r = floor((2^64 - 1) / d) is computed once. For any 64-bit
// n, the high half of n * r is floor(n / d) or at most two less
// (n * (2^64 / d - r) / 2^64 < 2), and at most two compare-and-subtract
// steps make it exact: floor() equals n / d for every n.
#pragma once

#include <cstdint>
#include <stdexcept>

namespace tessera {

class FixedDivider {
 public:
  explicit FixedDivider(uint64_t divisor)
      : m_divisor(divisor), m_reciprocal(divisor ? ~uint64_t{0} / divisor : 0), m_shift(shift_of(divisor)) {
    if (divisor == 0) throw std::invalid_argument("division by zero");
  }

  uint64_t divisor() const { return m_divisor; }

  // n / d, rounded down.
  uint64_t floor(uint64_t n) const {
    if (m_shift != NOT_A_POWER_OF_TWO) return n >> m_shift;
    __extension__ typedef unsigned __int128 Wide;  // GCC and clang
    uint64_t quotient = static_cast<uint64_t>((static_cast<Wide>(n) * m_reciprocal) >> 64);
    uint64_t remainder = n - quotient * m_divisor;
    while (remainder >= m_divisor) {
      ++quotient;
      remainder -= m_divisor;
    }
    return quotient;
  }

  // n / d, rounded up.
  uint64_t ceil(uint64_t n) const {
    if (m_shift != NOT_A_POWER_OF_TWO) return (n >> m_shift) + ((n & (m_divisor - 1)) != 0 ? 1 : 0);
    const uint64_t quotient = floor(n);
    return quotient + (quotient * m_divisor != n ? 1 : 0);
  }

 private:
  static constexpr unsigned NOT_A_POWER_OF_TWO = 64;
  static unsigned shift_of(uint64_t divisor) {
    if (divisor == 0 || (divisor & (divisor - 1)) != 0) return NOT_A_POWER_OF_TWO;
    unsigned shift = 0;
    while ((uint64_t{1} << shift) != divisor) ++shift;
    return shift;
  }

  uint64_t m_divisor;
  uint64_t m_reciprocal;
  unsigned m_shift;  // log2 of the divisor, or NOT_A_POWER_OF_TWO
};

}  // namespace tessera
