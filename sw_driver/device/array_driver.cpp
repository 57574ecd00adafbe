#include "device/array_driver.h"

#include <algorithm>
#include <cstring>

#include "array/array_regs.h"
#include "costs/host_cost.h"
#include "soc/irq_map.h"
#include "soc/memory_map.h"

namespace tessera {

namespace regs = array_regs;

namespace {

using costs::HostCost;

constexpr uint32_t AC = memory_map::array_regs.base;

}  // namespace

ArrayDriver::ArrayDriver(AppEnvironment& env)
    : m_host(*env.host),
      m_columns(m_host.read32(AC + regs::COLUMNS)),
      m_rows(m_host.read32(AC + regs::ROWS)),
      m_cmem_bytes(m_host.read32(AC + regs::CMEM_BYTES)),
      m_program_words(m_host.read32(AC + regs::PROGRAM_WORDS)),
      m_clock_khz(m_host.read32(AC + regs::CLOCK_KHZ)),
      m_groups_per_row(m_columns / 4) {}

unsigned ArrayDriver::registers() {
  return m_host.read32(AC + regs::REGISTERS);
}

void ArrayDriver::load(const std::vector<uint64_t>& words, unsigned at) {
  if (at > m_program_words || words.size() > m_program_words - at)
    throw std::invalid_argument("array program of " + std::to_string(words.size()) + " words at word " +
                                std::to_string(at) + " does not fit the AC's " + std::to_string(m_program_words) +
                                " words of program memory");
  // STM of up to four instruction words (eight registers) at a time.
  uint32_t halves[8];
  for (size_t first = 0; first < words.size(); first += 4) {
    const size_t count = std::min<size_t>(4, words.size() - first);
    for (size_t k = 0; k < count; ++k) {
      halves[2 * k] = static_cast<uint32_t>(words[first + k]);
      halves[2 * k + 1] = static_cast<uint32_t>(words[first + k] >> 32);
    }
    m_host.write_words(memory_map::array_program.base + static_cast<uint32_t>((at + first) * regs::PROGRAM_WORD_BYTES),
                       halves, static_cast<unsigned>(2 * count));
  }
}

void ArrayDriver::load(const ap::Program& program, unsigned at) {
  for (const auto& [name, variable] : program.variables)
    if (variable.address >= m_cmem_bytes || variable.size > m_cmem_bytes - variable.address)
      throw std::out_of_range(program.source_name + ": CMEM variable '" + name + "' (" + std::to_string(variable.size) +
                              " bytes at " + std::to_string(variable.address) + ") is outside the array's " +
                              std::to_string(m_cmem_bytes) + " bytes of CMEM (array.cmem_bytes)");
  load(program.words, at);
}

void ArrayDriver::start(unsigned entry) {
  costs::charge(m_host, HostCost::array_run);
  if (!m_irq_enabled) {
    m_host.write32(AC + regs::IRQ_ENABLE, regs::IRQ_DONE | regs::IRQ_ERROR);
    m_irq_enabled = true;
  }
  m_host.write32(AC + regs::ENTRY, entry);
  m_host.write32(AC + regs::START, 1);
}

namespace {

uint32_t finish(HostApi& host, uint32_t irq_status) {
  host.write32(AC + regs::IRQ_STATUS, irq_status);
  if ((irq_status & regs::IRQ_ERROR) != 0) {
    const uint32_t code = host.read32(AC + regs::ERROR_CODE);
    const uint32_t pc = host.read32(AC + regs::ERROR_PC);
    throw ArrayError("array program stopped with error " + std::to_string(code) + " at program word " +
                         std::to_string(pc) + " (the simulator's log says why)",
                     code, pc);
  }
  return host.read32(AC + regs::CYCLES);
}

}  // namespace

// The interrupt controller's line may still show the previous program's
// done interrupt when this program starts: the AC drops it when its
// IRQ_STATUS is cleared, but the controller sees the drop only when the
// simulation's kernel catches up with the host, which runs ahead of it in
// its quantum (tlm/common/peripheral.cpp). A host fast enough to start the
// next program and wait within that time wakes at once; only the AC's
// STATUS says whether this program has finished, so the wait goes on
// until it is idle (each check a bus read: the host's time moves on, the
// kernel catches up, the stale line falls and the next wait sleeps).
uint32_t ArrayDriver::wait() {
  do {
    m_host.wait_irq(irq_map::array);
  } while ((m_host.read32(AC + regs::STATUS) & regs::STATUS_BUSY) != 0);
  return finish(m_host, m_host.read32(AC + regs::IRQ_STATUS));
}

uint32_t ArrayDriver::poll() {
  while ((m_host.read32(AC + regs::STATUS) & regs::STATUS_BUSY) != 0) {
  }
  return finish(m_host, m_host.read32(AC + regs::IRQ_STATUS));
}

void ArrayDriver::check_access(unsigned i, unsigned j, unsigned a, unsigned bytes) const {
  if (i >= m_groups_per_row || j >= m_rows || a >= m_cmem_bytes || bytes > m_cmem_bytes - a)
    throw std::out_of_range("CMEM access at group (" + std::to_string(i) + ", " + std::to_string(j) + "), address " +
                            std::to_string(a) + (bytes > 1 ? " (" + std::to_string(bytes) + " bytes)" : "") +
                            " is outside the array (" + std::to_string(m_groups_per_row) + "x" +
                            std::to_string(m_rows) + " groups, " + std::to_string(m_cmem_bytes) + " bytes)");
}

// The study's WriteMem32 and ReadMem32: an MLA for the group number, an MLA
// with the address, the base added, the access. On the ISS these are the
// instructions; natively the measured cost table's rows array_write32
// and array_read32 are charged (the call outside its bus access).
void ArrayDriver::write32(unsigned i, unsigned j, unsigned a, uint32_t value) {
  costs::charge(m_host, HostCost::array_write32);
  m_host.write32(cmem_address(i, j, a), value);
}

uint32_t ArrayDriver::read32(unsigned i, unsigned j, unsigned a) {
  costs::charge(m_host, HostCost::array_read32);
  return m_host.read32(cmem_address(i, j, a));
}

// Packing four values into a word of their high bytes and one of their low
// bytes (array_pack16, array_unpack16).
void ArrayDriver::write16(unsigned i, unsigned j, unsigned a, const std::array<uint16_t, 4>& values) {
  check_access(i, j, a, 2);
  uint32_t high = 0, low = 0;
  for (unsigned k = 0; k < 4; ++k) {
    high |= uint32_t{static_cast<uint8_t>(values[k] >> 8)} << (8 * k);
    low |= uint32_t{static_cast<uint8_t>(values[k])} << (8 * k);
  }
  costs::charge(m_host, HostCost::array_pack16);
  write32(i, j, a, high);
  write32(i, j, a + 1, low);
}

std::array<uint16_t, 4> ArrayDriver::read16(unsigned i, unsigned j, unsigned a) {
  check_access(i, j, a, 2);
  const uint32_t high = read32(i, j, a);
  const uint32_t low = read32(i, j, a + 1);
  std::array<uint16_t, 4> values{};
  for (unsigned k = 0; k < 4; ++k)
    values[k] = static_cast<uint16_t>(((high >> (8 * k)) & 0xffu) << 8 | ((low >> (8 * k)) & 0xffu));
  costs::charge(m_host, HostCost::array_unpack16);
  return values;
}

void ArrayDriver::write_all8(unsigned a, const std::vector<uint8_t>& per_cu, HostCost row) {
  if (per_cu.size() != cus()) throw std::invalid_argument("write_all8: one value per CU expected");
  check_access(m_groups_per_row - 1, m_rows - 1, a);
  for (unsigned j = 0; j < m_rows; ++j)
    for (unsigned i = 0; i < groups_per_row(); ++i) {
      uint32_t word = 0;
      for (unsigned k = 0; k < 4; ++k) word |= uint32_t{per_cu[j * m_columns + 4 * i + k]} << (8 * k);
      costs::charge(m_host, row);
      write32(i, j, a, word);
    }
}

void ArrayDriver::write_all16(unsigned a, const std::vector<uint16_t>& per_cu) {
  if (per_cu.size() != cus()) throw std::invalid_argument("write_all16: one value per CU expected");
  for (unsigned j = 0; j < m_rows; ++j)
    for (unsigned i = 0; i < groups_per_row(); ++i) {
      std::array<uint16_t, 4> values{};
      for (unsigned k = 0; k < 4; ++k) values[k] = per_cu[j * m_columns + 4 * i + k];
      write16(i, j, a, values);
    }
}

std::vector<uint8_t> ArrayDriver::read_all8(unsigned a, HostCost row) {
  check_access(m_groups_per_row - 1, m_rows - 1, a);
  std::vector<uint8_t> values(cus());
  for (unsigned j = 0; j < m_rows; ++j)
    for (unsigned i = 0; i < groups_per_row(); ++i) {
      const uint32_t word = read32(i, j, a);
      for (unsigned k = 0; k < 4; ++k) values[j * m_columns + 4 * i + k] = static_cast<uint8_t>(word >> (8 * k));
      costs::charge(m_host, row);
    }
  return values;
}

std::vector<uint16_t> ArrayDriver::read_all16(unsigned a) {
  std::vector<uint16_t> values(cus());
  for (unsigned j = 0; j < m_rows; ++j)
    for (unsigned i = 0; i < groups_per_row(); ++i) {
      const std::array<uint16_t, 4> group = read16(i, j, a);
      for (unsigned k = 0; k < 4; ++k) values[j * m_columns + 4 * i + k] = group[k];
    }
  return values;
}

void ArrayDriver::fill8(unsigned a, uint8_t value) {
  check_access(m_groups_per_row - 1, m_rows - 1, a);
  costs::charge(m_host, HostCost::array_fill_word, uint64_t{m_rows} * m_groups_per_row);
#if defined(TESSERA_HOST_ISS)
  const uint32_t word = value * 0x01010101u;  // `value` in each of the group's four CUs
  for (unsigned j = 0; j < m_rows; ++j)
    for (unsigned i = 0; i < groups_per_row(); ++i) write32(i, j, a, word);
#else
  // Group j * groups_per_row + i, row by row: the groups' words one CMEM
  // window stride apart (array_regs::cmem_offset).
  const unsigned groups = m_rows * m_groups_per_row;
  // Every word holds `value` for each of its group's four CUs, so one
  // memset fills them (assign() took about a hundred instructions for 24
  // words, a loop of word stores ninety); the vectors are sized once.
  if (m_train_values.size() != groups) {
    m_train_values.resize(groups);
    m_train_cycles.resize(groups);
  }
  std::memset(m_train_values.data(), value, sizeof(uint32_t) * groups);
  costs::meter_cycles_each(HostCost::array_write32, m_train_cycles.data(), groups);
  m_host.write32_train(cmem_address(0, 0, a), array_regs::cmem_offset(1, 0, m_cmem_bytes), m_train_values.data(),
                       m_train_cycles.data(), groups);
#endif
}

unsigned ArrayDriver::lut_entries() {
  return m_host.read32(AC + regs::LUT_ENTRIES);
}

void ArrayDriver::write_lut(unsigned first, const std::vector<uint16_t>& entries) {
  const unsigned table = lut_entries();
  if (first > table || entries.size() > table - first)
    throw std::invalid_argument("lookup table entries " + std::to_string(first) + " .. " +
                                std::to_string(first + entries.size()) + " (exclusive) are beyond the table's " +
                                std::to_string(table) + " entries (array.lut.entries; 0: array.features.lut = false)");
  m_host.write32(AC + regs::LUT_INDEX, first);
  for (const uint16_t entry : entries) m_host.write32(AC + regs::LUT_DATA, entry);
}

void ArrayDriver::write_constants(const Constants& constants) {
  if (constants.xpos >= 0) {
    std::vector<uint8_t> columns(cus());
    for (unsigned lane = 0; lane < cus(); ++lane) columns[lane] = static_cast<uint8_t>(lane % m_columns);
    write_all8(static_cast<unsigned>(constants.xpos), columns);
  }
  if (constants.ypos >= 0) {
    std::vector<uint8_t> rows(cus());
    for (unsigned lane = 0; lane < cus(); ++lane) rows[lane] = static_cast<uint8_t>(lane / m_columns);
    write_all8(static_cast<unsigned>(constants.ypos), rows);
  }
  if (constants.one >= 0) fill8(static_cast<unsigned>(constants.one), 0x01);
  if (constants.ones >= 0) fill8(static_cast<unsigned>(constants.ones), 0xff);
  for (unsigned k = 0; constants.x_counter >= 0 && k < constants.x_counter_length; ++k)
    fill8(static_cast<unsigned>(constants.x_counter) + k, static_cast<uint8_t>(k));
  for (unsigned k = 0; constants.y_counter >= 0 && k < constants.y_counter_length; ++k)
    fill8(static_cast<unsigned>(constants.y_counter) + k, static_cast<uint8_t>(k));
}

}  // namespace tessera
