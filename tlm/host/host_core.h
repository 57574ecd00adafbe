// What an instruction-set simulator running as the host's program
// (host.model=iss, tools/soc_sim/launch/iss_launcher.cpp) needs of the host beyond the
// device layer (HostApi): the instruction side's bus reads, the core's two
// interrupt inputs, the wait for an interrupt, CP15's control of the data
// cache and its c7 operations, and access to memory that takes no time (a
// debugger's, semihosting's). Host implements it; the
// launcher gets it from soc_sim (IssHost), not through AppEnvironment.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/data_hit_lines.h"

namespace tessera {

class HostCore {
 public:
  virtual ~HostCore() = default;

  // An instruction-side read over the bus at the host's local time: an
  // instruction-cache line fill or one uncached fetch. The core stalls
  // until it completes. Throws BusError (a prefetch abort).
  virtual void fetch(uint32_t address, unsigned bytes) = 0;

  // The core's IRQ and FIQ inputs (the interrupt controller's outputs) as
  // the kernel sees them now.
  virtual bool irq_asserted() = 0;
  virtual bool fiq_asserted() = 0;
  // CP15's wait for interrupt: the core idles until IRQ or FIQ is asserted
  // (returns at once if one is), whether or not the CPSR masks it.
  virtual void wait_for_interrupt() = 0;

  // Memory as a debugger sees it: no time, no cache or bus activity.
  // false where no target answers (an unmapped address).
  virtual bool debug_read(uint32_t address, uint8_t* data, unsigned bytes) = 0;
  virtual bool debug_write(uint32_t address, const uint8_t* data, unsigned bytes) = 0;

  // System memory as the instruction fetches read it: directly (the bus's
  // DMI), where every bus master's writes land (the core's stores, the
  // DMA's, a debugger's, semihosting's), so that a fetch sees what memory
  // holds whoever wrote it. `data` holds the `size` bytes from `base`;
  // size 0 where no direct access reaches `address` (the launcher then
  // fetches by debug access). Valid until the host calls the function given
  // to on_direct_memory_invalidated (the memory withdrew its DMI).
  struct DirectMemory {
    const uint8_t* data = nullptr;
    uint32_t base = 0;
    uint64_t size = 0;
  };
  virtual DirectMemory direct_memory(uint32_t /*address*/) { return {}; }
  virtual void on_direct_memory_invalidated(const std::function<void()>& /*callback*/) {}

  // CP15 c1's data-side bits (ARM922T TRM, ARM DDI 0184B: register 1 of
  // the CP15 chapter, and 4.3):
  // C switches the data cache (off: its contents are kept but not looked up,
  // every data access is uncached, reads on the bus after the write buffer
  // has drained, writes through the write buffer); RR selects round-robin
  // replacement (clear, as at reset: pseudo-random).
  virtual void set_data_cache_control(bool enabled, bool round_robin) = 0;
  // CP15 c7's data-side operations (TRM 2.3.11), at the host's local time:
  // invalidating drops lines, dirty or not, and takes no time; cleaning
  // posts a line's dirty data (the line or its dirty half) to the write
  // buffer, by address or by c7's index (the way in bits 31:26, the set in
  // bits 6:5 for the ARM922T's geometry), and invalidates it with
  // `invalidate`; draining the write buffer stalls until its writes have
  // completed.
  virtual void invalidate_data_cache() = 0;
  virtual void invalidate_data_line(uint32_t address) = 0;
  virtual void clean_data_line(uint32_t address, bool invalidate) = 0;
  virtual void clean_data_index(uint32_t index, bool invalidate) = 0;
  virtual void drain_write_buffer() = 0;

  // The cycles the host has charged as busy (the launcher charges the
  // instructions' cycles less those its accesses were charged), and for the
  // program's profile the cycles it has stalled on the bus and its data
  // cache's misses, so far.
  virtual uint64_t busy_cycles() const = 0;
  virtual double stalled_cycles() const = 0;
  virtual uint64_t data_cache_misses() const = 0;
  // Where those three counters live, for a launcher that reads them around
  // every load and store (the ISS launcher's HostMemory::Charged): loads
  // through these pointers give the same values as the three calls, without
  // the calls. stalled_cycles() is *stall_ticks / period_ticks, as doubles.
  // The pointers stay valid as long as the core. Every core gives them
  // (the launcher refuses one that does not).
  struct CounterLocations {
    const uint64_t* busy_cycles = nullptr;
    const uint64_t* stall_ticks = nullptr;
    uint64_t period_ticks = 1;
    const uint64_t* data_cache_misses = nullptr;
  };
  virtual CounterLocations counter_locations() const = 0;

  // The data-cache lines whose hits the launcher may serve itself
  // (DataHitLines: the host's own charges and counts, done in place), kept
  // up to date by the host from this call on; null from a core that grants
  // none (a test's stand-in). Asked once, before the program runs.
  virtual DataHitLines* data_hit_lines() { return nullptr; }

  // The program's own statistics (instructions, CPI, caches, its profile),
  // asked for whenever the host's are written: stats.json's host.iss.
  virtual void set_program_statistics(std::function<nlohmann::json()> statistics) = 0;

  // Whether a VCD is being written; then the program counter, the function
  // holding it (an index the launcher names) and the CPSR (mode, state,
  // interrupt masks, flags) are traced at the host's local time: host.pc,
  // host.function, host.cpsr.
  virtual bool tracing_program() const = 0;
  virtual void trace_program(uint32_t pc, uint32_t function, uint32_t cpsr) = 0;
  // The functions' names by index (soc_sim writes them beside the VCD).
  virtual void set_function_names(std::vector<std::string> names) = 0;
  // Whether the launcher keeps its per-function profile of the program
  // (soc_sim --iss-profile: stats.json's host.iss.profile). It costs the
  // simulation a look-up per instruction, so it is off unless asked for;
  // no other figure depends on it.
  virtual bool profiling_program() const { return false; }
};

}  // namespace tessera
