#include "launch/iss_launcher.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "host/host_core.h"
#include "host/iss/arm922t_timing.h"
#include "host/iss/arm_core.h"
#include "host/iss/bare_machine.h"
#include "host/iss/cp15.h"
#include "host/iss/elf_image.h"
#include "host/iss/gdb_server.h"
#include "host/iss/profile.h"
#include "host/iss/semihosting.h"
#include "runtime/boot_info.h"

namespace tessera {

namespace {

// The console and exit registers of the bare machine's test programs
// (tests/host/iss_programs): still taken here, beside semihosting, so that
// those programs run in the SoC unchanged.
constexpr uint32_t CONSOLE = iss::BareMachine::CONSOLE, EXIT = iss::BareMachine::EXIT;
// Cycles added up before the host is told (the host's time moves in these
// steps between memory accesses; the interrupt inputs are looked at as often).
constexpr uint64_t CHARGE_BATCH = 256;

// Console output without a newline is printed once this much has gathered.
constexpr size_t CONSOLE_CHUNK = 4096;

// The ISS's memory port over the host. Data accesses are the host's
// (HostApi: its data-cache tag model, write buffer and bus; each charges
// the host's one issue cycle, host.cycles.load or .store), those that hit
// the lines the host grants served here as the host would (DataHitLines,
// tlm/host/README.md). Instruction
// fetches read system memory itself, directly (HostCore::direct_memory,
// the bus's DMI), so that they see every bus master's writes: the
// program's stores, the DMA's, a debugger's (a private copy of the code
// would miss those of every master but the core); the decode cache
// compares each fetched word with the one it decoded. Their time is the
// timing layer's instruction cache, whose line fills are the host's
// instruction-side bus reads (HostCore::fetch). A fetch inside the window
// that the instruction cache would hit again grants its line to the core
// (iss::ResidentLines): the fetches after it from that line are the core's
// pointer reads, counted as the cache's hits, until the cache evicts it or
// the cache or the window changes.
class HostMemory : public iss::IssMemory, public iss::DebugMemory {
 public:
  HostMemory(HostApi& host, HostCore& core, iss::Arm922tTiming& timing)
      : m_host(host),
        m_core(core),
        m_timing(timing),
        m_counters(core.counter_locations()),
        m_hit(core.data_hit_lines()) {
    if (m_counters.busy_cycles == nullptr || m_counters.stall_ticks == nullptr ||
        m_counters.data_cache_misses == nullptr || m_counters.period_ticks == 0)
      throw std::logic_error("the ISS launcher: the host core does not say where its counters are");
    m_core.on_direct_memory_invalidated([this] {
      m_window_size = 0;
      m_resident.revoke_all();
    });
    m_timing.revoke_on_change(&m_resident);
    rebase();
  }
  ~HostMemory() override {
    m_timing.revoke_on_change(nullptr);
    m_core.on_direct_memory_invalidated(nullptr);
  }
  HostMemory(const HostMemory&) = delete;
  HostMemory& operator=(const HostMemory&) = delete;

  // The cycles not yet charged to the host: the timing layer's count since
  // it was last charged (flush) or a hit charged it (took_hit), less the
  // issue cycles the host charged for the accesses of the instructions
  // since (charge_instruction). Kept as that count's value then (m_base),
  // so that an instruction without an access adds nothing here: the timing
  // layer's step has counted its cycles already.
  uint64_t pending() const { return m_timing.cycles() - m_base; }
  void flush() {
    if (const uint64_t cycles = pending(); cycles != 0) m_host.compute_cycles(cycles);
    rebase();
  }
  // Whether the run loop should look up from the program: CHARGE_BATCH
  // cycles gathered (to charge them and sample the interrupt inputs), or
  // the program ended (stop()). One compare per instruction for both.
  bool needs_attention() const { return m_timing.cycles() >= m_attention_cycles; }
  void stop() {
    m_attention_at = 0;
    m_attention_cycles = m_base;
  }
  // After the timing layer's step of an instruction of `cycles` cycles: of
  // them, those beyond the issue cycles the host charged as busy for its
  // accesses (host.cycles.load and .store, per word) are pending, at least
  // 0. Most instructions make no access: they are the first branch.
  void charge_instruction(unsigned cycles) {
    if (__builtin_expect(m_host_charged == 0, 1)) return;
    const uint64_t charged = std::min<uint64_t>(cycles, m_host_charged);
    m_base += charged;
    m_attention_cycles += charged;
    m_host_charged = 0;
  }

