// Divisor, the set-up code's division by a per-triangle number without a
// 64-bit division helper, against the compiler's 64-bit division: divisors
// of every size (1, powers of two and their neighbours, 2^32 - 1, random
// ones of 1 to 32 bits), numerators of every size and sign.
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "renderers/common/divisor.h"

namespace {

using tessera::Divisor;

std::vector<uint32_t> divisors() {
  std::vector<uint32_t> out = {1,     2,     3,           7,           255,         256,         65535,
                               65536, 65537, 0x7fffffffu, 0x80000000u, 0x80000001u, 0xfffffffeu, 0xffffffffu};
  std::mt19937_64 random(20261202);
  for (int i = 0; i < 300; ++i) {
    const unsigned bits = 1 + static_cast<unsigned>(random() % 32);
    const auto d = static_cast<uint32_t>(random() >> (64 - bits));
    out.push_back(d == 0 ? 1 : d);
  }
  return out;
}

std::vector<uint64_t> numerators(std::mt19937_64& random) {
  std::vector<uint64_t> out = {0, 1, 2, 0xffffffffu, 0x100000000u, ~uint64_t{0}, ~uint64_t{0} >> 1};
  for (int i = 0; i < 200; ++i) {
    const unsigned bits = 1 + static_cast<unsigned>(random() % 64);
    out.push_back(random() >> (64 - bits));
  }
  return out;
}

TEST(Divisor, DividesAsTheCompilerDoes) {
  std::mt19937_64 random(7);
  for (uint32_t d : divisors()) {
    const Divisor divisor(d);
    for (uint64_t n : numerators(random)) {
      const Divisor::Unsigned u = divisor.divide(n);
      ASSERT_EQ(u.quotient, n / d) << n << " / " << d;
      ASSERT_EQ(u.remainder, n % d) << n << " % " << d;
      const int64_t s = static_cast<int64_t>(n >> 2) * ((random() & 1) != 0 ? -1 : 1);  // |s| < 2^62
      const Divisor::Floor f = divisor.floor_divide(s);
      const int64_t q = s / int64_t{d}, r = s % int64_t{d};
      const int64_t floor_q = r < 0 ? q - 1 : q;
      ASSERT_EQ(f.quotient, floor_q) << s << " / " << d;
      ASSERT_EQ(int64_t{f.remainder}, s - floor_q * int64_t{d}) << s << " / " << d;
      // Halves away from zero.
      const int64_t t = s / 2;
      const int64_t half = int64_t{d} / 2;
      const int64_t rounded = t >= 0 ? (t + half) / int64_t{d} : -((-t + half) / int64_t{d});
      ASSERT_EQ(divisor.round_divide(t), rounded) << t << " / " << d;
    }
  }
}

// The reciprocal is computed at compile time for a constant divisor.
TEST(Divisor, IsAConstantExpression) {
  constexpr Divisor BY_255(255);
  static_assert(BY_255.divide(1000).quotient == 3 && BY_255.divide(1000).remainder == 235);
  static_assert(BY_255.floor_divide(-1).quotient == -1 && BY_255.floor_divide(-1).remainder == 254);
  EXPECT_EQ(BY_255.value(), 255u);
}

}  // namespace
