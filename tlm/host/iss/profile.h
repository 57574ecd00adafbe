// Profile: where a program's time goes on the ISS, per function of its
// symbol table (ElfImage::functions): instructions, the core's cycles, the
// cycles it stalled on the bus (the host's line fills, uncached accesses,
// write-buffer waits), and instruction- and data-cache misses. The
// launcher charges each step to the function holding its PC; consecutive
// steps in one function cost a range check. Plain C++.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/iss/elf_image.h"

namespace tessera::iss {

class Profile {
 public:
  struct Entry {
    uint64_t instructions = 0;
    uint64_t cycles = 0;      // the core's (Arm922tTiming's)
    double stall_cycles = 0;  // the host's, waiting on the bus (its clock's ticks need not be whole cycles)
    uint64_t icache_misses = 0;
    uint64_t dcache_misses = 0;
  };
  struct Row {
    std::string function;  // demangled
    uint32_t address;
    Entry entry;
  };

  explicit Profile(const std::vector<ElfFunction>& functions);

  // The entry of the function holding `pc` (one for every address outside
  // the symbol table's functions).
  Entry& at(uint32_t pc) {
    if (pc - m_last_start < m_last_size) return *m_last;
    return find(pc);
  }
  // Whether `pc` is in the function `at` last returned (its entry is the
  // one `at` would return): a caller charging runs of instructions at a
  // time asks this of each.
  bool holds(uint32_t pc) const { return pc - m_last_start < m_last_size; }
  // The index of the function `at` last returned (the VCD's function
  // signal): its position in the symbol table's functions, or their count
  // for an address outside them.
  uint32_t last_index() const { return m_last_index; }

  // Functions with any instruction, most cycles (with stalls) first.
  std::vector<Row> rows() const;
  // `count` of them.
  std::vector<Row> top(size_t count) const;
  // The functions' names, demangled, by index; the last is "(outside the symbol table)".
  std::vector<std::string> names() const;

  static std::string demangle(const std::string& name);

 private:
  Entry& find(uint32_t pc);
  // The binary search: sets m_last_index, m_last_start and m_last_size.
  void search(uint32_t pc);

  // The model's speed, not the profile's figures: the last look-ups by the
  // exact PC they were made for (a call's target, a return address), so that
  // a PC leaving and re-entering the same functions over and over (calls in
  // a loop) needs no binary search of the symbol table. A slot holds what
  // the search gave for its PC, which the table (fixed) always gives again.
  struct Memo {
    bool valid = false;
    uint32_t pc = 0, start = 0, size = 0, index = 0;
  };
  static constexpr unsigned MEMO_SLOTS = 1024;
  std::vector<Memo> m_memo = std::vector<Memo>(MEMO_SLOTS);

  std::vector<ElfFunction> m_functions;
  std::vector<Entry> m_entries;  // one per function, then the one outside them
  uint32_t m_last_start = 0, m_last_size = 0, m_last_index = 0;
  Entry* m_last;
};

}  // namespace tessera::iss
