#include "host/data_cache.h"

#include <algorithm>

namespace tessera {

DataCache::DataCache(unsigned size_bytes, unsigned line_bytes, unsigned ways, bool round_robin)
    : m_line_bytes(line_bytes),
      m_ways(ways),
      m_sets(size_bytes == 0 ? 0 : size_bytes / (line_bytes * ways)),
      m_line_shift(0),
      m_way_shift(32),
      m_round_robin(round_robin),
      m_replacement(m_sets, ways) {
  while ((1u << m_line_shift) < line_bytes) ++m_line_shift;
  while (m_way_shift > 0 && (uint64_t{1} << (32 - m_way_shift)) < ways) --m_way_shift;
  m_lines.resize(static_cast<size_t>(m_sets) * m_ways);
}

DataCache::Line* DataCache::find_in_set(uint32_t tag) {
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

// The dirty bits decide whether the whole line, one half or nothing is
// written back (ARM922T TRM 4.3).
DataCache::WriteBack DataCache::take_dirty(Line& line, bool invalidate) {
  WriteBack write_back;
  if (line.valid && line.dirty != 0) {
    const unsigned half = m_line_bytes / 2;
    const uint32_t address = line.tag << m_line_shift;
    write_back.address = line.dirty == 2 ? address + half : address;
    write_back.bytes = line.dirty == 3 ? m_line_bytes : half;
    ++m_writebacks;
  }
  line.dirty = 0;
  if (invalidate) {
    revoke(line);
    forget(line);
    line = Line{};
  }
  return write_back;
}

DataCache::WriteBack DataCache::clean_line(uint32_t address, bool invalidate) {
  if (!enabled()) return {};
  Line* line = find(address);
  return line ? take_dirty(*line, invalidate) : WriteBack{};
}

DataCache::WriteBack DataCache::clean_index(uint32_t index, bool invalidate) {
  if (!enabled()) return {};
  const uint32_t way = m_way_shift < 32 ? index >> m_way_shift : 0;
  if (way >= m_ways) return {};  // no such way (a cache whose ways are not a power of two)
  const uint32_t set = (index >> m_line_shift) & (m_sets - 1);
  return take_dirty(m_lines[static_cast<size_t>(set) * m_ways + way], invalidate);
}

void DataCache::invalidate_line(uint32_t address) {
  if (Line* line = enabled() ? find(address) : nullptr) {
    revoke(*line);
    forget(*line);
    *line = Line{};
  }
}

void DataCache::invalidate_all() {
  if (m_granted != nullptr) m_granted->revoke_all();
  for (auto& line : m_lines) {
    forget(line);
    line = Line{};
  }
}

}  // namespace tessera
