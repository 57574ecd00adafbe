// Arm922tTiming: the ARM922T's cycles per instruction (the ARM9TDMI's
// pipeline: the Technical Reference Manual's cycle counts and load-use
// interlocks) and its instruction-cache tag model, plain C++ over what the
// core reports of each step (ArmCore::last_step). The data side is the
// launcher's (the SoC host's data-cache tag model and write buffer, or none);
// tlm/host/iss/README.md, "Timing", lists each rule with its source.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>

#include "host/cache_replacement.h"
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
  // charges the fill), and the line it replaced is evicted().
  bool access(uint32_t address, bool round_robin);
  // The line the last miss replaced, or INVALID if its way was empty.
  uint32_t evicted() const { return m_evicted; }
  static constexpr uint32_t INVALID = 1;  // line addresses are multiples of 32: bit 0 is free
  // A fetch from the line of the last hit: a hit, counted, without a search
  // (false: not that line; nothing counted, access() decides).
  bool hit_last_line(uint32_t address) {
    if ((address & ~(LINE_BYTES - 1)) != m_last_line) return false;
    ++m_hits;
    return true;
  }
  // The hit counter, if `address` is in the line of the last hit (the next
  // fetch from it is a hit, counted and nothing else); else nullptr.
  uint64_t* last_line_hits(uint32_t address) {
    return (address & ~(LINE_BYTES - 1)) == m_last_line ? &m_hits : nullptr;
  }
  void invalidate_all();
  void invalidate_line(uint32_t address);

  uint64_t hits() const { return m_hits; }
  uint64_t misses() const { return m_misses; }

 private:
  std::array<uint32_t, SETS * WAYS> m_lines{};  // line address per way, set-major; INVALID if empty
  // The model's speed, not the cache's behaviour: lines known to be
  // resident, direct-mapped by line number (a slot holds a resident line or
  // INVALID), so that most hits on another line than the last need no
  // search of a 64-way set. Cleared with the line it holds.
  static constexpr unsigned RESIDENT_SLOTS = 512;
  std::array<uint32_t, RESIDENT_SLOTS> m_resident{};
  static unsigned resident_slot(uint32_t line) { return (line / LINE_BYTES) % RESIDENT_SLOTS; }
  CacheReplacement m_replacement{SETS, WAYS};
  uint32_t m_last_line = INVALID;  // the line of the last hit: consecutive fetches skip the search
  uint32_t m_evicted = INVALID;
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

  // Stall cycles of an instruction fetch at `address` (0 on a hit). Inline:
  // one per instruction; a fetch from the line of the one before is a hit
  // without a search.
  unsigned fetch(uint32_t address) {
    if ((m_cp15 == nullptr || m_cp15->instruction_cache_enabled()) && m_icache.hit_last_line(address)) return 0;
    return fetch_other_line(address);
  }
  // The hit counter a fetch from `address` only counts on (the cache on, the
  // line that of the last hit), for a port's ResidentLines; else nullptr.
  uint64_t* resident_hits(uint32_t address) {
    if (m_cp15 != nullptr && !m_cp15->instruction_cache_enabled()) return nullptr;
    return m_icache.last_line_hits(address);
  }
  // The port's ResidentLines, all revoked whenever the cache's answer may
  // change (invalidated, the control register written), and a line the
  // cache evicts revoked.
  void revoke_on_change(ResidentLines* lines) { m_resident = lines; }
  // Makes line fills (32 bytes at the line's address) and uncached fetches
  // (the word) calls of `fill`, a bus read whose time is the caller's,
  // instead of TimingParams' cycle figures: fetch() then returns 0 for them.
  // What `fill` throws (a bus error) passes through fetch().
  using Fill = std::function<void(uint32_t address, unsigned bytes)>;
  void on_fill(Fill fill) { m_fill = std::move(fill); }
  // Cycles of the step the core just made, interlocks included (the fetch's
  // stall is fetch()'s). One per instruction.
  // Always inline: as a call (GCC's choice in the SoC launcher's loop) it
  // cost the simulation a sixth of its time.
  __attribute__((always_inline)) unsigned step(const StepInfo& info) {
    ++m_instructions;
    unsigned interlock = 0;
    if (m_load_register >= 0 && info.executed && !info.exception && (info.reads >> m_load_register) & 1u)
      interlock = m_load_age == 0 && m_load_narrow ? 2 : 1;
    const unsigned base = base_cycles(info);
    // The next instruction's interlock state.
    if (info.executed && !info.exception && info.loaded >= 0 && !info.pc_written) {
      m_load_register = static_cast<uint8_t>(info.loaded);  // 0..14 here
      m_load_age = 0;
      m_load_narrow = info.narrow_load;
    } else if (m_load_register >= 0 && m_load_age == 0 && m_load_narrow && interlock == 0 && base == 1) {
      m_load_age = 1;  // a byte/halfword load still interlocks the instruction after next
    } else {
      m_load_register = -1;
    }
    m_interlock_cycles += interlock;
    m_cycles += base + interlock;
    return base + interlock;
  }

  // The ARM9TDMI's multiplier cycles for a multiplier operand, one per 8
  // significant bits (early termination): 1 if its bits 31:8 are all zero
  // (or, signed, all one), 2 for bits 31:16, 3 for bits 31:24, 4 otherwise
  // (ARM9TDMI TRM, the instruction cycle summary's multiply rows).
  static unsigned multiplier_cycles(uint32_t multiplier, bool is_signed) {
    const uint32_t value = is_signed && (multiplier & 0x80000000u) ? ~multiplier : multiplier;
    if ((value >> 8) == 0) return 1;
    if ((value >> 16) == 0) return 2;
    if ((value >> 24) == 0) return 3;
    return 4;
  }

  uint64_t instructions() const { return m_instructions; }
  uint64_t cycles() const { return m_cycles; }  // steps' cycles plus fetch stalls
  uint64_t interlock_cycles() const { return m_interlock_cycles; }
  uint64_t fetch_stall_cycles() const { return m_fetch_stall_cycles; }
  const InstructionCache& icache() const { return m_icache; }

  // CP15 c7's instruction-side operations.
  void invalidate_instruction_cache() override {
    revoke();
    m_icache.invalidate_all();
  }
  void invalidate_instruction_line(uint32_t address) override {
    revoke();
    m_icache.invalidate_line(address);
  }
  void control_written(uint32_t /*control*/) override { revoke(); }

 private:
  unsigned fetch_other_line(uint32_t address);
  void revoke() {
    if (m_resident != nullptr) m_resident->revoke_all();
  }
  // The rules of the README's table, as a table (a switch here costs the
  // simulation a mispredicted jump per instruction): the cycles of each
  // class without and with the PC written, to which a register shift, MSR's
  // control field, the multiplier and the LDM/STM register count add.
  static constexpr uint8_t FIXED_CYCLES[][2] = {
      {1, 1},  // none
      {1, 3},  // data_processing: + 2 for the refill
      {1, 1},  // multiply: + m, + 1 with the accumulate
      {2, 2},  // multiply_long: + m, + 1 with the accumulate
      {1, 5},  // load: LDR pc 5
      {1, 1},  // store
      {0, 4},  // load_multiple: + n (at least 2); n + 4 with the PC
      {0, 0},  // store_multiple: + n (at least 2)
      {2, 2},  // swap
      {1, 3},  // branch: taken 3 (Thumb's B<cond> not taken: 1)
      {2, 2},  // status_read
      {1, 1},  // status_write: 3 with the control field
      {2, 2},  // coprocessor_read
      {1, 1},  // coprocessor_write
      {3, 3},  // exception
  };
  static_assert(sizeof FIXED_CYCLES / sizeof FIXED_CYCLES[0] == static_cast<size_t>(InsnClass::exception) + 1,
                "a row per instruction class");
  // Always inline: GCC left it a call in the SoC launcher's loop (a tenth
  // of soc_sim's time once the core ran by blocks).
  __attribute__((always_inline)) static unsigned base_cycles(const StepInfo& info) {
    if (info.exception) return 3;  // SWI, undefined, aborts, interrupts: the vector's pipeline refill
    if (!info.executed) return 1;  // a failed condition: the instruction passes through as a no-op
    const auto kind = info.kind;
    unsigned cycles = FIXED_CYCLES[static_cast<unsigned>(kind)][info.pc_written ? 1 : 0] +
                      (info.register_shift ? 1 : 0) + (info.control_write ? 2 : 0);
    if (kind == InsnClass::multiply || kind == InsnClass::multiply_long)
      cycles += multiplier_cycles(info.multiplier, info.signed_multiply) + (info.accumulate ? 1 : 0);
    else if (kind == InsnClass::load_multiple || kind == InsnClass::store_multiple)
      cycles +=
          kind == InsnClass::load_multiple && info.pc_written ? info.registers : std::max<unsigned>(info.registers, 2);
    return cycles;
  }

  TimingParams m_params;
  const Cp15* m_cp15 = nullptr;
  InstructionCache m_icache;
  ResidentLines* m_resident = nullptr;
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
// A fetch grants its line (ResidentLines) when the other port has it as
// plain memory and the instruction cache would hit it again (or there is
// no timing layer). `Memory`: the other port's type, deduced from the
// constructor's argument; where that class is final (BareMachine) the
// forwarded calls are direct, not virtual.
template <class Memory = IssMemory>
class TimedFetch : public IssMemory {
 public:
  TimedFetch(Memory& memory, Arm922tTiming* timing) : m_memory(memory), m_timing(timing) {
    if (m_timing != nullptr) m_timing->revoke_on_change(&m_resident);
  }
  ~TimedFetch() override {
    if (m_timing != nullptr) m_timing->revoke_on_change(nullptr);
  }
  TimedFetch(const TimedFetch&) = delete;
  TimedFetch& operator=(const TimedFetch&) = delete;
  bool read(uint32_t address, unsigned bytes, uint32_t& value) override { return m_memory.read(address, bytes, value); }
  bool write(uint32_t address, unsigned bytes, uint32_t value) override {
    return m_memory.write(address, bytes, value);
  }
  // A line of plain memory (code_line) is read here, where it is granted;
  // any other fetch is the other port's.
  bool fetch(uint32_t address, unsigned bytes, uint32_t& value) override {
    if (m_timing != nullptr) m_timing->fetch(address);
    const uint32_t line = ResidentLines::line_of(address);
    uint64_t* fetches = m_timing != nullptr ? m_timing->resident_hits(address) : &m_untimed_fetches;
    const uint8_t* data = fetches != nullptr ? m_memory.code_line(line) : nullptr;
    if (data == nullptr) return m_memory.fetch(address, bytes, value);
    value = load_little_endian(data + (address - line), bytes);
    m_resident.grant(line, data, fetches);
    return true;
  }
  ResidentLines* resident_lines() override { return &m_resident; }

 private:
  Memory& m_memory;
  Arm922tTiming* m_timing;
  ResidentLines m_resident;
  uint64_t m_untimed_fetches = 0;  // the count of a grant without a timing layer: nobody reads it
};

}  // namespace tessera::iss
