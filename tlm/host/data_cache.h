// Tag model of the ARM922T data cache: set associative, round-robin
// replacement, write back, allocation on read misses only (ARM922T). Data
// stay in system memory; the cache only decides what costs a bus access.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera {

class DataCache {
 public:
  struct Result {
    bool hit;
    bool evicted_dirty;        // a dirty line must be written back
    uint32_t evicted_address;  // its address
  };

  // size 0 disables the cache (every access misses and nothing allocates).
  DataCache(unsigned size_bytes, unsigned line_bytes, unsigned ways);

  bool enabled() const { return m_sets != 0; }
  unsigned line_bytes() const { return m_line_bytes; }
  uint32_t line_address(uint32_t address) const { return address & ~(m_line_bytes - 1); }

  // A read: on a miss the line is allocated (the caller fills it).
  Result read(uint32_t address);
  // A write: hit marks the line dirty; a miss does not allocate.
  bool write(uint32_t address);
  void invalidate_all();
  // Counts further hits on a line just looked up (a span's other elements).
  void count_hits(uint64_t n) { m_hits += n; }

  uint64_t hits() const { return m_hits; }
  uint64_t misses() const { return m_misses; }
  uint64_t writebacks() const { return m_writebacks; }

 private:
  struct Line {
    uint32_t tag = 0;
    bool valid = false;
    bool dirty = false;
  };
  Line* find(uint32_t address);

  unsigned m_line_bytes;
  unsigned m_ways;
  unsigned m_sets;
  unsigned m_line_shift;
  std::vector<Line> m_lines;       // set-major
  std::vector<unsigned> m_victim;  // round-robin pointer per set
  // Where each resident line is, by tag (line number + 1, 0: absent): the
  // model's speed, not the cache's behaviour. Lookups, hits and misses alike,
  // cost one load instead of a search of a 64-way set. The table covers the
  // tags below INDEXED_TAGS (128 MiB with 32-byte lines) and grows with the
  // highest tag allocated; lines above it are found by searching their set.
  static constexpr uint32_t INDEXED_TAGS = 1u << 22;
  std::vector<uint32_t> m_where;
  void forget(const Line& line);
  void remember(const Line& line, size_t index);
  uint64_t m_hits = 0;
  uint64_t m_misses = 0;
  uint64_t m_writebacks = 0;
};

}  // namespace tessera
