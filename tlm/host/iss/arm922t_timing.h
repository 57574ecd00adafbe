// Arm922tTiming: the ARM922T's cycles per instruction (the ARM9TDMI's
// pipeline: the Technical Reference Manual's cycle counts and load-use
// interlocks) and its instruction-cache tag model, plain C++ over what the
// core reports of each step (ArmCore::last_step). The data side is the
// launcher's (the SoC host's data-cache tag model and write buffer, or none);
// tlm/host/iss/README.md, "Timing", lists each rule with its source.
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "host/iss/arm_core.h"
#include "host/iss/cp15.h"

namespace tessera::iss {

// Tag model of the ARM922T's instruction cache: 8 KB, 64-way, 8-word lines,
// so 4 sets (the TRM's "segments", address bits 6:5); pseudo-random or
// round-robin replacement (CP15 c1's RR bit). Read-only: no dirty state.
class InstructionCache {
 public:
  static constexpr unsigned SIZE_BYTES = 8192, LINE_BYTES = 32, WAYS = 64;
  static constexpr unsigned SETS = SIZE_BYTES / (LINE_BYTES * WAYS);

  InstructionCache() { invalidate_all(); }

  // A fetch: true on a hit; on a miss the line is allocated (the caller
  // charges the fill).
  bool access(uint32_t address, bool round_robin);
  void invalidate_all();
  void invalidate_line(uint32_t address);

  uint64_t hits() const { return m_hits; }
  uint64_t misses() const { return m_misses; }

 private:
  static constexpr uint32_t INVALID = 1;        // line addresses are multiples of 32: bit 0 is free
  std::array<uint32_t, SETS * WAYS> m_lines{};  // line address per way, set-major; INVALID if empty
  std::array<uint8_t, SETS> m_round_robin{};
  uint16_t m_lfsr = 0xace1u;       // the pseudo-random victim's source
  uint32_t m_last_line = INVALID;  // the line of the last hit: consecutive fetches skip the search
  uint64_t m_hits = 0, m_misses = 0;
};

struct TimingParams {
  // Core cycles an instruction-cache line fill (8 words) stalls the core:
  // with the SoC's defaults (mem.first_access_cycles 3, one beat a bus
  // cycle, an address phase, bus at 96 MHz, host at 192 MHz) a 32-byte
  // burst takes 12 bus cycles = 24 core cycles, on an otherwise idle bus.
  unsigned line_fill_cycles = 24;
  // A fetch with the instruction cache off: a single-word read, 5 bus
  // cycles = 10 core cycles with the same defaults.
  unsigned uncached_fetch_cycles = 10;
};

class Arm922tTiming : public CacheMaintenance {
 public:
  explicit Arm922tTiming(TimingParams params = {}) : m_params(params) {}

  // The CP15 whose control register (I, RR) the cache obeys; without one the
  // instruction cache is on with pseudo-random replacement.
  void attach(const Cp15* cp15) { m_cp15 = cp15; }

  // Stall cycles of an instruction fetch at `address` (0 on a hit).
  unsigned fetch(uint32_t address);
  // Makes line fills (32 bytes at the line's address) and uncached fetches
  // (the word) calls of `fill`, a bus read whose time is the caller's,
  // instead of TimingParams' cycle figures: fetch() then returns 0 for them.
  // What `fill` throws (a bus error) passes through fetch().
  using Fill = std::function<void(uint32_t address, unsigned bytes)>;
  void on_fill(Fill fill) { m_fill = std::move(fill); }
  // Cycles of the step the core just made, interlocks included (the fetch's
  // stall is fetch()'s).
  unsigned step(const StepInfo& info);

  // The ARM9TDMI's multiplier cycles for a multiplier operand: 1 to 4, one
  // per 8 significant bits (early termination).
  static unsigned multiplier_cycles(uint32_t multiplier, bool is_signed);

  uint64_t instructions() const { return m_instructions; }
  uint64_t cycles() const { return m_cycles; }  // steps' cycles plus fetch stalls
  uint64_t interlock_cycles() const { return m_interlock_cycles; }
  uint64_t fetch_stall_cycles() const { return m_fetch_stall_cycles; }
  const InstructionCache& icache() const { return m_icache; }

  // CP15 c7's instruction-side operations.
  void invalidate_instruction_cache() override { m_icache.invalidate_all(); }
  void invalidate_instruction_line(uint32_t address) override { m_icache.invalidate_line(address); }

 private:
  unsigned base_cycles(const StepInfo& info) const;

  TimingParams m_params;
  const Cp15* m_cp15 = nullptr;
  InstructionCache m_icache;
  Fill m_fill;
  // The last load's destination while it can still interlock: the next
  // instruction (age 0), or for a byte, halfword or unaligned load the one
  // after (age 1) when the one between took a single cycle.
  int m_load_register = -1;
  unsigned m_load_age = 0;
  bool m_load_narrow = false;
  uint64_t m_instructions = 0, m_cycles = 0, m_interlock_cycles = 0, m_fetch_stall_cycles = 0;
};

// A memory port that charges each instruction fetch to a timing layer and
// forwards every access to another port (iss_run and the tests: the data
// side is that port's, at no cost beyond the instructions' own cycles).
class TimedFetch : public IssMemory {
 public:
  TimedFetch(IssMemory& memory, Arm922tTiming* timing) : m_memory(memory), m_timing(timing) {}
  bool read(uint32_t address, unsigned bytes, uint32_t& value) override { return m_memory.read(address, bytes, value); }
  bool write(uint32_t address, unsigned bytes, uint32_t value) override {
    return m_memory.write(address, bytes, value);
  }
  bool fetch(uint32_t address, unsigned bytes, uint32_t& value) override {
    if (m_timing != nullptr) m_timing->fetch(address);
    return m_memory.fetch(address, bytes, value);
  }

 private:
  IssMemory& m_memory;
  Arm922tTiming* m_timing;
};

}  // namespace tessera::iss
