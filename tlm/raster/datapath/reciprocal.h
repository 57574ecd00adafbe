// Reciprocal unit of the rasterizer datapath: 1/X of an unsigned 10.4 operand.
//
// Functional core (plain C++, no SystemC) of the unit that the rasterizer uses
// for the EASA edge normalisation 1/(|dx| + |dy|) and for the triangle-setup
// denominator. Source: D. Crisu, S. Cotofana, S. Vassiliadis, P. Liuha,
// "Design Tradeoffs for an Embedded OpenGL-Compliant Hardware Rasterizer",
// Section IV, Methods 1-3 and Tables I-III. The Verilog reference of Method 3
// is rtl_models/raster/reciprocal.sv; the two agree bit for bit on every
// 16-bit operand, the invalid ones included
// (tests/rtl_models/raster/test_raster_reciprocal_cosim.cpp).
//
// Operand: X in unsigned 10.4 fixed point, raw 1..16383 (X = raw / 16).
//
// Methods (all truncate, none round):
//   method1  16k-entry table of 1/X in unsigned 5.10 fixed point (Table I).
//   method2  16k-entry table of 1/X in floating point: mantissa 1.6 with the
//            leading one implied, 5-bit two's complement exponent (Table II).
//   method3  prescaler + 1k-entry table (Table III, the paper's method): X is
//            shifted left by s = 0..4 places while the top 4 bits of the 14-bit
//            word hold leading zeros, the 4 LSBs are dropped and the remaining
//            10 bits index a table of 1/index stored as a 1.6 mantissa and a
//            4-bit inverted (non-negative) exponent k; the result exponent is
//            s - k, formed in a 5-bit two's complement subtracter.
//
// Common output: unsigned 5.16 fixed point in 21 bits (q5_16). The smallest
// Method 2/3 result, 1.000000 x 2^-10, has its LSB at 2^-16, so both
// floating-point formats convert to it exactly; Method 1's 5.10 entry is
// shifted left by 6. The largest result is 16.0 (X = 2^-4).
//
// Invalid operand (raw 0, or raw > 16383 which does not fit in 14 bits): no
// exception, no crash. The result has invalid_operand = true and every field
// saturated to all ones, like the unused entry 0 of Tables I-III:
//   q5_16 = RECIP_Q5_16_SATURATED (0x1FFFFF, i.e. 32 - 2^-16),
//   fixed_q5_10 = 0x7FFF (method 1), mantissa = 0x3F and exponent = -1
//   (5-bit field 11111; methods 2 and 3).
//
// Speed: Method 3, the one the rasterizer uses, is inline and branch-free
// (the prescaler four comparisons, Table III a constexpr table built at
// compile time by the same integer rule, the invalid operand a select), and
// has a batch form (reciprocal_method3_batch, batch.h); Methods 1 and 2
// (16k-entry tables) stay in reciprocal.cpp.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "raster/datapath/batch.h"
#include "raster/datapath/fixed_point.h"

namespace tessera::raster {

enum class RecipMethod { method1, method2, method3 };

// Accepts "1", "2", "3" and "method1", "method2", "method3"; anything else
// gives std::nullopt.
std::optional<RecipMethod> parse_recip_method(std::string_view text);
// Prints "method1", "method2" or "method3" (accepted back by the parser).
std::string_view to_string(RecipMethod method);

constexpr uint16_t RECIP_OPERAND_MAX = 0x3FFF;  // 1023.9375 in 10.4
constexpr unsigned RECIP_OPERAND_FRACTION_BITS = 4;
constexpr unsigned RECIP_Q5_16_FRACTION_BITS = 16;
constexpr unsigned RECIP_Q5_16_BITS = 21;
constexpr uint32_t RECIP_Q5_16_SATURATED = (1u << RECIP_Q5_16_BITS) - 1;
constexpr unsigned RECIP_MANTISSA_BITS = 6;  // fraction bits of 1.ffffff
constexpr unsigned RECIP_EXPONENT_BITS = 5;  // two's complement

struct ReciprocalResult {
  RecipMethod method = RecipMethod::method3;
  // 1/X in unsigned 5.16, the format the rest of the datapath multiplies by.
  uint32_t q5_16 = 0;
  bool invalid_operand = false;
  // Method 1 only (0 otherwise): the 15-bit 5.10 table entry.
  uint16_t fixed_q5_10 = 0;
  // Methods 2 and 3 only (0 otherwise): 1/X = (1 + mantissa / 64) * 2^exponent.
  uint8_t mantissa = 0;
  int8_t exponent = 0;

