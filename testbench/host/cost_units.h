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

// The phases' buckets hold every charge once; the split's hold the array
// back ends' again, so they are left out of the sums.
inline std::map<std::string, uint64_t> take_cost_units() {
  std::map<std::string, uint64_t> units;
  for (const auto& [name, value] : costs::take_cost_units()) {
    for (unsigned bucket = 0; bucket < costs::PHASE_BUCKETS; ++bucket) {
      const std::string prefix = std::string("units_") + costs::COST_BUCKET_NAMES[bucket] + "_";
      if (name.compare(0, prefix.size(), prefix) == 0)
        units[name.substr(prefix.size())] += static_cast<uint64_t>(value);
    }
  }
  return units;
}

}  // namespace tessera::test
