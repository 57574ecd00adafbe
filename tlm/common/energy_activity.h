// What a block tells the energy model (tlm/power/): for each energy unit it
// holds, the count of every event class since the start of the run. Counts
// are doubles because some are times in clock cycles (the host's stalled
// cycles are bus time at the host's clock). Plain C++, no SystemC.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace tessera {

struct UnitActivity {
  std::string unit;                      // "host", "cu_array": a unit of tlm/power/energy_params.def
  std::map<std::string, double> counts;  // event class -> events
};

using EnergyActivity = std::vector<UnitActivity>;

}  // namespace tessera
