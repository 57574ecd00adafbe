// The border division and the decimal printing (fixed_point.h).
#include "forward_texture/fixed_point.h"

#include <climits>

namespace tessera::forward_texture {

bool divide_border(q12_20 numerator, q2_30 denominator, q16_16& border) {
  if (denominator <= 0 || numerator == INT32_MIN) {
    return false;
  }
  const uint32_t magnitude = numerator < 0 ? 0u - static_cast<uint32_t>(numerator) : static_cast<uint32_t>(numerator);
  const auto divisor = static_cast<uint32_t>(denominator);
  uint32_t remainder = 0;
  uint32_t quotient = 0;
  for (int i = 0; i < BORDER_DIVISION_ITERATIONS; ++i) {
    // Bits 30..0 of the magnitude (< 2^31), then zeros.
    const int bit_index = 30 - i;
    const uint32_t bit = bit_index >= 0 ? (magnitude >> bit_index) & 1u : 0u;
    if (quotient >= (uint32_t{1} << 30)) {
      return false;  // the next shift would leave q16_16's 31 magnitude bits
    }
    remainder = (remainder << 1) | bit;  // remainder < divisor < 2^31 before the shift
    quotient <<= 1;
    if (remainder >= divisor) {
      remainder -= divisor;
      quotient |= 1u;
    }
  }
  border = numerator < 0 ? -static_cast<int32_t>(quotient) : static_cast<int32_t>(quotient);
  return true;
}

std::string format_fixed(int64_t raw, int fraction_bits) {
  const bool negative = raw < 0;
  const uint64_t magnitude = negative ? 0u - static_cast<uint64_t>(raw) : static_cast<uint64_t>(raw);
  const uint64_t whole = magnitude >> fraction_bits;
  const uint64_t fraction = magnitude & ((uint64_t{1} << fraction_bits) - 1u);
  // Four decimal places, rounded: fraction * 10000 / 2^fraction_bits, by
  // shifts (fraction < 2^fraction_bits <= 2^50, times 10000 < 2^64).
  uint64_t places = (fraction * 10000u + (uint64_t{1} << (fraction_bits - 1))) >> fraction_bits;
  uint64_t whole_part = whole;
  if (places >= 10000u) {
    places -= 10000u;
    ++whole_part;
  }
  // Printed as 32-bit words, so that no 64-bit division is linked in: the
  // values printed have whole parts far below 2^32 (they come from q12_20,
  // q2_30, q16_16 and the set-up's 2^-46 scale); a larger one prints as
  // 4294967295.
  const uint32_t whole_word = whole_part > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(whole_part);
  std::string digits = std::to_string(static_cast<uint32_t>(places));
  digits.insert(0, 4 - digits.size(), '0');
  return (negative ? "-" : "") + std::to_string(whole_word) + "." + digits;
}

}  // namespace tessera::forward_texture
