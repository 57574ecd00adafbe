// DataHitLines: lines of the host's data cache that a core model may serve
// hits from without calling the host (HostCore::data_hit_lines), the data
// side's counterpart of the ISS's ResidentLines. Taking a load or store here
// does exactly what the host does for one that hits (Host::read_data,
// write_data, read_words, write_words): the compute cycles pending before it
// charged, then the access's issue cycles, the loads or stores and the
// cache's hits counted, a write-back store's half-line dirty bits set, the
// bytes moved in memory. An access is taken only when those charges leave
// the host's local time short of its budget, so no quantum ends within it;
// otherwise, and outside the granted lines, the caller calls the host.
//
// The host grants the line of each hit (the whole line cacheable and in its
// direct window, no busy interval being noted for a timeline) into a small
// direct-mapped table (a program's stack and the data it works on stay
// granted side by side), and revokes a line whenever a hit there may stop
// being that plain hit: the line replaced or invalidated in the cache; and
// every line when the cache is switched or invalidated, the window
// withdrawn or a timeline attached.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace tessera {

struct DataHitLines {
  static constexpr uint32_t NONE = 1;  // line addresses are multiples of the line size: bit 0 is free
  static constexpr unsigned SLOTS = 64;
  struct Line {
    uint32_t line = NONE;      // the granted line's address, or NONE
    uint8_t* data = nullptr;   // its bytes in memory
    uint8_t* dirty = nullptr;  // its dirty bits (bit 0: first half), or null: stores call the host
  };
  Line lines[SLOTS];        // by line number, modulo SLOTS
  unsigned line_shift = 0;  // log2(line bytes)
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

  // The host's side: whether a host has filled the figures in (it grants
  // lines from then on).
  bool attached() const { return local_ticks != nullptr; }
  void grant(uint32_t line, uint8_t* data, uint8_t* dirty) { slot(line) = {line, data, dirty}; }
  void revoke(uint32_t line) {
    Line& entry = slot(line);
    if (entry.line == line) entry.line = NONE;
  }
  void revoke_all() {
    for (Line& entry : lines) entry.line = NONE;
  }
  bool holds(uint32_t line) const { return lines[(line >> line_shift) % SLOTS].line == line; }

  // The core model's side. The issue cycles each kind of access is charged
  // (as the host charges them: an LDM a load per word, an STM a store cycle
  // per word and one more), for a caller that keeps account of them.
  uint64_t load_issue(unsigned words = 1) const { return uint64_t{load_cycles} * words; }
  uint64_t store_issue() const { return store_cycles; }
  uint64_t store_words_issue(unsigned words) const { return uint64_t{store_cycles} * words + 1; }
  // A load of 1, 2 or 4 aligned bytes (little-endian into `value`) after
  // `pending` compute cycles: true if taken (issue cycles load_issue()).
  bool load(uint32_t address, unsigned bytes, uint64_t pending, uint32_t& value) {
    const Line& entry = slot(address);
    if (line_of(address) != entry.line || (address & (bytes - 1)) != 0 || !charge(pending, load_issue())) return false;
    ++*loads;
    ++*hits;
    const uint8_t* p = entry.data + (address - entry.line);
    value = bytes == 4   ? uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24
            : bytes == 2 ? uint32_t{p[0]} | uint32_t{p[1]} << 8
                         : uint32_t{p[0]};
    return true;
  }
  // A store of 1, 2 or 4 aligned bytes: true if taken (issue cycles store_issue()).
  bool store(uint32_t address, unsigned bytes, uint64_t pending, uint32_t value) {
    const Line& entry = slot(address);
    if (line_of(address) != entry.line || entry.dirty == nullptr || (address & (bytes - 1)) != 0 ||
        !charge(pending, store_issue()))
      return false;
    ++*stores;
    ++*hits;
    *entry.dirty = static_cast<uint8_t>(*entry.dirty | half_bit(address));
    uint8_t* p = entry.data + (address - entry.line);
    for (unsigned i = 0; i < bytes; ++i) p[i] = static_cast<uint8_t>(value >> (8 * i));
    return true;
  }
  // LDM: `count` words from an aligned `address`, every line they reach
  // granted (a list may cross a line's end), one load as the host counts
  // it: true if taken (issue cycles load_issue(count)).
  bool load_words(uint32_t address, uint32_t* words, unsigned count, uint64_t pending) {
    if (!words_granted(address, count, false) || !charge(pending, load_issue(count))) return false;
    ++*loads;
    *hits += count;
    for_each_piece(address, count,
                   [&](uint8_t* p, unsigned first, unsigned n) { std::memcpy(words + first, p, 4 * size_t{n}); });
    return true;
  }
  // STM: one store of `count` words, as the host counts it: true if taken
  // (issue cycles store_words_issue(count)).
  bool store_words(uint32_t address, const uint32_t* words, unsigned count, uint64_t pending) {
    if (!words_granted(address, count, true) || !charge(pending, store_words_issue(count))) return false;
    ++*stores;
    *hits += count;
    for_each_piece(address, count, [&](uint8_t* p, unsigned first, unsigned n) {
      const Line& entry = slot(address + 4 * first);
      for (unsigned i = first; i < first + n; ++i)
        *entry.dirty = static_cast<uint8_t>(*entry.dirty | half_bit(address + 4 * i));
      std::memcpy(p, words + first, 4 * size_t{n});
    });
    return true;
  }

 private:
  Line& slot(uint32_t address) { return lines[(address >> line_shift) % SLOTS]; }
  uint32_t line_of(uint32_t address) const { return address >> line_shift << line_shift; }
  unsigned half_bit(uint32_t address) const { return 1u << ((address >> (line_shift - 1)) & 1u); }
  // Whether `count` words from `address` (aligned) lie in granted lines
  // (with their dirty bits, for a store).
  bool words_granted(uint32_t address, unsigned count, bool store) {
    if (count == 0 || (address & 3u) != 0 || uint64_t{address} + 4 * uint64_t{count} > uint64_t{1} << 32) return false;
    const uint32_t last = address + 4 * (count - 1);
    for (uint32_t line = line_of(address); line <= line_of(last); line += 1u << line_shift) {
      const Line& entry = slot(line);
      if (entry.line != line || (store && entry.dirty == nullptr)) return false;
      if (line == line_of(last)) break;  // the last line (also where adding a line would wrap)
    }
    return true;
  }
  // `f(data, first, n)` for each granted line's piece of the words: words
  // first .. first + n - 1, at `data` in memory.
  template <class F>
  void for_each_piece(uint32_t address, unsigned count, F f) {
    unsigned first = 0;
    while (first < count) {
      const uint32_t at = address + 4 * first;
      const Line& entry = slot(at);
      const unsigned left_in_line = ((entry.line + (1u << line_shift)) - at) / 4;
      const unsigned n = std::min(count - first, left_in_line);
      f(entry.data + (at - entry.line), first, n);
      first += n;
    }
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
