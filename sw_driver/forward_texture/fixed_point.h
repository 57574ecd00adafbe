// The fixed-point formats of the forward texture mapper (README.md, "Fixed-
// point formats and their bounds"), the fixed-iteration division that turns a
// stepped numerator and denominator into a texel border, and the decimal
// printing of a value for an error message. 32-bit words only: the host is an
// ARM922T without an FPU and the array's CUs will run the same steps.
#pragma once

#include <cstdint>
#include <string>

namespace tessera::forward_texture {

using q12_20 = int32_t;   // matrix entries A..F, a pass's numerator; abs < 2^11
using q2_30 = int32_t;    // matrix entries G, H, I, a pass's denominator; abs < 2
using q16_16 = int32_t;   // texel borders in pixels; abs < 2^15
using q8_8 = int32_t;     // colours in the resampler: 0 .. 255, differences abs < 2^16
using uq1_15 = uint16_t;  // H values in the filter table: 0 .. 1, 1.0 = 32768

constexpr int Q12_20_FRACTION_BITS = 20;
constexpr int Q2_30_FRACTION_BITS = 30;
constexpr int Q16_16_FRACTION_BITS = 16;
constexpr int Q8_8_FRACTION_BITS = 8;
constexpr int UQ1_15_FRACTION_BITS = 15;
constexpr int32_t Q16_16_ONE = int32_t{1} << Q16_16_FRACTION_BITS;
constexpr uint32_t UQ1_15_ONE = uint32_t{1} << UQ1_15_FRACTION_BITS;

// Iterations of the restoring division: the 31 magnitude bits of the
// numerator (abs < 2^31), then the fraction bits the quotient gains (16 + 30 - 20 = 26).
constexpr int BORDER_DIVISION_ITERATIONS = 31 + Q16_16_FRACTION_BITS + Q2_30_FRACTION_BITS - Q12_20_FRACTION_BITS;

// numerator / denominator in q16_16, truncated toward zero (error < 2^-16),
// by BORDER_DIVISION_ITERATIONS steps of restoring division on uint32_t
// words: the remainder stays below the divisor (< 2^31), so doubling it
// fits. Requires denominator > 0; returns false when the quotient does not
// fit in q16_16 (abs >= 2^15) or the numerator is INT32_MIN.
bool divide_border(q12_20 numerator, q2_30 denominator, q16_16& border);

// A fixed-point value with `fraction_bits` fraction bits as a decimal with
// four places, e.g. "-1.2500", in integer arithmetic.
std::string format_fixed(int64_t raw, int fraction_bits);

}  // namespace tessera::forward_texture
