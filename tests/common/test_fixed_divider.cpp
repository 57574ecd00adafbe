// FixedDivider (common/fixed_divider.h) against the division it replaces:
// floor and ceil equal n / d and (n + d - 1) / d, computed with the
// division instruction, for the bus's clock periods in picoseconds and bus
// widths, at multiples of d and one either side, over the whole 64-bit
// range (where the reciprocal's error is largest), and on random values.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "common/fixed_divider.h"

namespace {

using tessera::FixedDivider;

uint64_t ceil_divide(uint64_t n, uint64_t d) {
  return n / d + (n % d != 0 ? 1 : 0);
}

void check(const FixedDivider& divider, uint64_t n) {
  const uint64_t d = divider.divisor();
  ASSERT_EQ(divider.floor(n), n / d) << n << " / " << d;
  ASSERT_EQ(divider.ceil(n), ceil_divide(n, d)) << n << " / " << d;
}

std::vector<uint64_t> divisors() {
  // 1 and the bus widths in bytes; clock periods in ps: 96 MHz (10417),
  // 100 MHz, 192 MHz (5208), 1 MHz, 7 MHz (an odd period); primes; 2^63.
  return {1,           2, 3, 4, 8, 16, 10417, 10000, 5208, 1000000, 142857, 65537, 4294967291ull, uint64_t{1} << 63,
          ~uint64_t{0}};
}

TEST(FixedDivider, MultiplesAndNeighbours) {
  for (uint64_t d : divisors()) {
    const FixedDivider divider(d);
    for (uint64_t k : {uint64_t{0}, uint64_t{1}, uint64_t{2}, uint64_t{1000}, uint64_t{123456789}, ~uint64_t{0} / d - 1,
                       ~uint64_t{0} / d}) {
      const uint64_t n = k * d;
      check(divider, n);
      if (n > 0) check(divider, n - 1);
      if (n < ~uint64_t{0}) check(divider, n + 1);
    }
    check(divider, ~uint64_t{0});
  }
}

TEST(FixedDivider, RandomValues) {
  std::mt19937_64 random(13);
  for (uint64_t d : divisors()) {
    const FixedDivider divider(d);
    for (int i = 0; i < 20000; ++i) {
      check(divider, random());
      check(divider, random() >> (i % 64));  // small values too
    }
  }
  for (int i = 0; i < 20000; ++i) {
    const uint64_t d = random() >> (i % 63) | 1;
    check(FixedDivider(d), random());
  }
}

TEST(FixedDivider, ZeroDivisorRefused) {
  EXPECT_THROW(FixedDivider(0), std::invalid_argument);
}

}  // namespace
