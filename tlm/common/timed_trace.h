// A traced signal whose changes may be scheduled at future times. Loosely
// timed initiators run ahead of simulated time, so the bus knows when a
// request, grant or release happens before the kernel gets there; this module
// replays those edges at their own times so a VCD shows them where they are.
// Owners only schedule changes while tracing is on, so it costs nothing otherwise.
// TimedTrace carries a bit (busy, request); TimedWord a value (a program
// id, a stage code).
#pragma once

#include <cstdint>
#include <map>

#include <systemc>

namespace tessera {

template <class T>
class TimedSignal : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(TimedSignal);

  sc_core::sc_signal<T> signal;

  explicit TimedSignal(sc_core::sc_module_name name);

  // Schedules `value` at absolute time `when` (now if `when` is in the past).
  void set_at(T value, const sc_core::sc_time& when);

 private:
  void apply();

  std::multimap<sc_core::sc_time, T> m_pending;
  sc_core::sc_event m_wake;
};

// How many changes every TimedSignal has been given to schedule so far: an
// initiator running ahead of the kernel tells from it that none was
// scheduled while it was not looking (tlm/host: run-ahead).
uint64_t timed_signal_edges();

using TimedTrace = TimedSignal<bool>;
using TimedWord = TimedSignal<uint32_t>;

extern template class TimedSignal<bool>;
extern template class TimedSignal<uint32_t>;

}  // namespace tessera