  // One call per instruction: a fetch inside the direct window reads
  // memory there.
  bool fetch(uint32_t address, unsigned bytes, uint32_t& value) override {
    try {
      m_timing.fetch(address);  // a miss's fill is the host's bus read (on_fill); a stall counts in cycles()
    } catch (const BusError&) {
      return false;  // a prefetch abort
    }
    const uint32_t offset = address - m_window_base;  // wraps below the base: then past the size
    if (uint64_t{offset} + bytes <= m_window_size) {
      value = iss::load_little_endian(m_window + offset, bytes);
      const uint32_t line = iss::ResidentLines::line_of(address);
      const uint32_t line_offset = line - m_window_base;  // the whole line in the window, wherever it starts
      if (line >= m_window_base && uint64_t{line_offset} + iss::ResidentLines::BYTES <= m_window_size)
        if (uint64_t* hits = m_timing.resident_hits(address)) m_resident.grant(line, m_window + line_offset, hits);
      return true;
    }
    return fetch_outside_window(address, bytes, value);
  }
  iss::ResidentLines* resident_lines() override { return &m_resident; }

  // Loads and stores: a hit in a line the host grants (DataHitLines) is
  // served here, as the host would; any other access is the host's, in a
  // function of its own (the *_by_host below, never inline), so that the
  // hit's path saves no registers for it.
  bool read(uint32_t address, unsigned bytes, uint32_t& value) override {
    if (m_hit != nullptr && m_hit->load(address, bytes, pending(), value)) {
      took_hit(m_hit->load_issue());
      return true;
    }
    return read_by_host(address, bytes, value);
  }
  __attribute__((noinline)) bool read_by_host(uint32_t address, unsigned bytes, uint32_t& value) {
    flush();
    const Charged charged(*this);
    try {
      value = bytes == 4 ? m_host.read32(address) : bytes == 2 ? m_host.read16(address) : m_host.read8(address);
      return true;
    } catch (const BusError&) {
      m_fault_address = address;
      return false;
    }
  }

  bool write(uint32_t address, unsigned bytes, uint32_t value) override {
    if (__builtin_expect(address == CONSOLE || address == EXIT, 0)) return write_console_or_exit(address, value);
    if (m_hit != nullptr && m_hit->store(address, bytes, pending(), value)) {
      took_hit(m_hit->store_issue());
      return true;
    }
    return write_by_host(address, bytes, value);
  }
  __attribute__((noinline)) bool write_console_or_exit(uint32_t address, uint32_t value) {
    if (address == CONSOLE) {
      m_console += static_cast<char>(value);
      if (static_cast<char>(value) == '\n' || m_console.size() >= CONSOLE_CHUNK) {
        std::cout << m_console << std::flush;
        m_console.clear();
      }
      return true;
    }
    m_exited = true;
    m_status = value;
    stop();
    return true;
  }
  __attribute__((noinline)) bool write_by_host(uint32_t address, unsigned bytes, uint32_t value) {
    flush();
    const Charged charged(*this);
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
    return true;
  }

  // A debugger's access (GDB's): the host's, taking no time.
  bool debug_read(uint32_t address, uint8_t* data, unsigned bytes) override {
    return m_core.debug_read(address, data, bytes);
  }
  bool debug_write(uint32_t address, const uint8_t* data, unsigned bytes) override {
    return m_core.debug_write(address, data, bytes);
  }

  // LDM and STM: the host's read_words and write_words, one burst where
  // the words miss the data cache.
  bool read_block(uint32_t address, uint32_t* words, unsigned count) override {
    if (m_hit != nullptr && m_hit->load_words(address, words, count, pending())) {
      took_hit(m_hit->load_issue(count));
      return true;
    }
    return read_block_by_host(address, words, count);
  }
  __attribute__((noinline)) bool read_block_by_host(uint32_t address, uint32_t* words, unsigned count) {
    flush();
    const Charged charged(*this);
    try {
      m_host.read_words(address, words, count);
      return true;
    } catch (const BusError& error) {
      m_fault_address = error.address();
      return false;
    }
  }

  bool write_block(uint32_t address, const uint32_t* words, unsigned count) override {
    if (address <= EXIT && uint64_t{address} + 4 * count > CONSOLE)
      return IssMemory::write_block(address, words, count);
    if (m_hit != nullptr && m_hit->store_words(address, words, count, pending())) {
      took_hit(m_hit->store_words_issue(count));
      return true;
    }
    return write_block_by_host(address, words, count);
  }
  __attribute__((noinline)) bool write_block_by_host(uint32_t address, const uint32_t* words, unsigned count) {
    flush();
    const Charged charged(*this);
    try {
      m_host.write_words(address, words, count);
    } catch (const BusError& error) {
      m_fault_address = error.address();
      return false;
    }
    return true;
  }

