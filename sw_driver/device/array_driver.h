// Driver of the array processor: the AC (program load, start, wait) and the
// CIU (CMEM reads and writes with the J2210's WriteMem32 layout and the
// host-side packing the study needed). Every access is a bus transaction of
// the host model, and the address computation and packing the ARM does
// around it are charged by rows of the measured cost table (sw_driver/
// costs), so what a renderer pays to talk to the array is what the board paid.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "array/array_regs.h"
#include "array/program.h"
#include "costs/host_cost.h"
#include "device/app_environment.h"
#include "soc/memory_map.h"

namespace tessera {

// A program that stopped with an error: the AC's code and word.
class ArrayError : public std::runtime_error {
 public:
  ArrayError(const std::string& what, uint32_t code, uint32_t pc) : std::runtime_error(what), m_code(code), m_pc(pc) {}
  uint32_t code() const { return m_code; }
  uint32_t pc() const { return m_pc; }

 private:
  uint32_t m_code;
  uint32_t m_pc;
};

class ArrayDriver {
 public:
  // Reads the array's geometry from the AC's registers.
  explicit ArrayDriver(AppEnvironment& env);

  unsigned columns() const { return m_columns; }
  unsigned rows() const { return m_rows; }
  unsigned cus() const { return m_columns * m_rows; }
  unsigned groups_per_row() const { return m_groups_per_row; }
  unsigned cmem_bytes() const { return m_cmem_bytes; }
  unsigned program_words() const { return m_program_words; }
  double clock_hz() const { return m_clock_khz * 1e3; }
  // Registers per CU (array.registers), read from the AC when asked.
  unsigned registers();

  // Writes an image into program memory from word `at`. Throws
  // std::invalid_argument if it does not fit.
  void load(const std::vector<uint64_t>& words, unsigned at = 0);
  // The same for an assembled program, whose CMEM variables are checked
  // once here against this array's CMEM (std::out_of_range naming the
  // variable otherwise), so that the per-access path need not check them.
  void load(const ap::Program& program, unsigned at = 0);
  // Starts the program at word `entry` (the AC must be idle).
  void start(unsigned entry);
  // Sleeps until the AC's interrupt, clears it, and returns the program's
  // array cycles; throws ArrayError naming the code and word if it failed.
  uint32_t wait();
  // Polls STATUS until the AC is idle instead of sleeping (the host keeps
  // working between polls in a real driver; here each poll is a bus read).
  uint32_t poll();
  uint32_t run(unsigned entry) {
    start(entry);
    return wait();
  }

  // The bus address of CMEM address `a` of CU group (i, j).
  uint32_t cmem_address(unsigned i, unsigned j, unsigned a) const {
    return memory_map::array_cmem.base + array_regs::cmem_offset(j * m_groups_per_row + i, a, m_cmem_bytes);
  }

  // Throws std::out_of_range, naming the access and the array's size,
  // unless CMEM addresses a .. a + bytes - 1 of group (i, j) are in the
  // array. write32/read32 do not check their arguments, as the study's
  // driver did not on every access: a loop checks once the last group and
  // the last address it reaches (the first are no smaller), and every
  // function below checks its own arguments once.
  void check_access(unsigned i, unsigned j, unsigned a, unsigned bytes = 1) const;

  // WriteMem32 / ReadMem32: one word, byte k to/from CU column 4i+k of row
  // j: the address computation and the access, nothing else. Natively the
  // ARM's cycles for the call outside the bus access are charged (the
  // measured cost table's rows array_write32 and array_read32).
  void write32(unsigned i, unsigned j, unsigned a, uint32_t value);
  uint32_t read32(unsigned i, unsigned j, unsigned a);

  // Four 16-bit values, one per CU of group (i, j), big-endian at a, a+1:
  // packed by the host into a word of high bytes (at a) and one of low
  // bytes (at a+1), as the study did.
  void write16(unsigned i, unsigned j, unsigned a, const std::array<uint16_t, 4>& values);
  std::array<uint16_t, 4> read16(unsigned i, unsigned j, unsigned a);

  // Every CU at once, in CU order (row by row): one value per CU.
  // `row`: the measured cost table's row charged per word for the packing
  // around the access (a caller whose loop around the call differs from
  // the study's has its own).
  void write_all8(unsigned a, const std::vector<uint8_t>& per_cu,
                  costs::HostCost row = costs::HostCost::array_pack_word);
  void write_all16(unsigned a, const std::vector<uint16_t>& per_cu);
  std::vector<uint8_t> read_all8(unsigned a, costs::HostCost row = costs::HostCost::array_unpack_word);
  std::vector<uint16_t> read_all16(unsigned a);
  // The same byte in every CU (a constant the array cannot load itself).
  // Natively the words go to the host as one store train
  // (HostApi::write32_train), the cycles before each the row
  // array_write32's, as write32 charges them; on the ISS the loop of
  // write32 calls is the instructions.
  void fill8(unsigned a, uint8_t value);

  // The shared lookup table of lut (tlm/array/README.md, "The lookup
  // table"): its entries (LUT_ENTRIES: array.lut.entries, 0 with
  // array.features.lut off), read from the AC when asked; `entries` written
  // from index `first` on, as one LUT_INDEX write and a LUT_DATA write per
  // entry (the AC steps the index). Throws std::invalid_argument naming
  // array.lut.entries if they do not fit the table. The ARM's loop around
  // the writes is not charged (no row of the cost table measures it; a
  // table is written once per filter).
  unsigned lut_entries();
  void write_lut(unsigned first, const std::vector<uint16_t>& entries);

  // The per-CU constants of the study, at the addresses a program declares
  // for them (a negative address: the program has none): the CU's column
  // (XPOS) and row (YPOS), 0x01, 0xff, and counter tables 0..n-1.
  struct Constants {
    int xpos = -1, ypos = -1, one = -1, ones = -1;
    int x_counter = -1;
    unsigned x_counter_length = 0;
    int y_counter = -1;
    unsigned y_counter_length = 0;
  };
  void write_constants(const Constants& constants);

 private:
  HostApi& m_host;
  unsigned m_columns, m_rows, m_cmem_bytes, m_program_words, m_clock_khz;
  unsigned m_groups_per_row;
  bool m_irq_enabled = false;
#if !defined(TESSERA_HOST_ISS)
  // fill8's store train: each group's word and the cycles charged before it.
  std::vector<uint32_t> m_train_values;
  std::vector<uint64_t> m_train_cycles;
#endif
};

}  // namespace tessera
