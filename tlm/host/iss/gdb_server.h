// GdbServer: the GDB remote serial protocol over TCP for the ISS, so that
// gdb-multiarch can debug a program the ISS runs: registers (r0-r15 and the
// CPSR, described to GDB by a target description), memory, breakpoints,
// single step, continue, interrupting a run (Ctrl-C), kill, detach, the
// program's faults and its exit. One server for every launcher: iss_run's
// bare machine and soc_sim's host (host.model=iss) each hand it the core, a
// debugger's view of memory and the step their run makes.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <string>
#include <unordered_set>

#include "host/iss/arm_core.h"

namespace tessera::iss {

// Memory as a debugger sees it: no simulated time, no cache or bus activity.
// false where nothing answers (an unmapped address).
class DebugMemory {
 public:
  virtual ~DebugMemory() = default;
  virtual bool debug_read(uint32_t address, uint8_t* data, unsigned bytes) = 0;
  virtual bool debug_write(uint32_t address, const uint8_t* data, unsigned bytes) = 0;
};

// The remote serial protocol's framing, a byte at a time: '$', the data,
// '#' and two hex digits, the data's sum modulo 256. Plain C++ (the server
// feeds it what the socket gives; the tests and the fuzz target feed it
// bytes). Anything between packets (acknowledgements, a Ctrl-C while the
// program is stopped) is skipped. A packet whose checksum does not match is
// reported, not returned (the server answers '-': GDB sends it again); one
// longer than MAX_DATA is read to its end but not kept (bounded memory),
// then reported.
class GdbPacketReader {
 public:
  // Twice the packet size the server offers GDB (qSupported's PacketSize):
  // no well-behaved client comes near it.
  static constexpr size_t MAX_DATA = 0x8000;
  enum class Event { none, packet, bad_checksum, too_long };
  Event feed(char c);
  // The data of the packet `feed` has just returned `packet` for.
  const std::string& packet() const { return m_data; }

 private:
  enum class State { between, data, checksum_high, checksum_low } m_state = State::between;
  std::string m_data;
  unsigned m_sum = 0;
  unsigned m_checksum = 0;
  bool m_bad_digit = false;
  bool m_too_long = false;
};

class GdbServer {
 public:
  // What the server debugs.
  struct Target {
    ArmCore& core;
    DebugMemory& memory;
    // Executes one instruction as the launcher's run does (its timing, its
    // host's time, its interrupt sampling), so that a program under GDB
    // behaves as it does without. A ProgramFault or IssError it throws is
    // the program's fault: shown to GDB, then rethrown when GDB resumes or
    // leaves; anything else is rethrown at once.
    std::function<void()> step;
    std::function<bool()> exited;
    std::function<uint32_t()> status;
  };

  // How serving ended.
  enum class End {
    exited,        // the program exited (reported to GDB)
    detached,      // GDB detached: the program runs on without it
    disconnected,  // the connection closed without a detach: the same
    killed,        // GDB killed the program
    limit,         // the instruction limit (reported to GDB as SIGXCPU)
  };

  GdbServer() = default;
  ~GdbServer();
  GdbServer(const GdbServer&) = delete;
  GdbServer& operator=(const GdbServer&) = delete;

  // Listens on 127.0.0.1:port (0: any free port); returns the port. Throws
  // std::runtime_error naming the port if it cannot listen (in use, say).
  unsigned listen(unsigned port);
  // Waits for GDB with the program stopped before its first instruction,
  // then serves it until GDB detaches, kills the program or goes away, or the
  // program exits. The listening socket is closed once GDB is connected.
  End serve(const Target& target, uint64_t instruction_limit);
  // The run ends from outside while the program runs under GDB (soc_sim's
  // simulated-time limit, say): GDB is told that the program was killed
  // (SIGKILL) and the connection is closed. Nothing if GDB is not there.
  void abandon();

  // The reply serve() sends for one packet's data, without a connection
  // and without running the program (a c or s packet gets "" here): for
  // the tests and the fuzz target.
  std::string reply(const Target& target, const std::string& packet);

 private:
  std::string handle(const std::string& packet, bool& resume, bool& step, bool& stop_serving);
  // One byte from GDB; false, with m_connected cleared, when the connection closed.
  bool receive(char& c);
  // A packet's data (acknowledged '+'); "" with m_connected cleared when
  // the connection closed. A packet with a bad checksum is answered '-' and
  // one too long an error, and reading goes on.
  std::string read_packet();
  void send_packet(const std::string& data);
  std::string read_memory(uint32_t address, uint32_t length) const;
  std::string registers() const;
  std::string stop_reply() const;
  // Steps until a breakpoint, the program's end, its fault, the limit or
  // GDB's interrupt; false at the limit.
  bool run(bool single_step, uint64_t& budget);
  // GDB sent Ctrl-C, or the connection closed (m_connected cleared).
  bool interrupted();
  void close_connection();

  const Target* m_target = nullptr;
  int m_listen_fd = -1;
  int m_fd = -1;
  bool m_connected = false;
  bool m_running = false;  // GDB waits for a stop reply
  unsigned m_signal = 5;   // of the last stop: SIGTRAP, SIGINT, or the fault's
  std::unordered_set<uint32_t> m_breakpoints;
  GdbPacketReader m_reader;
  std::exception_ptr m_fault;  // the program's fault, shown to GDB, not yet rethrown
};

}  // namespace tessera::iss