  // The profile entry of the instruction being executed: its data
  // accesses' stalls and misses are charged to it. Null while the program
  // is not profiled (soc_sim --iss-profile, or a VCD's function signal):
  // then nothing is charged to functions.
  void set_profile_entry(iss::Profile::Entry* entry) { m_entry = entry; }
  iss::Profile::Entry* profile_entry() const { return m_entry; }
  // The cycles the program's accesses and fills have stalled on the bus
  // (the host's clock ticks summed as whole numbers, divided once: the
  // same figure with the profile or without it).
  double stall_cycles() const {
    return static_cast<double>(m_stall_ticks) / static_cast<double>(m_counters.period_ticks);
  }

  // What the host's busy, stall and miss counters moved by while it lives:
  // the busy cycles are the accesses' issue cycles (not charged again), the
  // stall ticks the program's stalls, and with a profile entry the stall
  // and the misses go to it too. Around every load and store, so the
  // counters are read where the core keeps them (HostCore::counter_locations)
  // rather than by virtual calls each side, and the entry's division is
  // made only when the stall ticks moved (most accesses do not stall).
  class Charged {
   public:
    explicit Charged(HostMemory& memory)
        : m_memory(memory),
          m_busy(*memory.m_counters.busy_cycles),
          m_stall_ticks(*memory.m_counters.stall_ticks),
          m_misses(*memory.m_counters.data_cache_misses) {}
    ~Charged() {
      const HostCore::CounterLocations& at = m_memory.m_counters;
      m_memory.m_host_charged += *at.busy_cycles - m_busy;
      iss::Profile::Entry* const entry = m_memory.m_entry;
      if (*at.stall_ticks != m_stall_ticks) {
        m_memory.m_stall_ticks += *at.stall_ticks - m_stall_ticks;
        if (entry != nullptr) {
          const auto period = static_cast<double>(at.period_ticks);
          // As stalled_cycles() after less stalled_cycles() before.
          entry->stall_cycles +=
              static_cast<double>(*at.stall_ticks) / period - static_cast<double>(m_stall_ticks) / period;
        }
      }
      if (entry != nullptr) entry->dcache_misses += *at.data_cache_misses - m_misses;
    }
    Charged(const Charged&) = delete;
    Charged& operator=(const Charged&) = delete;

   private:
    HostMemory& m_memory;
    const uint64_t m_busy;
    const uint64_t m_stall_ticks;
    const uint64_t m_misses;
  };

  bool exited() const { return m_exited; }
  uint32_t status() const { return m_status; }
  uint32_t fault_address() const { return m_fault_address; }
  void flush_console() {
    if (!m_console.empty()) std::cout << m_console << std::flush;
    m_console.clear();
  }

 private:
  // A fetch outside the direct window: the window is asked for again (a
  // first fetch, or after the memory withdrew its DMI); where there is
  // none, memory is read by debug access (no time: the timing layer's
  // instruction cache charges the fetch).
  bool fetch_outside_window(uint32_t address, unsigned bytes, uint32_t& value) {
    const HostCore::DirectMemory direct = m_core.direct_memory(address);
    if (direct.size != 0 && address >= direct.base && uint64_t{address - direct.base} + bytes <= direct.size) {
      m_window_base = direct.base;
      m_window_size = direct.size;
      m_window = direct.data;
      value = iss::load_little_endian(m_window + (address - m_window_base), bytes);
      return true;
    }
    uint8_t data[4];
    if (!m_core.debug_read(address, data, bytes)) {
      m_fault_address = address;
      return false;  // a prefetch abort
    }
    value = iss::load_little_endian(data, bytes);
    return true;
  }

  // After a hit served in the granted line: the pending cycles charged
  // with it, its issue cycles the host's (as Charged counts them).
  void took_hit(uint64_t issue_cycles) {
    rebase();
    m_host_charged += issue_cycles;
  }
  // Nothing pending from here on.
  void rebase() {
    m_base = m_timing.cycles();
    m_attention_cycles = m_base + m_attention_at;
  }

