// An ARM executable as the host's program: `soc_sim --app program.elf` runs
// the ELF on the ISS (tlm/host/iss) over the host's device layer, so that
// its loads and stores are the host's (data cache, write buffer, bus
// transactions) and its instructions are charged to the host's clock.
// sw_driver/README.md ("ARM executables") and sw_driver/runtime/README.md
// say how a program gets its environment.
#pragma once

#include <string>

#include "device/app_environment.h"

namespace tessera {

// True if `name` names an ARM executable (ends in .elf).
bool is_elf_app(const std::string& name);

// Loads the ELF into system memory and runs it to its exit; returns its exit
// status. `builtin_app` names the built-in application a build of the
// runtime with every built-in application (tessera_apps.elf) is to run;
// empty for an application of its own. Needs env.core (the host's
// HostCore). Throws std::runtime_error naming the file and the PC on an
// undefined instruction, an abort or an unpredictable encoding.
int run_elf_app(AppEnvironment& env, const std::string& path, const std::string& builtin_app = "");

}  // namespace tessera
