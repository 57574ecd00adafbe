// Tests of tessera::PowerTrace: windows follow each other, a window's
// energy is the model's energy of the activity between its ends, the
// windows add up to the energy over their whole span, and a window without
// activity holds static energy only.
#include <gtest/gtest.h>

#include "power/power_trace.h"

namespace {

using tessera::EnergyActivity;
using tessera::EnergyModel;
using tessera::PowerTrace;
using tessera::PowerWindow;

// 2 pJ per read, 1 mW static.
EnergyModel model() {
  return EnergyModel({{"block", {{"reads", 2.0}}, 1.0}});
}

EnergyActivity reads(double count) {
  return {{"block", {{"reads", count}}}};
}

TEST(PowerTrace, WindowsFollowEachOtherAndAddUpToTheirSpan) {
  const EnergyModel m = model();
  PowerTrace trace(m);
  trace.close_window(reads(1000), 1e-3);
  const PowerWindow& second = trace.close_window(reads(4000), 3e-3);
  EXPECT_DOUBLE_EQ(second.start_seconds, 1e-3);
  EXPECT_DOUBLE_EQ(second.end_seconds, 3e-3);
  // 3000 x 2 pJ = 6 nJ; 1 mW x 2 ms = 2 uJ; over 2 ms, 1.003 mW.
  EXPECT_DOUBLE_EQ(second.units.at(0).total_joules(), 2.006e-6);
  EXPECT_DOUBLE_EQ(second.milliwatts(second.total_joules()), 1.003);
  EXPECT_EQ(trace.windows(), 2u);
  const double whole = m.energy(reads(4000).at(0), 3e-3).total_joules();
  EXPECT_NEAR(trace.summed_joules().at("block"), whole, 1e-15 * whole);
}

TEST(PowerTrace, AWindowWithoutActivityHoldsStaticPowerOnly) {
  const EnergyModel m = model();
  PowerTrace trace(m);
  trace.close_window(reads(500), 1e-3);
  const PowerWindow& quiet = trace.close_window(reads(500), 2e-3);
  EXPECT_DOUBLE_EQ(quiet.units.at(0).dynamic_joules(), 0.0);
  EXPECT_DOUBLE_EQ(quiet.milliwatts(quiet.total_joules()), 1.0);
}

}  // namespace
