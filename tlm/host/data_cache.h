// Tag model of the ARM922T data cache (ARM922T TRM, ARM DDI 0184B, 4.3
// "DCache and write buffer"): set associative, round-robin or pseudo-random
// replacement, allocation on read misses only, two dirty bits per line (one
// per half), so that a write-back is the whole line or the dirty half. Data
// stay in system memory; the cache only decides what costs a bus access.
// Whether a store hit leaves the line dirty (write-back) or not
// (write-through) is the caller's: it knows the region's policy.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "host/cache_replacement.h"
#include "host/data_hit_lines.h"

namespace tessera {

class DataCache {
 public:
  // Dirty data to write to memory: the whole line, or the dirty half of it.
  struct WriteBack {
    uint32_t address = 0;
    unsigned bytes = 0;  // 0: nothing to write
  };
  struct Result {
    bool hit;
    WriteBack victim;  // a miss's replaced line, if it held dirty data
  };

  // size 0 disables the cache (every access misses and nothing allocates).
  DataCache(unsigned size_bytes, unsigned line_bytes, unsigned ways, bool round_robin = true);

  bool enabled() const { return m_sets != 0; }
  unsigned line_bytes() const { return m_line_bytes; }
  uint32_t line_address(uint32_t address) const { return address & ~(m_line_bytes - 1); }
  // CP15 c1's RR bit: round-robin (true) or pseudo-random replacement.
  void set_round_robin(bool round_robin) { m_round_robin = round_robin; }
  bool round_robin() const { return m_round_robin; }

  // A read: on a miss the line is allocated (the caller fills it, after
  // writing back the victim's dirty data). Hits, the host's common case,
  // are found here without a call.
  Result read(uint32_t address) {
    if (enabled() && find(address)) {
      ++m_hits;
      return {true, {}};
    }
    return read_miss(address);
  }
  // Whether read(address) would miss and replace a line that holds no
  // dirty data, changing nothing (the frame copy's blocks taken in closed
  // form are such misses: Host::copy_words).
  bool clean_miss(uint32_t address) {
    if (!enabled() || find(address) != nullptr) return false;
    const uint32_t tag = address >> m_line_shift;
    const unsigned set_index = tag & (m_sets - 1);
    const Line& victim =
        m_lines[static_cast<size_t>(set_index) * m_ways + m_replacement.peek(set_index, m_round_robin)];
    return !victim.valid || victim.dirty == 0;
  }
  // A write of `bytes` from `address` (within one line): true on a hit,
  // which marks the halves of the line it covers dirty if `write_back`; a
  // miss does not allocate.
  bool write(uint32_t address, bool write_back = true, unsigned bytes = 1) {
    Line* line = enabled() ? find(address) : nullptr;
    if (!line) return false;
    if (write_back) {
      const uint32_t last = std::min(address + std::max(bytes, 1u) - 1, line_address(address) + m_line_bytes - 1);
      line->dirty |= static_cast<uint8_t>(half_bit(address) | half_bit(last));
    }
    ++m_hits;
    return true;
  }

  // CP15 c7's data-side operations (ARM922T TRM 2.3.11). Clean: the line's
  // dirty data is returned for writing back and the line marked clean (and
  // invalid with `invalidate`); by address (a miss does nothing), or by
  // index in c7's index format: the way in the top bits (31:26 with 64
  // ways), the set above the line offset (6:5 with 4 sets of 32 bytes).
  WriteBack clean_line(uint32_t address, bool invalidate);
  WriteBack clean_index(uint32_t index, bool invalidate);
  // Invalidate: the line (or every line) is dropped, dirty or not.
  void invalidate_line(uint32_t address);
  void invalidate_all();

  // Counts further hits on a line just looked up (a span's other elements).
  void count_hits(uint64_t n) { m_hits += n; }

  uint64_t hits() const { return m_hits; }
  uint64_t misses() const { return m_misses; }
  // Where hits() is kept, and the dirty bits of the resident line holding
  // `address` (null if none): for DataHitLines.
  uint64_t* hits_location() { return &m_hits; }
  uint8_t* dirty_bits(uint32_t address) {
    Line* line = enabled() ? find(address) : nullptr;
    return line ? &line->dirty : nullptr;
  }
  // The granted lines (or null) that a line leaving the cache, replaced or
  // invalidated, is revoked from.
  void revoke_on_change(DataHitLines* granted) { m_granted = granted; }
  // Where misses() is kept (HostCore::counter_locations).
  const uint64_t* misses_location() const { return &m_misses; }
  // Dirty lines written back: evicted or cleaned.
  uint64_t writebacks() const { return m_writebacks; }

 private:
  struct Line {
    uint32_t tag = 0;
    bool valid = false;
    uint8_t dirty = 0;  // bit 0: the first half of the line, bit 1: the second
  };
  // The resident line holding `address`, or null: one load from the tag
  // table for the tags it covers, a search of the set above them.
  Line* find(uint32_t address) {
    const uint32_t tag = address >> m_line_shift;
    if (tag < m_where.size()) return m_where[tag] ? &m_lines[m_where[tag] - 1] : nullptr;
    return tag < INDEXED_TAGS ? nullptr : find_in_set(tag);  // an allocated tag this low would be in the table
  }
  Line* find_in_set(uint32_t tag);
  // Inline (below): returned from a call, the Result went through the
  // stack as stores the load of its return registers could not forward.
  Result read_miss(uint32_t address);
  // The dirty bit of the half of its line that `address` is in.
  unsigned half_bit(uint32_t address) const { return 1u << ((address >> (m_line_shift - 1)) & 1u); }
  WriteBack take_dirty(Line& line, bool invalidate);

  unsigned m_line_bytes;
  unsigned m_ways;
  unsigned m_sets;
  unsigned m_line_shift;
  unsigned m_way_shift;  // the way's position in a c7 index
  bool m_round_robin;
  std::vector<Line> m_lines;  // set-major
  CacheReplacement m_replacement;
  // Where each resident line is, by tag (line number + 1, 0: absent): the
  // model's speed, not the cache's behaviour. Lookups, hits and misses alike,
  // cost one load instead of a search of a 64-way set. The table covers the
  // tags below INDEXED_TAGS (128 MiB with 32-byte lines) and grows with the
  // highest tag allocated; lines above it are found by searching their set.
  static constexpr uint32_t INDEXED_TAGS = 1u << 22;
  std::vector<uint32_t> m_where;
  void forget(const Line& line);
  void remember(const Line& line, size_t index);
  void revoke(const Line& line) {
    if (m_granted != nullptr && line.valid) m_granted->revoke(line.tag << m_line_shift);
  }
  DataHitLines* m_granted = nullptr;
  uint64_t m_hits = 0;
  uint64_t m_misses = 0;
  uint64_t m_writebacks = 0;
};

inline DataCache::Result DataCache::read_miss(uint32_t address) {
  ++m_misses;
  if (!enabled()) return {false, {}};
  const uint32_t tag = address >> m_line_shift;
  const unsigned set_index = tag & (m_sets - 1);
  const size_t index = static_cast<size_t>(set_index) * m_ways + m_replacement.victim(set_index, m_round_robin);
  Line& victim = m_lines[index];
  const WriteBack dirty = take_dirty(victim, true);  // the victim revoked
  victim = {tag, true, 0};
  remember(victim, index);
  return {false, dirty};
}

}  // namespace tessera
