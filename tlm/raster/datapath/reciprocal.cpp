// Reciprocal unit, Methods 1-3 of Crisu et al.; formats and invalid-operand
// behaviour are described in reciprocal.h. Tables I and II are built once, on
// first use, and Table III at compile time (reciprocal.h), all from integer
// arithmetic only, so every entry is the exact
// truncation of the true reciprocal and no floating-point rounding can differ
// between hosts.
#include "raster/datapath/reciprocal.h"

#include <array>

namespace tessera::raster {

namespace {

using namespace recip_detail;

constexpr unsigned Q5_10_TO_Q5_16_SHIFT = 6;

uint32_t float_to_q5_16(uint8_t mantissa, int exponent) {
  return (IMPLIED_ONE | mantissa) << (exponent + Q5_16_SHIFT_BIAS);
}

// Table I: 1/X = 16/raw in 5.10, i.e. floor(2^14 / raw).
const std::array<uint16_t, RECIP_OPERAND_MAX + 1>& method1_table() {
  static const auto table = [] {
    std::array<uint16_t, RECIP_OPERAND_MAX + 1> t{};
    t[0] = 0x7FFF;
    for (uint32_t raw = 1; raw <= RECIP_OPERAND_MAX; ++raw) {
      t[raw] = static_cast<uint16_t>((1u << (OPERAND_BITS)) / raw);
    }
    return t;
  }();
  return table;
}

// Table II: 1/X = 2^4/raw, so the exponent is 4 - ceil(log2 raw).
const std::array<FloatEntry, RECIP_OPERAND_MAX + 1>& method2_table() {
  static const auto table = [] {
    std::array<FloatEntry, RECIP_OPERAND_MAX + 1> t{};
    t[0] = {MANTISSA_MASK, 0};  // never read: raw 0 is rejected first
    for (uint32_t raw = 1; raw <= RECIP_OPERAND_MAX; ++raw) {
      t[raw] = truncated_reciprocal(raw);
    }
    return t;
  }();
  return table;
}

ReciprocalResult method1(uint16_t raw) {
  ReciprocalResult r;
  r.method = RecipMethod::method1;
  r.fixed_q5_10 = method1_table()[raw];
  r.q5_16 = static_cast<uint32_t>(r.fixed_q5_10) << Q5_10_TO_Q5_16_SHIFT;
  return r;
}

ReciprocalResult method2(uint16_t raw) {
  const FloatEntry e = method2_table()[raw];
  ReciprocalResult r;
  r.method = RecipMethod::method2;
  r.mantissa = e.mantissa;
  r.exponent = static_cast<int8_t>(RECIP_OPERAND_FRACTION_BITS - e.negated_exponent);
  r.q5_16 = float_to_q5_16(r.mantissa, r.exponent);
  return r;
}

}  // namespace

std::optional<RecipMethod> parse_recip_method(std::string_view text) {
  if (text == "1" || text == "method1") {
    return RecipMethod::method1;
  }
  if (text == "2" || text == "method2") {
    return RecipMethod::method2;
  }
  if (text == "3" || text == "method3") {
    return RecipMethod::method3;
  }
  return std::nullopt;
}

std::string_view to_string(RecipMethod method) {
  switch (method) {
    case RecipMethod::method1: return "method1";
    case RecipMethod::method2: return "method2";
    case RecipMethod::method3: return "method3";
  }
  return "unknown";
}

bool operator==(const ReciprocalResult& a, const ReciprocalResult& b) {
  return a.method == b.method && a.q5_16 == b.q5_16 && a.invalid_operand == b.invalid_operand &&
         a.fixed_q5_10 == b.fixed_q5_10 && a.mantissa == b.mantissa && a.exponent == b.exponent;
}

bool operator!=(const ReciprocalResult& a, const ReciprocalResult& b) {
  return !(a == b);
}

ReciprocalResult reciprocal_invalid_result(RecipMethod method) {
  ReciprocalResult r;
  r.method = method;
  r.q5_16 = RECIP_Q5_16_SATURATED;
  r.invalid_operand = true;
  if (method == RecipMethod::method1) {
    r.fixed_q5_10 = method1_table()[0];
  } else {
    r.mantissa = MANTISSA_MASK;
    r.exponent = -1;
  }
  return r;
}

ReciprocalResult reciprocal_table_method(uint16_t x_q10_4, RecipMethod method) {
  if (x_q10_4 == 0 || x_q10_4 > RECIP_OPERAND_MAX) {
    return reciprocal_invalid_result(method);
  }
  switch (method) {
    case RecipMethod::method1: return method1(x_q10_4);
    case RecipMethod::method2: return method2(x_q10_4);
    case RecipMethod::method3: return reciprocal_method3(x_q10_4);
  }
  return reciprocal_invalid_result(method);
}

void reciprocal_method3_batch(const uint32_t* x_q10_4, unsigned count, const ReciprocalBatch& out, BatchIsa isa) {
  batch_detail::dispatch<ReciprocalKernel>(isa, x_q10_4, count, out);
}

double reciprocal_value(uint16_t x_q10_4, RecipMethod method) {
  return static_cast<double>(reciprocal_q5_16(x_q10_4, method)) / static_cast<double>(1u << RECIP_Q5_16_FRACTION_BITS);
}

}  // namespace tessera::raster
