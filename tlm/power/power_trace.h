// A power trace: the run cut into consecutive windows, each unit's average
// power over each window. A window's energy is the EnergyModel's energy of
// the activity between the window's ends (activity_difference), the same
// computation as the run's and the frames' energies, so the windows'
// energies add up to the energy from the start to the last window's end.
// Plain C++, no SystemC: the SoC samples the activity at each window's end
// (tlm/soc) and traces the powers in the VCD.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/energy_activity.h"
#include "power/energy_model.h"

namespace tessera {

struct PowerWindow {
  double start_seconds = 0;
  double end_seconds = 0;
  std::vector<UnitEnergy> units;  // in the order of the activity

  double seconds() const { return end_seconds - start_seconds; }
  double total_joules() const;
  // Average power over the window, in milliwatts (0 for an empty window).
  double milliwatts(double joules) const { return seconds() > 0 ? joules / seconds() * 1e3 : 0.0; }
};

class PowerTrace {
 public:
  // `model` must outlive the trace.
  explicit PowerTrace(const EnergyModel& model) : m_model(model) {}

  // Closes the window from the previous window's end (0 for the first) to
  // `end_seconds`; `activity` is every unit's activity from the start of the
  // run to `end_seconds`.
  const PowerWindow& close_window(const EnergyActivity& activity, double end_seconds);

  const PowerWindow& last_window() const { return m_last; }
  size_t windows() const { return m_windows; }
  // Every closed window's energy, summed per unit.
  const std::map<std::string, double>& summed_joules() const { return m_summed_joules; }

 private:
  const EnergyModel& m_model;
  EnergyActivity m_previous;
  PowerWindow m_last;
  size_t m_windows = 0;
  std::map<std::string, double> m_summed_joules;
};

}  // namespace tessera
