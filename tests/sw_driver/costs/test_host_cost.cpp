// costs::charge (sw_driver/costs/host_cost.h): the cycles a charge gives
// the host are the whole part of the row's cycles times the units plus
// the fraction carried from the charges before, the new fraction carried
// on; checked against that definition (std::floor) over random charges of
// every row, and a charge beyond what the host counts is an error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "costs/host_cost.h"
#include "host/recording_host.h"

namespace {

using tessera::costs::HostCost;
namespace costs = tessera::costs;

TEST(HostCost, ChargesGiveTheWholeCyclesAndCarryTheFraction) {
  costs::reset_cost_meter();
  tessera::test::RecordingHost host(4096);  // no memory is accessed: a charge is compute cycles alone
  std::mt19937_64 random(2026);
  double carry = 0;
  uint64_t expected = 0;
  for (int i = 0; i < 200000; ++i) {
    const auto row = static_cast<size_t>(random() % costs::HOST_COST_COUNT);
    // Mostly a few units, now and then many (a span, a frame's pixels).
    const uint64_t units = random() % 8 == 0 ? random() % 1000000 : random() % 5;
    costs::charge(host, static_cast<HostCost>(row), units);
    if (units == 0) continue;
    const double cycles = carry + costs::detail::ROW_CYCLES[row] * static_cast<double>(units);
    const double whole = std::floor(cycles);
    carry = cycles - whole;
    expected += static_cast<uint64_t>(whole);
    ASSERT_EQ(host.measured_cycles(), expected) << "charge " << i << ": row " << row << ", " << units << " units";
  }
  EXPECT_GT(expected, 0u);
}

TEST(HostCost, AChargeBeyondTheHostsCountIsAnError) {
  costs::reset_cost_meter();
  tessera::test::RecordingHost host(4096);  // no memory is accessed: a charge is compute cycles alone
  size_t row = 0;
  while (row < costs::HOST_COST_COUNT && costs::detail::ROW_CYCLES[row] < 1) ++row;
  ASSERT_LT(row, costs::HOST_COST_COUNT);
  EXPECT_THROW(costs::charge(host, static_cast<HostCost>(row), uint64_t{1} << 63), std::overflow_error);
  EXPECT_EQ(host.measured_cycles(), 0u);
  EXPECT_THROW(costs::charge(host, static_cast<HostCost>(costs::HOST_COST_COUNT), 1), std::invalid_argument);
}

// A store train's cycles (meter_cycles_each, ArrayDriver::fill8): what as
// many charges of the row one by one give the host, each, with the same
// fraction carried on and the same units counted.
TEST(HostCost, EachWordsCyclesAreWhatChargingItAloneGives) {
  std::mt19937_64 random(7);
  for (int trial = 0; trial < 200; ++trial) {
    const auto row = static_cast<HostCost>(random() % costs::HOST_COST_COUNT);
    const size_t count = 1 + random() % 40;
    const uint64_t before = 1 + random() % 10000;
    const HostCost before_row = static_cast<HostCost>(random() % costs::HOST_COST_COUNT);

    costs::reset_cost_meter();
    tessera::test::RecordingHost alone(4096);
    costs::charge(alone, before_row, before);
    std::vector<uint64_t> one_by_one;
    for (size_t k = 0; k < count; ++k) {
      const uint64_t was = alone.measured_cycles();
      costs::charge(alone, row, 1);
      one_by_one.push_back(alone.measured_cycles() - was);
    }
    costs::charge(alone, before_row, before);
    const uint64_t after_alone = alone.measured_cycles();
    const auto units_alone = costs::take_cost_units();

    costs::reset_cost_meter();
    tessera::test::RecordingHost train(4096);
    costs::charge(train, before_row, before);
    std::vector<uint64_t> each(count);
    costs::meter_cycles_each(row, each.data(), count);
    uint64_t sum = 0;
    for (uint64_t c : each) sum += c;
    train.compute_cycles(sum);
    costs::charge(train, before_row, before);
    ASSERT_EQ(each, one_by_one) << "trial " << trial;
    ASSERT_EQ(train.measured_cycles(), after_alone) << "the fraction carried on";
    ASSERT_EQ(costs::take_cost_units(), units_alone);
  }
}

}  // namespace
