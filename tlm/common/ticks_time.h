// An sc_time from a count of the kernel's time units (its resolution),
// inline. sc_time::from_value is a call into the SystemC library (about 25
// instructions behind a PLT jump: it also fixes the time resolution on its
// first use); on every bus transaction's path (the host's delay, the bus's
// wait for a clock edge, the memory's data phase) that was 2 % of an `arm`
// frame. sc_time is standard-layout with a single member, its value, so a
// pointer to it is a pointer to that value ([basic.compound]): the value is
// written there. Only once the resolution is fixed (from the end of
// elaboration on, where every caller is): before that, from_value.
#pragma once

#include <systemc>
#include <type_traits>

namespace tessera {

inline sc_core::sc_time ticks_time(sc_core::sc_time::value_type ticks) {
  static_assert(
      std::is_standard_layout_v<sc_core::sc_time> && sizeof(sc_core::sc_time) == sizeof(sc_core::sc_time::value_type),
      "sc_time is its value alone");
  sc_core::sc_time time;
  *reinterpret_cast<sc_core::sc_time::value_type*>(&time) = ticks;
  return time;
}

}  // namespace tessera
