// BareMachine: the ISS alone on a flat RAM with a console byte register and
// an exit register (tests/host/iss_programs/test.ld's machine), no SystemC,
// no timing: what the ISS's functional tests and its speed benchmark run.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "host/iss/arm_core.h"
#include "host/iss/elf_image.h"
#include "host/iss/gdb_server.h"

namespace tessera::iss {

class BareMachine final : public IssMemory, public DebugMemory {
 public:
  static constexpr uint32_t CONSOLE = 0xf0000000u, EXIT = 0xf0000004u;

  explicit BareMachine(uint32_t ram_bytes = 1u << 20) : m_ram(ram_bytes) {}

  // Loads the image (ElfError if it does not fit) and resets the core at its entry.
  void load(const ElfImage& image, ArmCore& core) {
    image.check_fits(0, m_ram.size(), "the bare machine's RAM");
    for (const ElfSegment& segment : image.segments)
      std::copy(segment.bytes.begin(), segment.bytes.end(), m_ram.begin() + segment.address);
    core.reset();
    core.set_reg(15, image.entry);
  }

  // Steps until the program writes the exit register or the limit is reached;
  // true if it exited. `after` is called after each instruction (a timing
  // layer's step).
  template <class After>
  bool run(ArmCore& core, uint64_t instruction_limit, After&& after) {
    if (m_exited || instruction_limit == 0) return m_exited;
    uint64_t steps = 0;
    // Always inline, and so the callers' `after`: GCC otherwise left the
    // timing layer's step a call, a fifth of iss_run --timing's time.
    core.run([&]() __attribute__((always_inline)) {
      after();
      return !m_exited && ++steps < instruction_limit;
    });
    return m_exited;
  }
  bool run(ArmCore& core, uint64_t instruction_limit) {
    return run(core, instruction_limit, [] {});
  }

  // Console output as the program writes it: handed to `sink` at each
  // newline and whenever CONSOLE_CHUNK bytes without one have gathered (the
  // rest at flush_console()). Without a sink it is kept whole: console().
  static constexpr size_t CONSOLE_CHUNK = 4096;
  void stream_console(std::function<void(const std::string& text)> sink) { m_console_sink = std::move(sink); }
  void flush_console() {
    if (m_console_sink && !m_console.empty()) m_console_sink(m_console);
    if (m_console_sink) m_console.clear();
  }

  const std::string& console() const { return m_console; }
  bool exited() const { return m_exited; }
  uint32_t status() const { return m_status; }

  bool read(uint32_t address, unsigned size, uint32_t& value) override {
    if (uint64_t{address} + size > m_ram.size()) return false;
    value = load_little_endian(&m_ram[address], size);
    return true;
  }
  // Every line of the RAM is plain memory: a fetch grants its line
  // (ResidentLines), counting nothing that anyone reads.
  bool fetch(uint32_t address, unsigned size, uint32_t& value) override {
    if (!BareMachine::read(address, size, value)) return false;
    const uint32_t line = ResidentLines::line_of(address);
    if (const uint8_t* data = BareMachine::code_line(line)) m_resident.grant(line, data, &m_line_fetches);
    return true;
  }
  ResidentLines* resident_lines() override { return &m_resident; }
  const uint8_t* code_line(uint32_t line) override {
    return uint64_t{line} + ResidentLines::BYTES <= m_ram.size() ? &m_ram[line] : nullptr;
  }
  // A debugger's access reaches the RAM only (not the console or exit register).
  bool debug_read(uint32_t address, uint8_t* data, unsigned bytes) override {
    if (uint64_t{address} + bytes > m_ram.size()) return false;
    std::copy_n(m_ram.begin() + address, bytes, data);
    return true;
  }
  bool debug_write(uint32_t address, const uint8_t* data, unsigned bytes) override {
    if (uint64_t{address} + bytes > m_ram.size()) return false;
    std::copy_n(data, bytes, m_ram.begin() + address);
    return true;
  }
  bool write(uint32_t address, unsigned size, uint32_t value) override {
    if (address == CONSOLE) {
      m_console += static_cast<char>(value);
      if (m_console_sink && (static_cast<char>(value) == '\n' || m_console.size() >= CONSOLE_CHUNK)) flush_console();
      return true;
    }
    if (address == EXIT) {
      m_exited = true;
      m_status = value;
      return true;
    }
    if (uint64_t{address} + size > m_ram.size()) return false;
    store_little_endian(&m_ram[address], size, value);
    return true;
  }

 private:
  std::vector<uint8_t> m_ram;
  std::string m_console;
  std::function<void(const std::string&)> m_console_sink;
  bool m_exited = false;
  uint32_t m_status = 0;
  ResidentLines m_resident;
  uint64_t m_line_fetches = 0;
};

}  // namespace tessera::iss
