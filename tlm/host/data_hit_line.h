// DataHitLine: a line of the host's data cache that a core model may serve
// hits from without calling the host (HostCore::data_hit_line), the data
// side's counterpart of the ISS's ResidentLine. Taking a load or store here
// does exactly what the host does for one that hits (Host::read_data,
// write_data, read_words, write_words): the compute cycles pending before it
// charged, then the access's issue cycles, the loads or stores and the
// cache's hits counted, a write-back store's half-line dirty bits set, the
// bytes moved in memory. An access is taken only when those charges leave
// the host's local time short of its budget, so no quantum ends within it;
// otherwise, and outside the line, the caller calls the host.
//
// The host grants the line of a hit (the whole line cacheable and in its
// direct window, no busy interval being noted for a timeline) and revokes
// it (line = NONE) whenever that may stop being true: a line allocated or
// invalidated in the cache, the cache switched, the window withdrawn, a
// timeline attached.
#pragma once

#include <cstdint>
#include <cstring>

namespace tessera {

struct DataHitLine {
  static constexpr uint32_t NONE = 1;  // line addresses are multiples of the line size: bit 0 is free
  uint32_t line = NONE;                // the granted line's address, or NONE
  uint32_t line_mask = ~0u;            // ~(line bytes - 1)
  unsigned half_shift = 0;             // log2(line bytes) - 1: an address's half of the line
  uint8_t* data = nullptr;             // the line's bytes in memory
  uint8_t* dirty = nullptr;            // its dirty bits (bit 0: first half), or null: stores call the host
  // The host's figures a hit moves (its own members, valid while it lives).
  uint64_t* busy_cycles = nullptr;
  uint64_t* measured_cycles = nullptr;  // cycles charged by compute_cycles (the pending cycles)
  uint64_t* local_ticks = nullptr;
  const uint64_t* budget_ticks = nullptr;
  uint64_t period_ticks = 1;
  uint64_t* loads = nullptr;
  uint64_t* stores = nullptr;
  uint64_t* hits = nullptr;
  unsigned load_cycles = 0;
  unsigned store_cycles = 0;

  // A load of 1, 2 or 4 aligned bytes (little-endian into `value`) after
  // `pending` compute cycles: true if taken (its issue cycles are
  // load_cycles).
  bool load(uint32_t address, unsigned bytes, uint64_t pending, uint32_t& value) {
    if ((address & line_mask) != line || (address & (bytes - 1)) != 0 || !charge(pending, load_cycles)) return false;
    ++*loads;
    ++*hits;
    const uint8_t* p = data + (address - line);
    value = bytes == 4   ? uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24
            : bytes == 2 ? uint32_t{p[0]} | uint32_t{p[1]} << 8
                         : uint32_t{p[0]};
    return true;
  }
  // A store of 1, 2 or 4 aligned bytes: true if taken (issue cycles store_cycles).
  bool store(uint32_t address, unsigned bytes, uint64_t pending, uint32_t value) {
    if (dirty == nullptr || (address & line_mask) != line || (address & (bytes - 1)) != 0 ||
        !charge(pending, store_cycles))
      return false;
    ++*stores;
    ++*hits;
    *dirty = static_cast<uint8_t>(*dirty | half_bit(address));
    uint8_t* p = data + (address - line);
    for (unsigned i = 0; i < bytes; ++i) p[i] = static_cast<uint8_t>(value >> (8 * i));
    return true;
  }
  // LDM: `count` words from an aligned `address`, all in the line, one load
  // each as the host counts them: true if taken (issue cycles
  // load_cycles * count).
  bool load_words(uint32_t address, uint32_t* words, unsigned count, uint64_t pending) {
    if (!words_in_line(address, count) || !charge(pending, uint64_t{load_cycles} * count)) return false;
    *loads += count;
    *hits += count;
    std::memcpy(words, data + (address - line), 4 * size_t{count});
    return true;
  }
  // STM: one store of `count` words, as the host counts it: true if taken
  // (issue cycles store_cycles * count + 1).
  bool store_words(uint32_t address, const uint32_t* words, unsigned count, uint64_t pending) {
    if (dirty == nullptr || !words_in_line(address, count) || !charge(pending, uint64_t{store_cycles} * count + 1))
      return false;
    ++*stores;
    *hits += count;
    for (unsigned i = 0; i < count; ++i) *dirty = static_cast<uint8_t>(*dirty | half_bit(address + 4 * i));
    std::memcpy(data + (address - line), words, 4 * size_t{count});
    return true;
  }

 private:
  unsigned half_bit(uint32_t address) const { return 1u << ((address >> half_shift) & 1u); }
  bool words_in_line(uint32_t address, unsigned count) const {
    return count != 0 && (address & line_mask) == line && (address & 3u) == 0 &&
           uint64_t{address - line} + 4 * uint64_t{count} <= ~line_mask + uint64_t{1};
  }
  // The host's charge of `pending` compute cycles and then `issue` busy
  // cycles, when neither reaches its budget (else nothing: false).
  bool charge(uint64_t pending, uint64_t issue) {
    const uint64_t ticks = (pending + issue) * period_ticks;
    if (*local_ticks + ticks >= *budget_ticks) return false;
    *measured_cycles += pending;
    *busy_cycles += pending + issue;
    *local_ticks += ticks;
    return true;
  }
};

}  // namespace tessera
