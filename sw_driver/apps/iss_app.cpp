#include "apps/iss_app.h"

#include <iostream>
#include <stdexcept>
#include <vector>

#include "host/iss/arm922t_timing.h"
#include "host/iss/arm_core.h"
#include "host/iss/bare_machine.h"
#include "host/iss/cp15.h"
#include "host/iss/elf_image.h"

namespace tessera {

namespace {

// The console and exit registers the test programs write (BareMachine's):
// taken by the launcher, not on the bus yet.
constexpr uint32_t CONSOLE = iss::BareMachine::CONSOLE, EXIT = iss::BareMachine::EXIT;
// Cycles added up before the host is told (the host's time moves in these
// steps between memory accesses).
constexpr uint64_t CHARGE_BATCH = 256;

// The ISS's memory port over the host's device layer. Data accesses are the
// host's (charged by its data-cache tag model, write buffer and bus; each
// charges the host's one issue cycle, host.cycles.load or .store);
// instruction fetches read a private copy of the executable segments, kept
// in step with the program's own stores into them, and are charged by the
// timing layer's instruction-cache model (a line fill as a cycle figure).
class HostMemory : public iss::IssMemory {
 public:
  HostMemory(HostApi& host, const iss::ElfImage& image, iss::Arm922tTiming& timing) : m_host(host), m_timing(timing) {
    for (const iss::ElfSegment& segment : image.segments)
      if (segment.executable) m_code.push_back({segment.address, segment.bytes});
  }

  void charge(uint64_t cycles) { m_pending += cycles; }
  void flush() {
    if (m_pending != 0) {
      m_host.compute(Op::alu, m_pending);
      m_pending = 0;
    }
  }
  uint64_t pending() const { return m_pending; }
  // Host accesses since the last call (each already charged its issue cycle).
  unsigned take_accesses() {
    const unsigned accesses = m_accesses;
    m_accesses = 0;
    return accesses;
  }

  // One call per instruction: a fetch from the segment of the one before
  // reads it directly.
  bool fetch(uint32_t address, unsigned bytes, uint32_t& value) override {
    m_pending += m_timing.fetch(address);
    const uint32_t offset = address - m_window_base;  // wraps below the base: then past the size
    if (uint64_t{offset} + bytes <= m_window_size) {
      value = iss::load_little_endian(m_window + offset, bytes);
      return true;
    }
    for (const Code& code : m_code)
      if (address >= code.base && uint64_t{address - code.base} + bytes <= code.bytes.size()) {
        m_window_base = code.base;
        m_window_size = code.bytes.size();
        m_window = code.bytes.data();
        value = iss::load_little_endian(m_window + (address - code.base), bytes);
        return true;
      }
    return read(address, bytes, value);  // code outside the image: through the data side
  }

  bool read(uint32_t address, unsigned bytes, uint32_t& value) override {
    flush();
    ++m_accesses;
    try {
      value = bytes == 4 ? m_host.read32(address) : bytes == 2 ? m_host.read16(address) : m_host.read8(address);
      return true;
    } catch (const BusError&) {
      m_fault_address = address;
      return false;
    }
  }

  bool write(uint32_t address, unsigned bytes, uint32_t value) override {
    if (address == CONSOLE) {
      m_console += static_cast<char>(value);
      if (static_cast<char>(value) == '\n') {
        std::cout << m_console << std::flush;
        m_console.clear();
      }
      return true;
    }
    if (address == EXIT) {
      m_exited = true;
      m_status = value;
      return true;
    }
    flush();
    ++m_accesses;
    try {
      if (bytes == 4)
        m_host.write32(address, value);
      else if (bytes == 2)
        m_host.write16(address, static_cast<uint16_t>(value));
      else
        m_host.write8(address, static_cast<uint8_t>(value));
    } catch (const BusError&) {
      m_fault_address = address;
      return false;
    }
    for (Code& code : m_code)  // a store into the code: the copy follows
      if (address >= code.base && address - code.base + bytes <= code.bytes.size())
        for (unsigned i = 0; i < bytes; ++i)
          code.bytes[address - code.base + i] = static_cast<uint8_t>(value >> (8 * i));
    return true;
  }

