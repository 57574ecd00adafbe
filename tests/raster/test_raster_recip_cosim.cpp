// Reciprocal unit co-simulation: every 14-bit operand through the functional
// core (Method 3) and the Verilated recip_unit.sv, every output bit compared.
#include <gtest/gtest.h>

#include <cstdint>
#include <iostream>

#include "raster/datapath/reciprocal.h"
#include "recip_unit_adapter.h"

namespace tessera::raster {
namespace {

TEST(RecipUnitCosim, EveryOperandMatchesTheFunctionalCoreBitForBit) {
  RecipUnitRtl rtl;
  unsigned compared = 0;
  unsigned mismatches = 0;
  // 0 included: the RTL defines its result (invalid_o, all ones).
  for (uint32_t raw = 0; raw <= RECIP_OPERAND_MAX; ++raw) {
    const auto x = static_cast<uint16_t>(raw);
    const ReciprocalResult expected = reciprocal(x, RecipMethod::method3);
    const ReciprocalResult actual = rtl.evaluate(x);
    ++compared;
    // The ports bit for bit, then the whole struct: the adapter's sign
    // extension must give back the core's exponent too.
    if (actual.q5_16 != expected.q5_16 || actual.mantissa != expected.mantissa ||
        actual.exponent_field() != expected.exponent_field() || actual.invalid_operand != expected.invalid_operand ||
        actual != expected) {
      if (++mismatches <= 10) {
        ADD_FAILURE() << "raw " << raw << ": rtl q5_16 " << actual.q5_16 << " mantissa " << unsigned{actual.mantissa}
                      << " exponent " << int{actual.exponent} << " invalid " << actual.invalid_operand
                      << ", core q5_16 " << expected.q5_16 << " mantissa " << unsigned{expected.mantissa}
                      << " exponent " << int{expected.exponent} << " invalid " << expected.invalid_operand;
      }
    }
  }
  std::cout << "compared " << compared << " vectors (16383 legal operands and 0), " << mismatches << " mismatches\n";
  EXPECT_EQ(compared, 16384u);
  EXPECT_EQ(mismatches, 0u);
}

TEST(RecipUnitCosim, ResultAppearsOneCycleAfterValidAndHoldsWhileIdle) {
  RecipUnitRtl rtl;
  EXPECT_EQ(RecipUnitRtl::LATENCY_CYCLES, 1u);
  EXPECT_FALSE(rtl.clock(false, 3).has_value());
  const auto first = rtl.clock(true, 3);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(*first, reciprocal(3, RecipMethod::method3));
  // Back to back: a new operand every cycle.
  const auto second = rtl.clock(true, 16383);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(*second, reciprocal(16383, RecipMethod::method3));
  // An idle cycle drops valid_o; a bubble does not disturb the next result.
  EXPECT_FALSE(rtl.clock(false, 1).has_value());
  const auto third = rtl.clock(true, 0);
  ASSERT_TRUE(third.has_value());
  EXPECT_TRUE(third->invalid_operand);
  EXPECT_EQ(third->q5_16, RECIP_Q5_16_SATURATED);
  rtl.reset();
  EXPECT_FALSE(rtl.clock(false, 0).has_value());
}

TEST(RecipUnitCosim, OperandsWiderThanThePortGetTheInvalidResult) {
  RecipUnitRtl rtl;
  EXPECT_EQ(rtl.evaluate(16384), reciprocal(16384, RecipMethod::method3));
  EXPECT_EQ(rtl.evaluate(0xFFFF), reciprocal_invalid_result(RecipMethod::method3));
}

}  // namespace
}  // namespace tessera::raster
