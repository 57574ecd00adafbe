// An ARM executable as the host's program: `soc_sim --app program.elf` runs
// the ELF on the ISS (tlm/host/iss) over the host's device layer, so that
// its loads and stores are the host's (data cache, write buffer, bus
// transactions) and its instructions are charged to the host's clock.
// sw_driver/README.md ("ARM executables") and sw_driver/runtime/README.md
// say how a program gets its environment.
#pragma once

#include <string>

#include "device/app_environment.h"
#include "host/host_core.h"

namespace tessera {

namespace iss {
class GdbServer;
}

// What the launcher needs of the SoC beyond the application's environment:
// the host's core interface (instruction fetches, the core's interrupt
// inputs, debug access) and, with soc_sim --gdb, a GDB server listening,
// which the launcher waits for before the program's first instruction and
// serves (null: no GDB).
struct IssHost {
  HostCore& core;
  iss::GdbServer* gdb = nullptr;
};

// True if `name` names an ARM executable (ends in .elf).
bool is_elf_app(const std::string& name);

// Loads the ELF into system memory and runs it to its exit; returns its exit
// status. The program's environment (frames, frame buffers, heap, arguments,
// configuration) is env's, handed over as the boot information
// (sw_driver/runtime/boot_info.h); its warnings, per-frame figures and
// counters come back to env's. `builtin_app` names the built-in application
// a build of the runtime with every built-in application (tessera_apps.elf)
// is to run; empty for an application of its own. Throws
// std::runtime_error naming the file and the PC on an undefined
// instruction, an abort or an unpredictable encoding.
int run_elf_app(AppEnvironment& env, const IssHost& iss_host, const std::string& path,
                const std::string& builtin_app = "");

}  // namespace tessera
