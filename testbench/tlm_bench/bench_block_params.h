// The host and the array of the TLM benches: the blocks' declared defaults,
// with the bench's clocks (round periods, so that expected times are whole
// numbers of cycles) and small, round figures of their own. Apart from
// bench_params.h so that a bench of the bus and memory alone needs neither
// block.
#pragma once

#include <cstdint>

#include <systemc>

#include "array/array_processor.h"
#include "host/host.h"

namespace tessera::test {

// A host of `clock_period` whose operations cost one cycle each (a branch
// three, a float division 130), loads and stores one; an 8 KiB data cache
// of 32-byte lines, 64 ways, round-robin, write-back; the ARM922T's write
// buffer (16 words, 4 addresses); four interrupt lines; cacheable from 0
// for `cacheable_bytes`.
inline HostParams bench_host_params(sc_core::sc_time clock_period, uint32_t cacheable_bytes) {
  HostParams p = HostParams::defaults();
  p.clock_period = clock_period;
  p.op_cycles.fill(1);
  p.op_cycles[static_cast<size_t>(Op::branch)] = 3;
  p.op_cycles[static_cast<size_t>(Op::fdiv)] = 130;
  p.load_cycles = 1;
  p.store_cycles = 1;
  p.dcache_bytes = 8192;
  p.dcache_line_bytes = 32;
  p.dcache_ways = 64;
  p.write_buffer_words = 16;
  p.write_buffer_addresses = 4;
  p.dcache_round_robin = true;
  p.write_through = false;
  p.irq_lines = 4;
  p.cacheable_base = 0;
  p.cacheable_size = cacheable_bytes;
  return p;
}

// An array of `clock_period` with 256 words of program memory and a limit
// of 100,000 cycles a program.
inline ArrayParams bench_array_params(sc_core::sc_time clock_period) {
  ArrayParams p = ArrayParams::defaults();
  p.clock_period = clock_period;
  p.program_words = 256;
  p.max_program_cycles = 100000;
  return p;
}

}  // namespace tessera::test
