// ticks_time (common/ticks_time.h) gives the sc_time SystemC's from_value
// gives, for values across the 64-bit range, once the time resolution is
// fixed (as in a simulation: from_value fixes it on its first use).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <systemc>
#include <vector>

#include "common/ticks_time.h"

namespace {

using sc_core::sc_time;
using tessera::ticks_time;

TEST(TicksTime, TheSameTimeAsFromValue) {
  (void)sc_time::from_value(1);  // fixes the resolution
  std::mt19937_64 random(7);
  std::vector<uint64_t> values = {
      0, 1, 2, 5208, 10417, 1000000, uint64_t{1} << 53, (uint64_t{1} << 53) + 1, uint64_t{1} << 63, ~uint64_t{0}};
  for (int i = 0; i < 1000; ++i) values.push_back(random() >> (i % 64));
  for (uint64_t v : values) {
    const sc_time expected = sc_time::from_value(v);
    const sc_time time = ticks_time(v);
    ASSERT_EQ(time.value(), v);
    ASSERT_EQ(time, expected) << v;
    ASSERT_EQ(time.to_seconds(), expected.to_seconds()) << v;
  }
}

TEST(TicksTime, ArithmeticOnItIsSystemCs) {
  (void)sc_time::from_value(1);
  const sc_time a = ticks_time(5208), b = ticks_time(10417);
  EXPECT_EQ((a + b).value(), 15625u);
  EXPECT_EQ((b - a).value(), 5209u);
  EXPECT_TRUE(a < b);
  EXPECT_EQ(ticks_time(0), sc_core::SC_ZERO_TIME);
}

}  // namespace

int sc_main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
