// The activity-based energy model: a unit's energy over an interval is the
// sum over its event classes of events x energy per event, plus its static
// power x the interval. The events are the counters the simulation already
// keeps (each block reports them, common/energy_activity.h); energy is
// computed from them at the end of a run and between frames, never sampled.
// Plain C++, no SystemC. README.md walks through the data flow and the
// parameter table (energy_params.def).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/energy_activity.h"
#include "config/config.h"

namespace tessera {

struct EventEnergy {
  std::string event;
  double picojoules = 0;
};

struct UnitEnergyParams {
  std::string unit;
  std::vector<EventEnergy> events;
  double static_milliwatts = 0;
};

struct UnitEnergy {
  std::string unit;
  std::map<std::string, double> event_joules;  // per event class
  double static_joules = 0;
  double dynamic_joules() const;
  double total_joules() const { return dynamic_joules() + static_joules; }
};

class EnergyModel {
 public:
  // Throws ConfigError naming the key (power.<unit>.<event>_pj) when an
  // energy or a static power is negative or not finite.
  explicit EnergyModel(std::vector<UnitEnergyParams> units);

  // The parameters (power.*), the one place their defaults live
  // (energy_params.def), and the model they configure.
  static ParamGroup parameters();
  static EnergyModel from_config(const Config& config);
  static EnergyModel defaults();

  const std::vector<UnitEnergyParams>& units() const { return m_units; }

  // The energy of `activity` over `seconds` (the static power over the
  // activity's clocked_seconds where it has them). A unit or an event class
  // the model does not know is a programming error (std::logic_error naming
  // it): every counter a block reports must have its parameter.
  UnitEnergy energy(const UnitActivity& activity, double seconds) const;
  std::vector<UnitEnergy> unit_energies(const EnergyActivity& activity, double seconds) const;

 private:
  const UnitEnergyParams& unit(const std::string& name) const;

  std::vector<UnitEnergyParams> m_units;
};

// The activity between two snapshots of the same blocks (`later` - `earlier`,
// unit by unit and event by event, and the clocked time); a unit missing
// from `earlier` counts from zero.
EnergyActivity activity_difference(const EnergyActivity& later, const EnergyActivity& earlier);

}  // namespace tessera
