#include "host/data_cache.h"

namespace tessera {

DataCache::DataCache(unsigned size_bytes, unsigned line_bytes, unsigned ways)
    : m_line_bytes(line_bytes), m_ways(ways),
      m_sets(size_bytes == 0 ? 0 : size_bytes / (line_bytes * ways)), m_line_shift(0) {
  while ((1u << m_line_shift) < line_bytes) ++m_line_shift;
  m_lines.resize(static_cast<size_t>(m_sets) * m_ways);
  m_victim.resize(m_sets, 0);
  m_hints.assign(kHints, nullptr);
}

DataCache::Line* DataCache::find(uint32_t address) {
  const uint32_t tag = address >> m_line_shift;
  if (m_last && m_last->valid && m_last->tag == tag) return m_last;
  Line*& hint = m_hints[tag & (kHints - 1)];
  if (hint && hint->valid && hint->tag == tag) return m_last = hint;
  Line* set = &m_lines[static_cast<size_t>(tag & (m_sets - 1)) * m_ways];
  for (unsigned way = 0; way < m_ways; ++way)
    if (set[way].valid && set[way].tag == tag) return m_last = hint = &set[way];
  return nullptr;
}

DataCache::Result DataCache::read(uint32_t address) {
  Result result{false, false, 0};
  if (!enabled()) {
    ++m_misses;
    return result;
  }
  if (find(address)) {
    ++m_hits;
    result.hit = true;
    return result;
  }
  ++m_misses;
  const uint32_t tag = address >> m_line_shift;
  const unsigned set_index = tag & (m_sets - 1);
  Line& victim = m_lines[static_cast<size_t>(set_index) * m_ways + m_victim[set_index]];
  m_victim[set_index] = (m_victim[set_index] + 1) % m_ways;
  if (victim.valid && victim.dirty) {
    result.evicted_dirty = true;
    result.evicted_address = victim.tag << m_line_shift;
    ++m_writebacks;
  }
  victim = {tag, true, false};
  m_last = m_hints[tag & (kHints - 1)] = &victim;
  return result;
}

bool DataCache::write(uint32_t address) {
  if (!enabled()) return false;
  Line* line = find(address);
  if (!line) return false;
  line->dirty = true;
  ++m_hits;
  return true;
}

void DataCache::invalidate_all() {
  for (auto& line : m_lines) line = Line{};
  m_last = nullptr;
  m_hints.assign(kHints, nullptr);
}

}  // namespace tessera
