#include "host/iss/arm922t_timing.h"

namespace tessera::iss {

bool InstructionCache::access(uint32_t address, bool round_robin) {
  const uint32_t line = address & ~(LINE_BYTES - 1);
  if (line == m_last_line) {
    ++m_hits;
    return true;
  }
  const unsigned set = (line / LINE_BYTES) % SETS;
  uint32_t* ways = &m_lines[static_cast<size_t>(set) * WAYS];
  for (unsigned way = 0; way < WAYS; ++way)
    if (ways[way] == line) {
      ++m_hits;
      m_last_line = line;
      return true;
    }
  ++m_misses;
  unsigned victim;
  if (round_robin) {
    victim = m_round_robin[set];
    m_round_robin[set] = static_cast<uint8_t>((victim + 1) % WAYS);
  } else {  // a 16-bit Galois LFSR (x^16 + x^14 + x^13 + x^11 + 1): deterministic, so runs repeat
    m_lfsr = static_cast<uint16_t>((m_lfsr >> 1) ^ (-(m_lfsr & 1u) & 0xb400u));
    victim = m_lfsr % WAYS;
  }
  ways[victim] = line;
  m_last_line = line;
  return false;
}

void InstructionCache::invalidate_all() {
  m_lines.fill(INVALID);
  m_last_line = INVALID;
}

void InstructionCache::invalidate_line(uint32_t address) {
  const uint32_t line = address & ~(LINE_BYTES - 1);
  const unsigned set = (line / LINE_BYTES) % SETS;
  for (unsigned way = 0; way < WAYS; ++way)
    if (m_lines[static_cast<size_t>(set) * WAYS + way] == line)
      m_lines[static_cast<size_t>(set) * WAYS + way] = INVALID;
  if (m_last_line == line) m_last_line = INVALID;
}

unsigned Arm922tTiming::fetch(uint32_t address) {
  unsigned stall = 0;
  if (m_cp15 != nullptr && !m_cp15->instruction_cache_enabled()) {
    if (m_fill)
      m_fill(address & ~3u, 4);
    else
      stall = m_params.uncached_fetch_cycles;
  } else {
    const bool round_robin = m_cp15 != nullptr && (m_cp15->control() & (1u << 14)) != 0;  // RR
    if (!m_icache.access(address, round_robin)) {
      if (m_fill)
        m_fill(address & ~(InstructionCache::LINE_BYTES - 1), InstructionCache::LINE_BYTES);
      else
        stall = m_params.line_fill_cycles;
    }
  }
  m_fetch_stall_cycles += stall;
  m_cycles += stall;
  return stall;
}

// m: 1 if the multiplier's bits 31:8 are all zero (or, signed, all one), 2
// for bits 31:16, 3 for bits 31:24, 4 otherwise (ARM9TDMI TRM, the
// instruction cycle summary's multiply rows).
unsigned Arm922tTiming::multiplier_cycles(uint32_t multiplier, bool is_signed) {
  const uint32_t value = is_signed && (multiplier & 0x80000000u) ? ~multiplier : multiplier;
  if ((value >> 8) == 0) return 1;
  if ((value >> 16) == 0) return 2;
  if ((value >> 24) == 0) return 3;
  return 4;
}

unsigned Arm922tTiming::base_cycles(const StepInfo& info) const {
  if (info.exception) return 3;                     // SWI, undefined, aborts, interrupts: the vector's pipeline refill
  if (!info.executed) return 1;                     // a failed condition: the instruction passes through as a no-op
  const unsigned refill = info.pc_written ? 2 : 0;  // a PC written in Execute: two more fetches
  switch (info.kind) {
    case InsnClass::data_processing: return 1 + (info.register_shift ? 1 : 0) + refill;
    case InsnClass::multiply:
      return multiplier_cycles(info.multiplier, info.signed_multiply) + (info.accumulate ? 2 : 1);
    case InsnClass::multiply_long:
      return multiplier_cycles(info.multiplier, info.signed_multiply) + (info.accumulate ? 3 : 2);
    case InsnClass::load: return info.pc_written ? 5 : 1;
    case InsnClass::store: return 1;
    case InsnClass::load_multiple:
      if (info.pc_written) return info.registers + 4u;
      return info.registers == 1 ? 2 : info.registers;
    case InsnClass::store_multiple: return info.registers == 1 ? 2 : info.registers;
    case InsnClass::swap: return 2;
    case InsnClass::branch: return info.pc_written ? 3 : 1;  // Thumb's B<cond> not taken: 1
    case InsnClass::status_read: return 2;
    case InsnClass::status_write: return info.control_write ? 3 : 1;
    case InsnClass::coprocessor_read: return 2;
    case InsnClass::coprocessor_write: return 1;
    case InsnClass::exception: return 3;
    case InsnClass::none: return 1;
  }
  return 1;
}

unsigned Arm922tTiming::step(const StepInfo& info) {
  ++m_instructions;
  unsigned interlock = 0;
  if (m_load_register >= 0 && info.executed && !info.exception && (info.reads >> m_load_register) & 1u)
    interlock = m_load_age == 0 ? (m_load_narrow ? 2 : 1) : 1;
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

}  // namespace tessera::iss
