// soc_sim's simulated-time limit (tools/soc_sim/time_limit.h): automatic
// unless given, and described as the summary and the messages show it.
#include "time_limit.h"

#include <gtest/gtest.h>

namespace tessera {
namespace {

TEST(TimeLimit, AutomaticIsSixtySecondsPlusTenPerFrame) {
  const TimeLimit three = choose_time_limit(3, 0);
  EXPECT_TRUE(three.automatic);
  EXPECT_EQ(three.ms, 90000u);
  EXPECT_EQ(three.describe(), "90.000 s (automatic: 60 s + 10 s x 3 frames)");
  EXPECT_EQ(choose_time_limit(1, 0).describe(), "70.000 s (automatic: 60 s + 10 s x 1 frame)");
  // The teapot's 400 frames need 67 s of simulated time; 60 s used to stop them after 355.
  EXPECT_EQ(choose_time_limit(400, 0).ms, 4060000u);
  // --frames allows 100000: about 11.6 days of simulated time, within sc_time's range.
  EXPECT_EQ(choose_time_limit(100000, 0).ms, 1000060000u);
  EXPECT_EQ(TimeLimit::automatic_rule(), "60 s + 10 s per frame requested");
}

TEST(TimeLimit, GivenValueIsTakenAsItIs) {
  const TimeLimit given = choose_time_limit(400, 20);
  EXPECT_FALSE(given.automatic);
  EXPECT_EQ(given.ms, 20u);
  EXPECT_EQ(given.describe(), "20.000 ms (sim.time_limit_ms)");
  EXPECT_EQ(choose_time_limit(3, 60000).describe(), "60.000 s (sim.time_limit_ms)");
}

}  // namespace
}  // namespace tessera