  bool exited() const { return m_exited; }
  uint32_t status() const { return m_status; }
  uint32_t fault_address() const { return m_fault_address; }
  void flush_console() {
    if (!m_console.empty()) std::cout << m_console << std::flush;
    m_console.clear();
  }

 private:
  struct Code {
    uint32_t base;
    std::vector<uint8_t> bytes;
  };
  HostApi& m_host;
  iss::Arm922tTiming& m_timing;
  std::vector<Code> m_code;
  // The segment of the last fetch (its bytes never move: stores change them in place).
  uint32_t m_window_base = 0;
  uint64_t m_window_size = 0;
  const uint8_t* m_window = nullptr;
  uint64_t m_pending = 0;
  unsigned m_accesses = 0;
  std::string m_console;
  bool m_exited = false;
  uint32_t m_status = 0;
  uint32_t m_fault_address = 0;
};

}  // namespace

bool is_elf_app(const std::string& name) {
  return name.size() > 4 && name.compare(name.size() - 4, 4, ".elf") == 0;
}

int run_elf_app(AppEnvironment& env, const std::string& path) {
  HostApi& host = *env.host;
  const iss::ElfImage image = iss::read_elf(path);
  image.check_fits(0, env.memory_bytes, "the populated system memory (mem.size_mib)");
  // The boot loader's copy of the image into system memory, charged as the
  // host's stores (a word at a time).
  for (const iss::ElfSegment& segment : image.segments) {
    size_t i = 0;
    for (; i + 4 <= segment.bytes.size(); i += 4)
      host.write32(segment.address + static_cast<uint32_t>(i),
                   uint32_t{segment.bytes[i]} | uint32_t{segment.bytes[i + 1]} << 8 |
                       uint32_t{segment.bytes[i + 2]} << 16 | uint32_t{segment.bytes[i + 3]} << 24);
    for (; i < segment.bytes.size(); ++i) host.write8(segment.address + static_cast<uint32_t>(i), segment.bytes[i]);
  }
  iss::Arm922tTiming timing;
  HostMemory memory(host, image, timing);
  iss::ArmCore core(memory);
  // c7's instruction-side operations reach the timing layer's instruction
  // cache; the data side is the host's (HostApi has no cache operations).
  iss::Cp15 cp15(core, &timing);
  core.set_coprocessors(&cp15);
  timing.attach(&cp15);
  // As a boot loader would: the caches on (CP15 c1's I and C) before the
  // program starts; the program may turn the instruction cache off.
  cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() | iss::Cp15::CONTROL_I | iss::Cp15::CONTROL_C);
  core.on_exception([&](iss::Exception exception, uint32_t pc) {
    const char* fault = iss::fault_name(exception);
    if (fault == nullptr) return;  // SWI and interrupts go to the program's vectors
    memory.flush_console();
    std::string text = path + ": " + fault + " at pc " + iss::address_text(pc);
    if (exception == iss::Exception::data_abort) text += ", address " + iss::address_text(memory.fault_address());
    throw std::runtime_error(text + " (the program has no handler: the ISS launcher stops it)");
  });
  core.reset();
  core.set_reg(15, image.entry);
  try {
    while (!memory.exited()) {
      core.step();
      // The instruction's cycles beyond the issue cycle of each host access
      // it made (those the host has charged already).
      const unsigned cycles = timing.step(core.last_step());
      const unsigned accesses = memory.take_accesses();
      memory.charge(cycles > accesses ? cycles - accesses : 0);
      if (memory.pending() >= CHARGE_BATCH) memory.flush();
    }
  } catch (const iss::IssError& error) {
    memory.flush_console();
    throw std::runtime_error(path + ": " + error.what());
  }
  memory.flush();
  memory.flush_console();
  return static_cast<int>(memory.status());
}

}  // namespace tessera