  // The exponent as the hardware's 5-bit two's complement field.
  constexpr uint8_t exponent_field() const {
    return static_cast<uint8_t>(exponent) & ((1u << RECIP_EXPONENT_BITS) - 1);
  }
};

bool operator==(const ReciprocalResult& a, const ReciprocalResult& b);
bool operator!=(const ReciprocalResult& a, const ReciprocalResult& b);

// The result that any method gives for an invalid operand (see above).
ReciprocalResult reciprocal_invalid_result(RecipMethod method);

namespace recip_detail {

constexpr unsigned TABLE3_INDEX_BITS = 10;
constexpr unsigned TABLE3_ENTRIES = 1u << TABLE3_INDEX_BITS;
constexpr unsigned PRESCALE_MAX = 4;
constexpr unsigned OPERAND_BITS = 14;
constexpr unsigned IMPLIED_ONE = 1u << RECIP_MANTISSA_BITS;
constexpr uint8_t MANTISSA_MASK = IMPLIED_ONE - 1;
// q5_16 LSB is 2^-16 and a 1.6 significand's LSB is 2^(exponent - 6), so the
// significand moves left by exponent + 10 (0 for the smallest result 2^-10).
constexpr int Q5_16_SHIFT_BIAS = RECIP_Q5_16_FRACTION_BITS - RECIP_MANTISSA_BITS;

// 1/d as (1 + mantissa/64) * 2^-k with the mantissa truncated, for d >= 1.
// k = ceil(log2 d) puts 2^(k + 6) / d in [64, 128).
struct FloatEntry {
  uint8_t mantissa;
  uint8_t negated_exponent;
};

constexpr FloatEntry truncated_reciprocal(uint32_t d) {
  uint8_t k = 0;
  while ((1u << k) < d) {
    ++k;
  }
  const uint32_t significand = (1u << (k + RECIP_MANTISSA_BITS)) / d;
  return {static_cast<uint8_t>(significand & MANTISSA_MASK), k};
}

// Table III: 1/index for the integers 1..1023, each entry the word
// mantissa | negated_exponent << 8; entry 0 is the unused all-ones pattern
// of the paper. 32-bit entries because a batch of operands (batch.h) reads
// them with one gather, which a 2-byte entry has not.
constexpr uint32_t table3_word(FloatEntry e) {
  return e.mantissa | uint32_t{e.negated_exponent} << 8;
}
struct Table3 {
  uint32_t word[TABLE3_ENTRIES];
};
constexpr Table3 make_table3() {
  Table3 t{};
  t.word[0] = table3_word({MANTISSA_MASK, 0xF});
  for (uint32_t index = 1; index < TABLE3_ENTRIES; ++index) t.word[index] = table3_word(truncated_reciprocal(index));
  return t;
}
inline constexpr Table3 TABLE3 = make_table3();

// The prescaler's shift: the leading zeros of the 14-bit word, at most 4
// (0 for an operand above 14 bits), as four comparisons rather than a
// leading-zero count, which has no vector form before AVX-512.
constexpr int prescale_shift(uint32_t raw) {
  return int{raw < 0x2000} + int{raw < 0x1000} + int{raw < 0x800} + int{raw < 0x400};
}

}  // namespace recip_detail

// Method 3's fields of one operand, for the scalar and the batch form.
// Integers rather than a ReciprocalResult with a bool in it: the batch
// loop keeps these in registers, which it does not do with that struct.
struct Method3Fields {
  uint32_t q5_16;
  uint32_t mantissa;
  int32_t exponent;
  uint32_t invalid;  // 1 for an invalid operand
};

constexpr Method3Fields method3_fields(uint32_t raw) {
  using namespace recip_detail;
  const uint32_t invalid = uint32_t{raw == 0} | uint32_t{raw > RECIP_OPERAND_MAX};
  // Prescaler: 1/X = 2^s * 16/(raw << s), s = the leading zeros of the
  // 14-bit word, at most 4; with the 4 LSBs of raw << s dropped the table
  // index approximates (raw << s) / 16.
  const int shift = prescale_shift(raw);
  const unsigned index = ((raw << shift) >> RECIP_OPERAND_FRACTION_BITS) & (TABLE3_ENTRIES - 1);
  const uint32_t word = TABLE3.word[index];
  const uint32_t mantissa = word & MANTISSA_MASK;
  const int exponent = shift - static_cast<int>(word >> 8);
  const uint32_t q5_16 = (IMPLIED_ONE | mantissa) << ((exponent + Q5_16_SHIFT_BIAS) & 31);
  return {invalid != 0 ? RECIP_Q5_16_SATURATED : q5_16, invalid != 0 ? uint32_t{MANTISSA_MASK} : mantissa,
          invalid != 0 ? -1 : exponent, invalid};
}

// Method 3 (the paper's method), inline and branch-free.
constexpr ReciprocalResult reciprocal_method3(uint16_t x_q10_4) {
  const Method3Fields f = method3_fields(x_q10_4);
  ReciprocalResult r;
  r.method = RecipMethod::method3;
  r.invalid_operand = f.invalid != 0;
  r.q5_16 = f.q5_16;
  r.mantissa = static_cast<uint8_t>(f.mantissa);
  r.exponent = static_cast<int8_t>(f.exponent);
  return r;
}

// Batch form of Method 3 (batch.h): `count` operands (an operand above 16
// bits is invalid, as one above 14), each field of the results in an array
// of its own, 32-bit elements as in every batch form, so that the loop runs
// vectorised from 8 elements on.
struct ReciprocalBatch {
  uint32_t* q5_16;
  uint32_t* mantissa;
  int32_t* exponent;
  uint32_t* invalid_operand;  // 1 for an invalid operand
};

struct ReciprocalKernel {
  TESSERA_BATCH_KERNEL void run(const uint32_t* x_q10_4, unsigned count, const ReciprocalBatch& out) {
    loop(x_q10_4, count, out.q5_16, out.mantissa, out.exponent, out.invalid_operand);
  }
  TESSERA_BATCH_KERNEL void loop(const uint32_t* __restrict x, unsigned count, uint32_t* __restrict q5_16,
                                 uint32_t* __restrict mantissa, int32_t* __restrict exponent,
                                 uint32_t* __restrict invalid) {
    for (unsigned i = 0; i < count; ++i) {
      const Method3Fields f = method3_fields(x[i]);
      q5_16[i] = f.q5_16;
      mantissa[i] = f.mantissa;
      exponent[i] = f.exponent;
      invalid[i] = f.invalid;
    }
  }
};

void reciprocal_method3_batch(const uint32_t* x_q10_4, unsigned count, const ReciprocalBatch& out,
                              BatchIsa isa = best_batch_isa());

// Methods 1 and 2 (reciprocal.cpp).
ReciprocalResult reciprocal_table_method(uint16_t x_q10_4, RecipMethod method);

inline ReciprocalResult reciprocal(uint16_t x_q10_4, RecipMethod method) {
  return method == RecipMethod::method3 ? reciprocal_method3(x_q10_4) : reciprocal_table_method(x_q10_4, method);
}

inline uint32_t reciprocal_q5_16(uint16_t x_q10_4, RecipMethod method) {
  return reciprocal(x_q10_4, method).q5_16;
}

// The same in the datapath's fixed-point types; an invalid operand gives the
// saturated code, as above.
inline q5_16 reciprocal_fixed(q10_4 x, RecipMethod method) {
  const uint16_t raw = x.raw > RECIP_OPERAND_MAX ? 0 : static_cast<uint16_t>(x.raw);
  return q5_16::from_raw(reciprocal_q5_16(raw, method));
}

// The q5_16 result as a real number (32 - 2^-16 for an invalid operand).
double reciprocal_value(uint16_t x_q10_4, RecipMethod method);

}  // namespace tessera::raster
