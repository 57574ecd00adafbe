// What a block tells the energy model (tlm/power/): for each energy unit it
// holds, the count of every event class since the start of the run. Counts
// are doubles because some are times in clock cycles (the host's stalled
// cycles are bus time at the host's clock). Plain C++, no SystemC.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tessera {

struct UnitActivity {
  UnitActivity() = default;
  UnitActivity(std::string unit_name, std::map<std::string, double> event_counts)
      : unit(std::move(unit_name)), counts(std::move(event_counts)) {}

  std::string unit;                      // "host", "cu_array": a unit of tlm/power/energy_params.def
  std::map<std::string, double> counts;  // event class -> events
  // How long the unit's clocks have run since the start, in seconds, where
  // the unit sleeps (clock gated) until the software first uses it
  // (power.sleep_unused); none: clocked the whole time. Its static power is
  // charged for this time.
  std::optional<double> clocked_seconds;
};

using EnergyActivity = std::vector<UnitActivity>;

}  // namespace tessera
