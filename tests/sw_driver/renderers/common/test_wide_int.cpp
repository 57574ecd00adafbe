// SoftInt128, the 128-bit integer of the set-up code on 32-bit targets (the
// driver cross-compiled for the ISS), against the compiler's __int128 on
// the same operands: random ones of every magnitude and sign, and the
// edges (zero, +-1, 2^63, 2^127 - 1, -2^127).
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "renderers/common/wide_int.h"

namespace {

using tessera::SoftInt128;
__extension__ typedef __int128 Native;
__extension__ typedef unsigned __int128 Unsigned;

SoftInt128 soft(Native v) {
  const auto u = static_cast<Unsigned>(v);
  return SoftInt128::from_halves(static_cast<uint64_t>(u >> 64), static_cast<uint64_t>(u));
}

Native native(const SoftInt128& v) {
  return static_cast<Native>((static_cast<Unsigned>(v.high_bits()) << 64) | v.low_bits());
}

// Operands of every size: a random number of significant bits, a random sign.
std::vector<Native> operands() {
  std::mt19937_64 random(20261129);
  std::vector<Native> out;
  const Native max = static_cast<Native>(~static_cast<Unsigned>(0) >> 1);
  for (Native v : {Native{0}, Native{1}, Native{-1}, Native{2}, Native{-7}, Native{1} << 63, -(Native{1} << 63), max,
                   -max - 1, max - 12345})
    out.push_back(v);
  for (int i = 0; i < 400; ++i) {
    const unsigned bits = 1 + static_cast<unsigned>(random() % 127);
    Unsigned v = (static_cast<Unsigned>(random()) << 64) | random();
    v >>= 128 - bits;
    out.push_back(random() & 1 ? -static_cast<Native>(v) : static_cast<Native>(v));
  }
  return out;
}

TEST(SoftInt128, ArithmeticMatchesInt128) {
  const std::vector<Native> values = operands();
  for (Native a : values)
    for (Native b : values) {
      const SoftInt128 sa = soft(a), sb = soft(b);
      const auto wrap = [](Unsigned v) { return static_cast<Native>(v); };
      // Wrapping sums and products, computed unsigned so that overflow is defined.
      ASSERT_EQ(native(sa + sb), wrap(static_cast<Unsigned>(a) + static_cast<Unsigned>(b)));
      ASSERT_EQ(native(sa - sb), wrap(static_cast<Unsigned>(a) - static_cast<Unsigned>(b)));
      ASSERT_EQ(native(sa * sb), wrap(static_cast<Unsigned>(a) * static_cast<Unsigned>(b)));
      ASSERT_EQ(sa < sb, a < b);
      ASSERT_EQ(sa >= sb, a >= b);
      ASSERT_EQ(sa == sb, a == b);
      const Native min = static_cast<Native>(static_cast<Unsigned>(1) << 127);
      if (b != 0 && !(a == min && b == -1)) {
        ASSERT_EQ(native(sa / sb), a / b);
      }
    }
}

TEST(SoftInt128, ConversionsAndShifts) {
  for (int64_t v : {int64_t{0}, int64_t{-1}, int64_t{42}, INT64_MIN, INT64_MAX}) {
    EXPECT_EQ(native(SoftInt128(v)), Native{v});
    EXPECT_EQ(static_cast<int64_t>(SoftInt128(v)), v);
    for (unsigned shift : {0u, 1u, 31u, 63u, 64u, 65u, 100u, 127u})
      EXPECT_EQ(native(SoftInt128(v) << shift), static_cast<Native>(static_cast<Unsigned>(Native{v}) << shift));
  }
}

}  // namespace
