// The units of each row of the host's measured cost table
// (sw_driver/costs) the native driver charged since the last call, summed
// over the meter's buckets: what a test asserts the driver charges, without
// depending on the rows' measured cycles.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "costs/host_cost.h"

namespace tessera::test {

// The phases' buckets (a .. d) hold every charge once; the split's (s)
// hold the array back ends' again.
inline constexpr const char* TEST_COST_BUCKETS[costs::COST_BUCKETS] = {"a", "b", "c", "d", "s", "s", "s", "s", "s"};
static_assert(costs::COST_BUCKETS == 9);

inline std::map<std::string, uint64_t> take_cost_units() {
  std::map<std::string, uint64_t> units;
  for (const auto& [name, value] : costs::take_cost_units(TEST_COST_BUCKETS)) {
    if (name.compare(0, 8, "units_s_") == 0) continue;
    units[name.substr(name.find('_', 6) + 1)] += static_cast<uint64_t>(value);  // units_<bucket>_<row>
  }
  return units;
}

}  // namespace tessera::test
