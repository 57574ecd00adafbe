// The bus and the memory of the TLM benches: the blocks' declared defaults,
// with the clock the bench runs at (a round period, so that expected times
// are whole numbers of cycles) and the memory's size and wait states.
#pragma once

#include <cstdint>

#include <systemc>

#include "bus/ahb_bus.h"
#include "mem/memory.h"

namespace tessera::test {

inline BusParams bench_bus_params(sc_core::sc_time clock_period) {
  BusParams p = BusParams::defaults();
  p.clock_period = clock_period;
  return p;
}

// A 32-bit memory on a bus of `clock_period`.
inline MemoryParams bench_memory_params(uint64_t size_bytes, sc_core::sc_time clock_period,
                                        unsigned first_access_cycles, unsigned beat_cycles = 1) {
  MemoryParams p = MemoryParams::defaults();
  p.size_bytes = size_bytes;
  p.clock_period = clock_period;
  p.width_bytes = 4;
  p.first_access_cycles = first_access_cycles;
  p.beat_cycles = beat_cycles;
  return p;
}

}  // namespace tessera::test
