// A traced boolean whose changes may be scheduled at future times. Loosely
// timed initiators run ahead of simulated time, so the bus knows when a
// request, grant or release happens before the kernel gets there; this module
// replays those edges at their own times so a VCD shows them where they are.
// Owners only schedule edges while tracing is on, so it costs nothing otherwise.
#pragma once

#include <map>

#include <systemc>

namespace tessera {

class TimedTrace : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(TimedTrace);

  sc_core::sc_signal<bool> signal;

  explicit TimedTrace(sc_core::sc_module_name name);

  // Schedules `value` at absolute time `when` (now if `when` is in the past).
  void set_at(bool value, const sc_core::sc_time& when);

 private:
  void apply();

  std::multimap<sc_core::sc_time, bool> m_pending;
  sc_core::sc_event m_wake;
};

}  // namespace tessera