  HostApi& m_host;
  HostCore& m_core;
  iss::Arm922tTiming& m_timing;
  const HostCore::CounterLocations m_counters;
  DataHitLines* const m_hit;  // the host's grants, or null
  iss::Profile::Entry* m_entry = nullptr;
  // Memory the fetches read directly (HostCore::direct_memory): system
  // memory's DMI window, size 0 until the first fetch and after the memory
  // withdraws it.
  uint32_t m_window_base = 0;
  uint64_t m_window_size = 0;
  const uint8_t* m_window = nullptr;
  iss::ResidentLines m_resident;
  uint64_t m_base = 0;                     // the timing layer's cycles() when nothing was pending
  uint64_t m_attention_at = CHARGE_BATCH;  // 0 once the program has ended
  uint64_t m_attention_cycles = 0;         // m_base + m_attention_at
  uint64_t m_host_charged = 0;
  uint64_t m_stall_ticks = 0;  // the program's (Charged)
  std::string m_console;
  bool m_exited = false;
  uint32_t m_status = 0;
  uint32_t m_fault_address = 0;
};

// The per-function profile's accounting, when asked for (soc_sim
// --iss-profile) or needed (a VCD's function signal: the index of the
// function holding the PC): each instruction's cycles, and each host
// access's stalls and misses (HostMemory's profile entry), charged to the
// function holding its PC; instructions and cycles a run at a time, when
// the PC leaves the function (the timing layer's counts less those at the
// run's start: whole numbers, the same sums), so that each instruction
// costs a range check. Off, the run loop does not call before() and
// nothing is charged to functions; every other figure is the same.
class ProfileAccounting {
 public:
  ProfileAccounting(const iss::ElfImage& image, const iss::Arm922tTiming& timing, HostMemory& memory, bool on)
      : m_timing(timing), m_memory(memory), m_on(on), m_profile(image.functions), m_entry(&m_profile.at(image.entry)) {
    if (m_on) m_memory.set_profile_entry(m_entry);
  }
  bool on() const { return m_on; }
  iss::Profile& profile() { return m_profile; }
  // Before the instruction at `pc`: a new run when it leaves the function.
  __attribute__((always_inline)) void before(uint32_t pc) {
    if (m_profile.holds(pc)) return;
    end_run();
    m_entry = &m_profile.at(pc);
    m_memory.set_profile_entry(m_entry);
  }
  // Charges the run so far to its function (on, before the rows are read).
  void end_run() {
    if (!m_on) return;
    m_entry->instructions += m_timing.instructions() - m_run_steps;
    m_entry->cycles += m_timing.cycles() - m_run_cycles;
    m_run_steps = m_timing.instructions();
    m_run_cycles = m_timing.cycles();
  }

 private:
  const iss::Arm922tTiming& m_timing;
  HostMemory& m_memory;
  const bool m_on;
  iss::Profile m_profile;
  iss::Profile::Entry* m_entry;
  uint64_t m_run_steps = 0, m_run_cycles = 0;  // the timing layer's counts when the run in m_entry began
};

// Semihosting's memory and clock: the host's debug access (no time) and its
// local time.
class HostSemihostingPort : public iss::SemihostingPort {
 public:
  HostSemihostingPort(HostApi& host, HostCore& core) : m_host(host), m_core(core), m_start(host.now_seconds()) {}
  bool read_memory(uint32_t address, uint8_t* data, unsigned bytes) override {
    return m_core.debug_read(address, data, bytes);
  }
  bool write_memory(uint32_t address, const uint8_t* data, unsigned bytes) override {
    return m_core.debug_write(address, data, bytes);
  }
  uint64_t elapsed_cycles() override {
    return static_cast<uint64_t>(std::llround((m_host.now_seconds() - m_start) * m_host.clock_hz()));
  }
  uint32_t clock_hz() override { return static_cast<uint32_t>(std::llround(m_host.clock_hz())); }

 private:
  HostApi& m_host;
  HostCore& m_core;
  double m_start;
};

// CP15's cache control and c7's operations: the instruction side's reach
// the timing layer's instruction cache; the data side's (c1's C and RR
// bits, c7's invalidations, cleans and the write-buffer drain) the host's
// data cache and write buffer, the cleans and the drain at the time the
// instructions before them have taken, their stalls charged to the
// instruction's function; a wait for interrupt idles the host until the
// interrupt controller asserts IRQ or FIQ.
class LauncherCaches : public iss::CacheMaintenance {
 public:
  LauncherCaches(iss::Arm922tTiming& timing, HostMemory& memory, HostCore& core)
      : m_timing(timing), m_memory(memory), m_core(core) {}
  void invalidate_instruction_cache() override { m_timing.invalidate_instruction_cache(); }
  void invalidate_instruction_line(uint32_t address) override { m_timing.invalidate_instruction_line(address); }
  void control_written(uint32_t control) override {
    m_timing.control_written(control);
    m_core.set_data_cache_control((control & iss::Cp15::CONTROL_C) != 0, (control & iss::Cp15::CONTROL_RR) != 0);
  }
  void invalidate_data_cache() override { m_core.invalidate_data_cache(); }
  void invalidate_data_line(uint32_t address) override { m_core.invalidate_data_line(address); }
  void clean_data_line(uint32_t address, bool invalidate) override {
    in_time([&] { m_core.clean_data_line(address, invalidate); });
  }
  void clean_data_index(uint32_t index, bool invalidate) override {
    in_time([&] { m_core.clean_data_index(index, invalidate); });
  }
  void drain_write_buffer() override {
    in_time([&] { m_core.drain_write_buffer(); });
  }
  void wait_for_interrupt() override {
    m_memory.flush();
    m_core.wait_for_interrupt();
  }

