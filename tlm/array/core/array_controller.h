// The array controller's functional core, plain C++: the program memory
// (kept decoded, each word decoded when it is written), the loop counters,
// and the run of a program from an entry point to its halt on the CU array,
// counting the cycles each instruction costs.
//
// A program runs as a whole: run() executes every instruction at once and
// returns the cycles the array took; the SystemC wrapper (array_processor.h)
// turns them into time at the array clock.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "array/core/cu_array.h"
#include "array/isa/ap_isa.h"

namespace tessera::ap {

// Cycles of every instruction (array.cycles.<mnemonic>) and the extra
// cycles of an RM-form instruction with an operand in CMEM.
struct CycleTable {
  std::array<unsigned, OPCODE_COUNT> cycles{};
  unsigned cmem_operand = 1;
  static CycleTable defaults();
  // The cost of one execution of `instruction`.
  unsigned cost(const Instruction& instruction) const;
};

struct RunResult {
  bool ok = true;
  uint64_t cycles = 0;
  uint64_t instructions = 0;
  std::string error;  // when !ok: what went wrong, naming the program word
  unsigned error_pc = 0;
};

// Totals over every program run since construction (or clear_activity()).
struct ControllerActivity {
  uint64_t programs = 0;
  uint64_t failed_programs = 0;
  uint64_t cycles = 0;
  uint64_t instructions = 0;  // instructions broadcast (loop iterations counted)
  std::array<uint64_t, OPCODE_COUNT> instruction_mix{};
  std::array<uint64_t, STAGE_COUNT> stage_cycles{};
  std::vector<uint64_t> word_cycles;  // per program word: the profile
  std::vector<uint64_t> word_executions;
};

class ArrayController {
 public:
  ArrayController(const ArrayGeometry& geometry, const CycleTable& cycles, unsigned program_words,
                  uint64_t max_program_cycles);

  CuArray& array() { return m_array; }
  const CuArray& array() const { return m_array; }
  unsigned program_words() const { return static_cast<unsigned>(m_words.size()); }

  // Program memory. write_word() returns false when `index` is beyond it.
  bool write_word(unsigned index, uint64_t word);
  uint64_t word(unsigned index) const { return index < m_words.size() ? m_words[index] : 0; }
  // Writes `words` from `first` on; false (nothing written) if they do not fit.
  bool load(unsigned first, const std::vector<uint64_t>& words);

  // Runs from `entry` to a halt. On an error (an undecodable word, a loop
  // the AC cannot run, a CMEM address out of range, more than
  // max_program_cycles) the run stops at that word with ok == false; the
  // state keeps what the instructions before it did.
  RunResult run(unsigned entry);

  const ControllerActivity& activity() const { return m_activity; }

 private:
  struct Slot {
    Instruction instruction;
    unsigned cost = 0;
    std::string error;  // why the word cannot run, or empty
  };
  void decode_slot(unsigned index);

  ArrayGeometry m_geometry;
  CycleTable m_cycles;
  uint64_t m_max_cycles;
  CuArray m_array;
  std::vector<uint64_t> m_words;
  std::vector<Slot> m_slots;
  ControllerActivity m_activity;
};

}  // namespace tessera::ap
