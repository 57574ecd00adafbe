#include "host/iss/arm922t_timing.h"

namespace tessera::iss {

bool InstructionCache::access(uint32_t address, bool round_robin) {
  const uint32_t line = address & ~(LINE_BYTES - 1);
  if (line == m_last_line) {
    ++m_hits;
    return true;
  }
  uint32_t& resident = m_resident[resident_slot(line)];
  if (resident == line) {
    ++m_hits;
    m_last_line = line;
    return true;
  }
  const unsigned set = (line / LINE_BYTES) % SETS;
  uint32_t* ways = &m_lines[static_cast<size_t>(set) * WAYS];
  for (unsigned way = 0; way < WAYS; ++way)
    if (ways[way] == line) {
      ++m_hits;
      m_last_line = line;
      resident = line;
      return true;
    }
  ++m_misses;
  const unsigned victim = m_replacement.victim(set, round_robin);
  m_evicted = ways[victim];
  if (m_resident[resident_slot(ways[victim])] == ways[victim]) m_resident[resident_slot(ways[victim])] = INVALID;
  ways[victim] = line;
  m_last_line = line;
  resident = line;
  return false;
}

void InstructionCache::invalidate_all() {
  m_lines.fill(INVALID);
  m_resident.fill(INVALID);
  m_last_line = INVALID;
}

void InstructionCache::invalidate_line(uint32_t address) {
  const uint32_t line = address & ~(LINE_BYTES - 1);
  const unsigned set = (line / LINE_BYTES) % SETS;
  for (unsigned way = 0; way < WAYS; ++way)
    if (m_lines[static_cast<size_t>(set) * WAYS + way] == line)
      m_lines[static_cast<size_t>(set) * WAYS + way] = INVALID;
  if (m_last_line == line) m_last_line = INVALID;
  if (m_resident[resident_slot(line)] == line) m_resident[resident_slot(line)] = INVALID;
}

unsigned Arm922tTiming::fetch_other_line(uint32_t address) {
  unsigned stall = 0;
  if (m_cp15 != nullptr && !m_cp15->instruction_cache_enabled()) {
    if (m_fill)
      m_fill(address & ~3u, 4);
    else
      stall = m_params.uncached_fetch_cycles;
  } else {
    const bool round_robin = m_cp15 != nullptr && (m_cp15->control() & Cp15::CONTROL_RR) != 0;
    if (!m_icache.access(address, round_robin)) {
      if (m_resident != nullptr && m_icache.evicted() != InstructionCache::INVALID)
        m_resident->revoke(m_icache.evicted());
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

}  // namespace tessera::iss