 private:
  template <typename Operation>
  void in_time(Operation operation) {
    m_memory.flush();
    const HostMemory::Charged charged(m_memory);
    operation();
  }

  iss::Arm922tTiming& m_timing;
  HostMemory& m_memory;
  HostCore& m_core;
};

// Text written to a semihosting file, handed on a line at a time (a line
// longer than MAX_LINE in pieces of that size).
class LineSink {
 public:
  explicit LineSink(std::function<void(const std::string& line)> take) : m_take(std::move(take)) {}
  void operator()(const std::string& data) {
    m_partial += data;
    for (size_t end; (end = m_partial.find('\n')) != std::string::npos;) {
      const std::string line = m_partial.substr(0, end);
      m_partial.erase(0, end + 1);
      m_take(line);
    }
    // Text that never ends its line is handed on in pieces, not kept without bound.
    while (m_partial.size() >= MAX_LINE) {
      m_take(m_partial.substr(0, MAX_LINE));
      m_partial.erase(0, MAX_LINE);
    }
  }

 private:
  static constexpr size_t MAX_LINE = 1u << 16;
  std::function<void(const std::string&)> m_take;
  std::string m_partial;
};

std::string file_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// Functions listed in stats.json's profile.
constexpr size_t PROFILE_ROWS = 40;

// `profile`: the per-function profile, listed in full (soc_sim
// --iss-profile), or null. `stalls`: the program's stall cycles
// (HostMemory::stall_cycles), the same with the profile or without it; the
// rows' stall cycles, each summed access by access, add up to it but for
// rounding in their last digits.
nlohmann::json program_statistics(const iss::ArmCore& core, const iss::Arm922tTiming& timing,
                                  const iss::Profile* profile, double stalls) {
  const uint64_t instructions = core.instructions();
  nlohmann::json rows = nlohmann::json::array();
  const std::vector<iss::Profile::Row> all = profile != nullptr ? profile->rows() : std::vector<iss::Profile::Row>{};
  const double total = static_cast<double>(timing.cycles()) + stalls;
  for (size_t i = 0; i < all.size() && i < PROFILE_ROWS; ++i) {
    const iss::Profile::Row& row = all[i];
    const double cycles = static_cast<double>(row.entry.cycles) + row.entry.stall_cycles;
    rows.push_back({{"function", row.function},
                    {"address", row.address},
                    {"instructions", row.entry.instructions},
                    {"cycles", cycles},
                    {"share", total > 0 ? cycles / total : 0.0},
                    {"core_cycles", row.entry.cycles},
                    {"stall_cycles", row.entry.stall_cycles},
                    {"icache_misses", row.entry.icache_misses},
                    {"dcache_misses", row.entry.dcache_misses}});
  }
  nlohmann::json statistics = {{"instructions", instructions},
                               {"core_cycles", timing.cycles()},
                               {"stall_cycles", stalls},
                               {"cpi", instructions > 0 ? total / static_cast<double>(instructions) : 0.0},
                               {"interlock_cycles", timing.interlock_cycles()},
                               {"icache", {{"hits", timing.icache().hits()}, {"misses", timing.icache().misses()}}}};
  if (profile != nullptr) {
    statistics["functions_profiled"] = all.size();
    statistics["profile"] = rows;
  }
  return statistics;
}

// Reads the ELF and loads it into system memory. The program's own part of
// system memory is below the driver's heap and the frame buffers
// (contract/soc/software_layout.h), which it must not cover. An executable that
// does not fit is bad input (status 2), found here because the memory's
// size is known only now.
iss::ElfImage load_program(HostCore& core_port, const AppEnvironment& env, const std::string& path) {
  iss::ElfImage image = iss::read_elf(path);
  const uint32_t application_end = env.heap_base != 0 ? env.heap_base : env.memory_bytes;
  try {
    image.check_fits(0, application_end, "the application's part of system memory (below the driver's heap)");
  } catch (const iss::ElfError& error) {
    throw ProgramInputError(error.what());
  }
  // The image is in memory when the program starts, as if a debugger had
  // loaded it: its copy takes no simulated time.
  for (const iss::ElfSegment& segment : image.segments)
    if (!segment.bytes.empty() &&
        !core_port.debug_write(segment.address, segment.bytes.data(), static_cast<unsigned>(segment.bytes.size())))
      throw std::runtime_error(path + ": cannot load the segment at " + iss::address_text(segment.address));
  return image;
}

// A warning of the launcher about the program at `path`: the host's, in the
// run's log (standard error without one).
void warn_from(const AppEnvironment& env, const std::string& path, const std::string& message) {
  if (env.warn)
    env.warn("host", path + ": " + message);
  else
    std::cerr << path << ": " << message << "\n";
}

// The boot information the program reads at its start (boot_info.h): the
// application's environment as the boot loader hands it over.
boot_info::BootInfo boot_info_for(const AppEnvironment& env, const std::string& app) {
  boot_info::BootInfo boot;
  boot.app = app;
  boot.args = env.args;
  boot.frames = env.frames;
  boot.frame_buffers[0] = env.frame_buffers[0];
  boot.frame_buffers[1] = env.frame_buffers[1];
  boot.memory_bytes = env.memory_bytes;
  boot.heap_base = env.heap_base;
  boot.heap_end = env.heap_end;
  // The program's C heap may continue in the first host.iss_heap_mib of
  // the driver's heap (host-compiled software allocates from the host's
  // memory, without a limit; the ARM program from the SoC's).
  const uint64_t program_heap = env.config != nullptr && env.config->has("host.iss_heap_mib")
                                    ? env.config->get_uint("host.iss_heap_mib") << 20
                                    : 0;
  if (program_heap != 0) {
    if (uint64_t{env.heap_base} + program_heap > env.heap_end)
      throw std::invalid_argument("host.iss_heap_mib=" + std::to_string(program_heap >> 20) +
                                  " MiB does not fit in the driver's heap (" +
                                  std::to_string((env.heap_end - env.heap_base) >> 20) +
                                  " MiB with this mem.size_mib and display): lower it or raise mem.size_mib");
    boot.program_heap_base = env.heap_base;
    boot.program_heap_end = static_cast<uint32_t>(env.heap_base + program_heap);
    boot.heap_base = boot.program_heap_end;
  }
  if (env.make_renderer && env.config != nullptr && env.config->has("driver.backend"))
    boot.backend = env.config->get_string("driver.backend");
  if (env.config != nullptr) boot.config = boot_info::effective_parameters(*env.config);
  return boot;
}

// The program's environment through semihosting: its command line, the
// boot information to read, and the files its driver writes its warnings,
// per-frame figures and counters to, handed on to env's a line at a time.
void offer_environment(iss::Semihosting& semihosting, AppEnvironment& env, const std::string& path,
                       const std::string& builtin_app) {
  const std::string app = builtin_app.empty() ? file_name(path) : builtin_app;
  std::string command_line = app;
  for (const std::string& arg : env.args) command_line += " " + arg;
  semihosting.command_line = command_line;
  semihosting.offer_file(boot_info::BOOT_FILE, boot_info::encode(boot_info_for(env, app)));
  // One sink per file, shared by every handle the program opens on it (each
  // open takes a copy of the function offered).
  const auto warnings = std::make_shared<LineSink>([&env](const std::string& line) {
    const size_t tab = line.find('\t');
    const std::string source = tab == std::string::npos ? "driver" : line.substr(0, tab);
    const std::string message = tab == std::string::npos ? line : line.substr(tab + 1);
    if (env.warn)
      env.warn(source, message);
    else
      std::cerr << source << ": " << message << "\n";
  });
  const auto figures = std::make_shared<LineSink>([&env](const std::string& line) {
    if (env.frame_statistics) env.frame_statistics(boot_info::decode_figures(line));
  });
  const auto counters = std::make_shared<LineSink>([&env](const std::string& line) {
    const size_t first = line.find('\t'), second = line.find('\t', first + 1);
    if (env.counters == nullptr || first == std::string::npos || second == std::string::npos) return;
    env.counters->counter(line.substr(0, first), line.substr(second + 1)) +=
        std::strtoull(line.c_str() + first + 1, nullptr, 10);
  });
  semihosting.offer_sink(boot_info::WARNINGS_FILE, [warnings](const std::string& data) { (*warnings)(data); });
  semihosting.offer_sink(boot_info::FRAME_FIGURES_FILE, [figures](const std::string& data) { (*figures)(data); });
  semihosting.offer_sink(boot_info::COUNTERS_FILE, [counters](const std::string& data) { (*counters)(data); });
}

// The program's statistics in stats.json (HostCore::set_program_statistics),
// live while it runs (a run stopped at its time limit reports them too),
// kept as they were when it ends.
class StatisticsPublisher {
 public:
  StatisticsPublisher(HostCore& core, std::function<nlohmann::json()> live) : m_core(core), m_live(std::move(live)) {
    m_core.set_program_statistics(m_live);
  }
  ~StatisticsPublisher() {
    m_core.set_program_statistics([final = m_live()] { return final; });
  }
  StatisticsPublisher(const StatisticsPublisher&) = delete;
  StatisticsPublisher& operator=(const StatisticsPublisher&) = delete;

