#include "host/data_cache.h"

#include <algorithm>

namespace tessera {

DataCache::DataCache(unsigned size_bytes, unsigned line_bytes, unsigned ways)
    : m_line_bytes(line_bytes),
      m_ways(ways),
      m_sets(size_bytes == 0 ? 0 : size_bytes / (line_bytes * ways)),
      m_line_shift(0) {
  while ((1u << m_line_shift) < line_bytes) ++m_line_shift;
  m_lines.resize(static_cast<size_t>(m_sets) * m_ways);
  m_victim.resize(m_sets, 0);
}

DataCache::Line* DataCache::find(uint32_t address) {
  const uint32_t tag = address >> m_line_shift;
  if (tag < m_where.size()) return m_where[tag] ? &m_lines[m_where[tag] - 1] : nullptr;
  if (tag < INDEXED_TAGS) return nullptr;  // an allocated tag this low would be in the table
  Line* set = &m_lines[static_cast<size_t>(tag & (m_sets - 1)) * m_ways];
  for (unsigned way = 0; way < m_ways; ++way)
    if (set[way].valid && set[way].tag == tag) return &set[way];
  return nullptr;
}

void DataCache::forget(const Line& line) {
  if (line.valid && line.tag < m_where.size()) m_where[line.tag] = 0;
}

void DataCache::remember(const Line& line, size_t index) {
  if (line.tag >= INDEXED_TAGS) return;
  if (line.tag >= m_where.size()) m_where.resize(std::min<size_t>(INDEXED_TAGS, (size_t{line.tag} + 1) * 2), 0);
  m_where[line.tag] = static_cast<uint32_t>(index + 1);
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
  const size_t index = static_cast<size_t>(set_index) * m_ways + m_victim[set_index];
  Line& victim = m_lines[index];
  m_victim[set_index] = (m_victim[set_index] + 1) % m_ways;
  if (victim.valid && victim.dirty) {
    result.evicted_dirty = true;
    result.evicted_address = victim.tag << m_line_shift;
    ++m_writebacks;
  }
  forget(victim);
  victim = {tag, true, false};
  remember(victim, index);
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
  for (auto& line : m_lines) {
    forget(line);
    line = Line{};
  }
}

}  // namespace tessera
