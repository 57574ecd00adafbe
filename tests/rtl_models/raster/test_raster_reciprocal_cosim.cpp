// Reciprocal unit co-simulation: every 16-bit operand (the 16,383 legal
// ones, 0 and those above 2^14 - 1) through the functional core (Method 3,
// its scalar form and its batch form in every variant this machine runs)
// and the Verilated reciprocal.sv, every output bit compared.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "cosim_support.h"
#include "raster/datapath/reciprocal.h"
#include "reciprocal_adapter.h"

namespace tessera::raster {
namespace {

// The batch form's fields of operand i against the RTL's result.
bool batch_matches(const ReciprocalResult& rtl, const ReciprocalBatch& batch, unsigned i) {
  return batch.q5_16[i] == rtl.q5_16 && batch.mantissa[i] == rtl.mantissa && batch.exponent[i] == rtl.exponent &&
         batch.invalid_operand[i] == uint32_t{rtl.invalid_operand};
}

struct RecipBatchBuffers {
  std::vector<uint32_t> q5_16, mantissa, invalid;
  std::vector<int32_t> exponent;
  explicit RecipBatchBuffers(size_t n) : q5_16(n), mantissa(n), invalid(n), exponent(n) {}
  ReciprocalBatch view(size_t offset = 0) {
    return {q5_16.data() + offset, mantissa.data() + offset, exponent.data() + offset, invalid.data() + offset};
  }
};

TEST(ReciprocalCosim, EveryOperandMatchesTheFunctionalCoreBitForBit) {
  ReciprocalRtl rtl;
  CosimTally legal;
  CosimTally invalid;
  // Every value of the 16-bit operand: the 16,383 legal ones, and 0 and the
  // 49,152 above RECIP_OPERAND_MAX, which the RTL must flag itself (invalid_o,
  // every other field all ones) as the core does. The batch form gets them
  // once as one batch and once cut into batches of 1 to 64.
  constexpr uint32_t OPERANDS = 0x10000;
  std::vector<uint32_t> operands(OPERANDS);
  for (uint32_t raw = 0; raw < OPERANDS; ++raw) operands[raw] = raw;
  std::vector<RecipBatchBuffers> whole, cut;
  std::mt19937_64 rng(0x4ec1);
  for (BatchIsa isa : batch_isas()) {
    whole.emplace_back(OPERANDS);
    reciprocal_method3_batch(operands.data(), OPERANDS, whole.back().view(), isa);
    cut.emplace_back(OPERANDS);
    for (uint32_t first = 0; first < OPERANDS;) {
      const unsigned length = std::min<unsigned>(random_batch_length(rng()), OPERANDS - first);
      reciprocal_method3_batch(operands.data() + first, length, cut.back().view(first), isa);
      first += length;
    }
  }
  for (uint32_t raw = 0; raw < OPERANDS; ++raw) {
    const auto x = static_cast<uint16_t>(raw);
    const ReciprocalResult expected = reciprocal(x, RecipMethod::method3);
    const ReciprocalResult actual = rtl.evaluate(x);
    // The ports bit for bit, then the whole struct: the adapter's sign
    // extension must give back the core's exponent too.
    bool same = actual.q5_16 == expected.q5_16 && actual.mantissa == expected.mantissa &&
                actual.exponent_field() == expected.exponent_field() &&
                actual.invalid_operand == expected.invalid_operand && actual == expected;
    for (size_t k = 0; k < whole.size(); ++k)
      same = same && batch_matches(actual, whole[k].view(), raw) && batch_matches(actual, cut[k].view(), raw);
    CosimTally& tally = raw == 0 || raw > RECIP_OPERAND_MAX ? invalid : legal;
    if (tally.count(same)) {
      ADD_FAILURE() << "raw " << raw << ": rtl q5_16 " << actual.q5_16 << " mantissa " << unsigned{actual.mantissa}
                    << " exponent " << int{actual.exponent} << " invalid " << actual.invalid_operand << ", core q5_16 "
                    << expected.q5_16 << " mantissa " << unsigned{expected.mantissa} << " exponent "
                    << int{expected.exponent} << " invalid " << expected.invalid_operand << " (or a batch variant)";
    }
  }
  std::printf(
      "reciprocal cosim: %llu legal operands, %llu mismatches; %llu invalid operands (0 and above %u), %llu "
      "mismatches; each through the scalar form and %zu batch variant(s)\n",
      static_cast<unsigned long long>(legal.vectors), static_cast<unsigned long long>(legal.mismatches),
      static_cast<unsigned long long>(invalid.vectors), unsigned{RECIP_OPERAND_MAX},
      static_cast<unsigned long long>(invalid.mismatches), batch_isas().size());
  EXPECT_EQ(legal.vectors, 16383u);
  EXPECT_EQ(invalid.vectors, 65536u - 16383u);
  EXPECT_EQ(legal.mismatches, 0u);
  EXPECT_EQ(invalid.mismatches, 0u);
}

TEST(ReciprocalCosim, ResultAppearsOneCycleAfterValidAndHoldsWhileIdle) {
  ReciprocalRtl rtl;
  EXPECT_EQ(ReciprocalRtl::LATENCY_CYCLES, 1u);
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

TEST(ReciprocalCosim, OperandsAboveFourteenBitsAreFlaggedByTheRtl) {
  // Not cut to the low 14 bits: 16385 would otherwise look like 1 and give
  // 16.0.
  ReciprocalRtl rtl;
  for (const uint16_t x : {uint16_t{16384}, uint16_t{16385}, uint16_t{0x8001}, uint16_t{0xFFFF}}) {
    const ReciprocalResult result = rtl.evaluate(x);
    EXPECT_TRUE(result.invalid_operand) << x;
    EXPECT_EQ(result.q5_16, RECIP_Q5_16_SATURATED) << x;
    EXPECT_EQ(result, reciprocal_invalid_result(RecipMethod::method3)) << x;
  }
  // The same through the clocked interface, between two legal operands.
  const uint16_t operands[] = {1, 16385, 16383};
  for (const uint16_t x : operands) {
    const auto result = rtl.clock(true, x);
    ASSERT_TRUE(result.has_value());
    EXPECT_EQ(*result, reciprocal(x, RecipMethod::method3)) << x;
  }
}

}  // namespace
}  // namespace tessera::raster