 private:
  HostCore& m_core;
  std::function<nlohmann::json()> m_live;
};

// host.iss_instruction_limit reached, at `pc`: stopped as a runaway.
[[noreturn]] void runaway(HostMemory& memory, const std::string& path, uint64_t limit, uint32_t pc) {
  memory.flush_console();
  throw std::runtime_error(path + ": still running after host.iss_instruction_limit=" + std::to_string(limit) +
                           " instructions, at pc " + iss::address_text(pc) + " (a runaway program?)");
}

// The core's SWI hook (a semihosting call served outside the program) and
// exception hook (a fault with no handler stops the program; run_elf_app's
// handler names the file).
void attach_hooks(iss::ArmCore& arm, HostCore& host_core, HostMemory& host_memory, iss::Semihosting& host_calls) {
  arm.on_swi([core = &arm, core_port = &host_core, memory = &host_memory, semihosting = &host_calls](uint32_t pc) {
    uint32_t instruction = 0;
    uint8_t bytes[4] = {};
    const unsigned size = core->thumb() ? 2 : 4;
    if (!core_port->debug_read(pc, bytes, size)) return false;
    for (unsigned i = 0; i < size; ++i) instruction |= uint32_t{bytes[i]} << (8 * i);
    if (!iss::Semihosting::is_call(instruction, core->thumb())) return false;
    memory->flush();
    core->set_reg(0, semihosting->serve(core->reg(0), core->reg(1)));
    if (semihosting->exited()) memory->stop();
    return true;
  });
  arm.on_exception([memory = &host_memory](iss::Exception exception, uint32_t pc) {
    const char* fault = iss::fault_name(exception);
    if (fault == nullptr) return;  // SWI and interrupts go to the program's vectors
    memory->flush_console();
    std::string text = std::string(fault) + " at pc " + iss::address_text(pc);
    if (exception == iss::Exception::data_abort) text += ", address " + iss::address_text(memory->fault_address());
    throw iss::ProgramFault(exception, text + " (the program has no handler: the ISS launcher stops it)");
  });
}

}  // namespace

bool is_elf_app(const std::string& name) {
  return name.size() > 4 && name.compare(name.size() - 4, 4, ".elf") == 0;
}

int run_elf_app(AppEnvironment& env, const IssHost& iss_host, const std::string& path, const std::string& builtin_app) {
  HostApi& host = *env.host;
  HostCore& core_port = iss_host.core;
  const iss::ElfImage image = load_program(core_port, env, path);

  iss::Arm922tTiming timing;
  HostMemory memory(host, core_port, timing);
  const bool profiling = core_port.profiling_program();
  const bool tracing = core_port.tracing_program();
  ProfileAccounting accounting(image, timing, memory, profiling || tracing);
  // Line fills and uncached fetches are the host's instruction-side reads,
  // at the time the instructions before them have taken.
  timing.on_fill([&memory, &core_port](uint32_t address, unsigned bytes) {
    memory.flush();
    const HostMemory::Charged charged(memory);
    if (iss::Profile::Entry* charged_to = memory.profile_entry()) ++charged_to->icache_misses;
    core_port.fetch(address, bytes);
  });
  iss::ArmCore core(memory);
  LauncherCaches caches(timing, memory, core_port);
  iss::Cp15 cp15(core, &caches);
  core.set_coprocessors(&cp15);
  timing.attach(&cp15);
  // As a boot loader would: the caches on (CP15 c1's I and C) before the
  // program starts, replacement as at reset (RR clear: pseudo-random); the
  // program may change any of them (the write reaches the host's data cache
  // through LauncherCaches::control_written).
  cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() | iss::Cp15::CONTROL_I | iss::Cp15::CONTROL_C);

