// Reciprocal unit, functional core: the accuracy claims of Crisu et al.
// (Section IV) over every legal 10.4 operand, spot values of Tables I-III and
// the invalid-operand contract. Expected values are worked out by hand from the
// formats, not taken from the code under test.
#include "raster/datapath/reciprocal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tessera::raster {
namespace {

constexpr uint16_t LEGAL_MAX = 16383;
constexpr double Q5_16_ONE = 65536.0;
// Truncating a 1.6 significand loses less than one unit in the 6th place.
const double MANTISSA_TRUNCATION = std::ldexp(1.0, -6);

double true_reciprocal(uint16_t raw) {
  return 16.0 / raw;
}

// Eq. 3 of the paper, signed.
double relative_error(uint16_t raw, RecipMethod method) {
  const double approx = reciprocal_q5_16(raw, method) / Q5_16_ONE;
  return (approx - true_reciprocal(raw)) / true_reciprocal(raw);
}

struct ErrorStats {
  double max_abs = 0.0;
  uint16_t worst_raw = 0;
  double mean_abs = 0.0;
};

ErrorStats error_stats(RecipMethod method) {
  ErrorStats s;
  double sum = 0.0;
  for (uint16_t raw = 1; raw <= LEGAL_MAX; ++raw) {
    const double e = std::fabs(relative_error(raw, method));
    sum += e;
    if (e > s.max_abs) {
      s.max_abs = e;
      s.worst_raw = raw;
    }
  }
  s.mean_abs = sum / LEGAL_MAX;
  return s;
}

TEST(ReciprocalMethod, ParsesShortAndLongNamesAndPrintsLongOnes) {
  EXPECT_EQ(parse_recip_method("1"), RecipMethod::method1);
  EXPECT_EQ(parse_recip_method("2"), RecipMethod::method2);
  EXPECT_EQ(parse_recip_method("3"), RecipMethod::method3);
  EXPECT_EQ(parse_recip_method("method1"), RecipMethod::method1);
  EXPECT_EQ(parse_recip_method("method3"), RecipMethod::method3);
  EXPECT_FALSE(parse_recip_method("4").has_value());
  EXPECT_FALSE(parse_recip_method("").has_value());
  EXPECT_FALSE(parse_recip_method("Method3").has_value());
  for (RecipMethod m : {RecipMethod::method1, RecipMethod::method2, RecipMethod::method3}) {
    EXPECT_EQ(parse_recip_method(to_string(m)), m);
  }
  EXPECT_EQ(to_string(RecipMethod::method2), "method2");
}

TEST(Reciprocal, Method3MaximumRelativeErrorIsBelowOnePointSixPercent) {
  const ErrorStats s = error_stats(RecipMethod::method3);
  std::cout << "method3: max |rel err| " << s.max_abs * 100 << "% at raw " << s.worst_raw << ", mean "
            << s.mean_abs * 100 << "%\n";
  EXPECT_LT(s.max_abs, 0.016);
  // The paper reports "about 1.5%": the mantissa truncation bound 2^-6
  // = 1.5625% must be approached, not merely respected.
  EXPECT_GT(s.max_abs, 0.015);
}

TEST(Reciprocal, Method3ErrorStaysWithinTheBoundsOfItsTwoTruncations) {
  // Truncating the 1.6 mantissa makes the result smaller by less than 2^-6.
  // Dropping the 4 LSBs after prescaling only happens when the prescaled
  // operand has its MSB set, i.e. index >= 512, and makes the divisor smaller
  // by at most 15/16 of an index unit: the result grows by at most 15/8192.
  const double upper = 15.0 / 8192.0;
  for (uint16_t raw = 1; raw <= LEGAL_MAX; ++raw) {
    const double e = relative_error(raw, RecipMethod::method3);
    ASSERT_GT(e, -MANTISSA_TRUNCATION) << "raw " << raw;
    ASSERT_LE(e, upper) << "raw " << raw;
  }
}

TEST(Reciprocal, Method2OnlyTruncatesTheTrueReciprocal) {
  for (uint16_t raw = 1; raw <= LEGAL_MAX; ++raw) {
    const double e = relative_error(raw, RecipMethod::method2);
    ASSERT_LE(e, 0.0) << "raw " << raw;
    ASSERT_GT(e, -MANTISSA_TRUNCATION) << "raw " << raw;
  }
}

TEST(Reciprocal, Method2IsCloseToMethod3) {
  // Below 1024 (raw) the prescaler drops only zeros, so the 1k table sees the
  // operand exactly and both methods truncate the same real number.
  for (uint16_t raw = 1; raw < 1024; ++raw) {
    ASSERT_EQ(reciprocal_q5_16(raw, RecipMethod::method3), reciprocal_q5_16(raw, RecipMethod::method2))
        << "raw " << raw;
  }
  // Above, the two truncate values that differ by less than 0.19%, so they
  // are at most one mantissa unit apart (2^-6 of the result, 1.5625%).
  unsigned differing = 0;
  for (uint16_t raw = 1024; raw <= LEGAL_MAX; ++raw) {
    const double m2 = reciprocal_q5_16(raw, RecipMethod::method2) / Q5_16_ONE;
    const double m3 = reciprocal_q5_16(raw, RecipMethod::method3) / Q5_16_ONE;
    ASSERT_LE(std::fabs(m3 - m2), std::min(m2, m3) * MANTISSA_TRUNCATION) << "raw " << raw;
    differing += m2 != m3;
  }
  const ErrorStats s2 = error_stats(RecipMethod::method2);
  const ErrorStats s3 = error_stats(RecipMethod::method3);
  std::cout << "method2: max |rel err| " << s2.max_abs * 100 << "% at raw " << s2.worst_raw << ", mean "
            << s2.mean_abs * 100 << "%; method3 differs from method2 on " << differing << " of 16383 operands\n";
  // The paper: "almost the same". Worst cases within 0.05 and means within
  // 0.1 percentage points; Method 3 is not worse, because the LSBs it drops
  // push its results up while the truncated mantissa pulls them down.
  EXPECT_NEAR(s3.max_abs, s2.max_abs, 5e-4);
  EXPECT_LE(s3.max_abs, s2.max_abs);
  EXPECT_NEAR(s3.mean_abs, s2.mean_abs, 1e-3);
}

TEST(Reciprocal, Method1IsFarWorseWithItsWorstCaseJustAboveFiveHundredTwelve) {
  // 5.10 truncation keeps one code for 1/X in [2^-10, 2^-9), so raw 8193
  // (X = 512.0625) reads back 2^-10: error 8193/16384 - 1.
  const ErrorStats s1 = error_stats(RecipMethod::method1);
  const ErrorStats s3 = error_stats(RecipMethod::method3);
  std::cout << "method1: max |rel err| " << s1.max_abs * 100 << "% at raw " << s1.worst_raw << ", mean "
            << s1.mean_abs * 100 << "%\n";
  EXPECT_EQ(s1.worst_raw, 8193);
  EXPECT_NEAR(s1.max_abs, 1.0 - 8193.0 / 16384.0, 1e-12);
  EXPECT_GT(s1.max_abs, 30 * s3.max_abs);
  EXPECT_GT(s1.mean_abs, s3.mean_abs);
}

TEST(Reciprocal, SmallestOperandGivesSixteenInEveryMethod) {
  for (RecipMethod m : {RecipMethod::method1, RecipMethod::method2, RecipMethod::method3}) {
    const ReciprocalResult r = reciprocal(1, m);
    EXPECT_FALSE(r.invalid_operand);
    EXPECT_EQ(r.q5_16, 16u << 16) << to_string(m);
    EXPECT_DOUBLE_EQ(reciprocal_value(1, m), 16.0);
    EXPECT_DOUBLE_EQ(reciprocal_value(2, m), 8.0);
  }
}

TEST(Reciprocal, Method1MatchesTableI) {
  EXPECT_EQ(reciprocal(1, RecipMethod::method1).fixed_q5_10, 0b10000'0000000000);
  EXPECT_EQ(reciprocal(2, RecipMethod::method1).fixed_q5_10, 0b01000'0000000000);
  EXPECT_EQ(reciprocal(3, RecipMethod::method1).fixed_q5_10, 0b00101'0101010101);
  EXPECT_EQ(reciprocal(16382, RecipMethod::method1).fixed_q5_10, 0b00000'0000000001);
  EXPECT_EQ(reciprocal(16383, RecipMethod::method1).fixed_q5_10, 0b00000'0000000001);
  // 101.0101010101 = 5461/1024, in 5.16 shifted left by 6.
  EXPECT_EQ(reciprocal_q5_16(3, RecipMethod::method1), 5461u << 6);
  EXPECT_DOUBLE_EQ(reciprocal_value(3, RecipMethod::method1), 5461.0 / 1024.0);
}

TEST(Reciprocal, Method2MatchesTableII) {
  struct Row {
    uint16_t raw;
    uint8_t mantissa;
    int8_t exponent;
  };
  for (const Row& row : {Row{1, 0, 4}, Row{2, 0, 3}, Row{3, 0b010101, 2}, Row{16382, 0, -10}, Row{16383, 0, -10}}) {
    const ReciprocalResult r = reciprocal(row.raw, RecipMethod::method2);
    EXPECT_EQ(r.mantissa, row.mantissa) << "raw " << row.raw;
    EXPECT_EQ(r.exponent, row.exponent) << "raw " << row.raw;
  }
  // 1.010101 x 2^2 = 85/16: 1/(3/16) = 5.333 truncated.
  EXPECT_DOUBLE_EQ(reciprocal_value(3, RecipMethod::method2), 85.0 / 16.0);
  // 1.000000 x 2^-10 is the smallest result and the LSB of 5.16 shifted by 6.
  EXPECT_EQ(reciprocal_q5_16(16383, RecipMethod::method2), 64u);
  EXPECT_EQ(reciprocal(16383, RecipMethod::method2).exponent_field(), 0b10110);
}

TEST(Reciprocal, Method3MatchesTableIIIThroughThePrescaler) {
  // Operands below 1024 are shifted by 4, so raw i uses table index i and the
  // exponent is 4 - k: index 1 -> (1.000000, k 0), 2 -> (1.000000, k 1),
  // 3 -> (1.010101, k 2), 1023 -> (1.000000, k 10).
  struct Row {
    uint16_t raw;
    uint8_t mantissa;
    int8_t exponent;
  };
  for (const Row& row : {Row{1, 0, 4}, Row{2, 0, 3}, Row{3, 0b010101, 2}, Row{1023, 0, -6},
                         // No shift: index = raw >> 4 = 1023, exponent 0 - 10.
                         Row{16383, 0, -10},
                         // raw 1024 = 0b00010000000000 has 3 leading zeros
                         // in the top 4 bits: index 512, k 9, exponent -6.
                         Row{1024, 0, -6},
                         // raw 3 << 10: shifted by 2 to 0b11 << 12, index
                         // 768 = 3 * 256, 1/768 = 1.010101 x 2^-10, exponent -8.
                         Row{3072, 0b010101, -8}}) {
    const ReciprocalResult r = reciprocal(row.raw, RecipMethod::method3);
    EXPECT_EQ(r.mantissa, row.mantissa) << "raw " << row.raw;
    EXPECT_EQ(r.exponent, row.exponent) << "raw " << row.raw;
    EXPECT_FALSE(r.invalid_operand);
  }
  EXPECT_DOUBLE_EQ(reciprocal_value(3, RecipMethod::method3), 85.0 / 16.0);
  // raw 8200 = X 512.5: no prescaling, index 512, so the dropped fraction .5
  // gives 1/512 instead of 1/512.5, 0.1% high.
  EXPECT_DOUBLE_EQ(reciprocal_value(8200, RecipMethod::method3), 1.0 / 512.0);
}

TEST(Reciprocal, ZeroAndOutOfRangeOperandsGiveTheSaturatedInvalidResult) {
  for (RecipMethod m : {RecipMethod::method1, RecipMethod::method2, RecipMethod::method3}) {
    for (uint16_t raw : {uint16_t{0}, uint16_t{16384}, uint16_t{0x8000}, uint16_t{0xFFFF}}) {
      const ReciprocalResult r = reciprocal(raw, m);
      EXPECT_TRUE(r.invalid_operand) << to_string(m) << " raw " << raw;
      EXPECT_EQ(r.q5_16, 0x1FFFFFu);
      EXPECT_EQ(reciprocal_q5_16(raw, m), 0x1FFFFFu);
      EXPECT_DOUBLE_EQ(reciprocal_value(raw, m), 32.0 - std::ldexp(1.0, -16));
      if (m == RecipMethod::method1) {
        EXPECT_EQ(r.fixed_q5_10, 0x7FFF);
      } else {
        EXPECT_EQ(r.mantissa, 0x3F);
        EXPECT_EQ(r.exponent_field(), 0x1F);
      }
      EXPECT_EQ(r, reciprocal_invalid_result(m));
    }
    EXPECT_FALSE(reciprocal(16383, m).invalid_operand);
  }
}

TEST(Reciprocal, FixedPointOverloadAgreesAndRejectsWideCodes) {
  EXPECT_EQ(reciprocal_fixed(q10_4::from_raw(3), RecipMethod::method3).raw, 85u << 12);
  EXPECT_EQ(reciprocal_fixed(q10_4{0x4001}, RecipMethod::method3).raw, 0x1FFFFFu);
}

TEST(Reciprocal, EveryResultFitsInTwentyOneBitsAndDecreasesWithTheOperand) {
  for (RecipMethod m : {RecipMethod::method1, RecipMethod::method2, RecipMethod::method3}) {
    uint32_t previous = reciprocal_q5_16(1, m);
    for (uint16_t raw = 2; raw <= LEGAL_MAX; ++raw) {
      const uint32_t q = reciprocal_q5_16(raw, m);
      ASSERT_LE(q, previous) << to_string(m) << " raw " << raw;
      ASSERT_GT(q, 0u) << to_string(m) << " raw " << raw;
      previous = q;
    }
  }
}

}  // namespace
}  // namespace tessera::raster
