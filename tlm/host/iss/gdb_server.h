// GdbServer: the GDB remote serial protocol over TCP for the ISS, so that
// gdb-multiarch can debug a program the ISS runs: registers (r0-r15 and the
// CPSR, described to GDB by a target description), memory, software
// breakpoints, single step, continue, and the program's exit.
#pragma once

#include <cstdint>
#include <functional>
#include <set>
#include <string>

#include "host/iss/arm_core.h"

namespace tessera::iss {

class GdbServer {
 public:
  // What the server runs: one instruction at a time; `exited` and `status`
  // say whether the program has ended and how.
  struct Target {
    ArmCore& core;
    IssMemory& memory;  // debugger reads and writes (no side effects expected)
    std::function<bool()> exited;
    std::function<uint32_t()> status;
  };

  explicit GdbServer(Target target) : m_target(std::move(target)) {}

  // Listens on 127.0.0.1:port (0: any free port); returns the port. Throws
  // std::runtime_error naming the port if it cannot listen.
  unsigned listen(unsigned port);
  // Waits for GDB, then serves it until it detaches or kills the program, or
  // the program exits (reported to GDB). Returns false if GDB killed it.
  bool serve(uint64_t instruction_limit);

 private:
  std::string handle(const std::string& packet, bool& resume, bool& step, bool& stop_serving);
  std::string read_packet();
  void send_packet(const std::string& data);
  std::string registers() const;
  std::string stop_reply() const;
  // Runs until a breakpoint, the program's end or the limit; false at the limit.
  bool run(bool single_step, uint64_t& budget);

  Target m_target;
  int m_listen_fd = -1;
  int m_fd = -1;
  std::set<uint32_t> m_breakpoints;
  bool m_killed = false;
};

}  // namespace tessera::iss