  HostSemihostingPort port(host, core_port);
  iss::Semihosting semihosting(port);
  semihosting.console = [&memory](int stream, const std::string& text) {
    memory.flush_console();
    (stream == 2 ? std::cerr : std::cout) << text << std::flush;
  };
  const auto warn = [&env, &path](const std::string& message) { warn_from(env, path, message); };
  semihosting.warn = warn;
  offer_environment(semihosting, env, path, builtin_app);

  attach_hooks(core, core_port, memory, semihosting);
  const StatisticsPublisher publisher(core_port, [&] {
    accounting.end_run();
    return program_statistics(core, timing, profiling ? &accounting.profile() : nullptr, memory.stall_cycles());
  });

  core.reset();
  core.set_reg(15, image.entry);
  const uint64_t instruction_limit = env.config != nullptr && env.config->has("host.iss_instruction_limit")
                                         ? env.config->get_uint("host.iss_instruction_limit")
                                         : 0;
  if (tracing) core_port.set_function_names(accounting.profile().names());
  uint32_t traced_function = ~0u;
  const auto ended = [&] { return memory.exited() || semihosting.exited(); };
  const auto exit_status = [&] {
    return semihosting.exited() ? static_cast<uint32_t>(semihosting.exit_status()) : memory.status();
  };
  // Before an instruction (the limit, the profile's function) and after it
  // (its cycles, the trace, the interrupt lines), for GDB's single steps
  // and the run's blocks (ArmCore::run) alike. Inline: as calls (GCC's
  // choice, each being used twice) the run took 8% more CPU time.
  // `watching` and `profiled` (std::true_type or std::false_type): whether
  // the checks that are off unless asked for (an instruction limit, the
  // program's trace), and the profile's accounting, are compiled in. The
  // run's loop is made for each pair; the one without either runs unless
  // one is asked for.
  const bool watched = tracing || instruction_limit != 0;
  const auto before = [&](auto watching, auto profiled) __attribute__((always_inline)) {
    if constexpr (decltype(watching)::value)
      if (instruction_limit != 0 && core.instructions() == instruction_limit)
        runaway(memory, path, instruction_limit, core.reg(15));
    if constexpr (decltype(profiled)::value) accounting.before(core.reg(15));
  };
  const auto after = [&](auto watching) __attribute__((always_inline)) {
    // Its cycles beyond its host accesses' issue cycles (charged by the host).
    memory.charge_instruction(timing.step(core.last_step()));
    if constexpr (decltype(watching)::value)
      if (tracing && accounting.profile().last_index() != traced_function) {
        memory.flush();
        traced_function = accounting.profile().last_index();
        core_port.trace_program(core.reg(15), traced_function, core.cpsr());
      }
    // A batch of cycles gathered, or the program ended (false: the run
    // stops; the flush is then the one the end of the run would make).
    if (memory.needs_attention()) {
      memory.flush();
      core.set_irq(core_port.irq_asserted());
      core.set_fiq(core_port.fiq_asserted());
      return !ended();
    }
    return true;
  };
  const auto step = [&] {
    if (accounting.on())
      before(std::true_type{}, std::true_type{});
    else
      before(std::true_type{}, std::false_type{});
    core.step();
    after(std::true_type{});
  };
  const auto run_blocks = [&](auto watching, auto profiled) {
    before(watching, profiled);
    core.run([&]() __attribute__((always_inline)) {
      if (!after(watching)) return false;
      before(watching, profiled);
      return true;
    });
  };
  try {
    // GDB (soc_sim --gdb) first, until it leaves or the program exits: it
    // holds the kernel on the host's thread, so no block's time passes.
    if (iss_host.gdb != nullptr) {
      const iss::GdbServer::End end = iss_host.gdb->serve({core, memory, step, ended, exit_status}, ~uint64_t{0});
      if (end == iss::GdbServer::End::killed)
        throw std::runtime_error(path + ": killed by GDB at pc " + iss::address_text(core.reg(15)));
      if (end == iss::GdbServer::End::disconnected) warn("GDB went away without detaching; the program runs on");
    }
    if (!ended()) {
      if (watched && accounting.on())
        run_blocks(std::true_type{}, std::true_type{});
      else if (watched)
        run_blocks(std::true_type{}, std::false_type{});
      else if (accounting.on())
        run_blocks(std::false_type{}, std::true_type{});
      else
        run_blocks(std::false_type{}, std::false_type{});
    }
  } catch (const iss::IssError& error) {
    memory.flush_console();
    throw std::runtime_error(path + ": " + error.what());
  }
  memory.flush();
  memory.flush_console();
  return static_cast<int>(exit_status());
}

}  // namespace tessera
