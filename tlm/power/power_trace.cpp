#include "power/power_trace.h"

namespace tessera {

double PowerWindow::total_joules() const {
  double sum = 0;
  for (const UnitEnergy& unit : units) sum += unit.total_joules();
  return sum;
}

const PowerWindow& PowerTrace::close_window(const EnergyActivity& activity, double end_seconds) {
  const double start_seconds = m_last.end_seconds;
  m_last = {start_seconds, end_seconds,
            m_model.unit_energies(activity_difference(activity, m_previous), end_seconds - start_seconds)};
  m_previous = activity;
  ++m_windows;
  for (const UnitEnergy& unit : m_last.units) m_summed_joules[unit.unit] += unit.total_joules();
  return m_last;
}

}  // namespace tessera
