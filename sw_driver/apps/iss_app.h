// An ARM executable as the host's program: `soc_sim --app program.elf` runs
// the ELF on the ISS (tlm/host/iss) over the host's device layer, so that
// its loads and stores are the host's (data cache, write buffer, bus
// transactions) and its instructions are charged to the host's clock.
// sw_driver/apps/README.md ("ARM executables") says what is and is not
// modelled yet.
#pragma once

#include <string>

#include "device/app_environment.h"

namespace tessera {

// True if `name` names an ARM executable (ends in .elf).
bool is_elf_app(const std::string& name);

// Loads the ELF into system memory and runs it to its exit; returns its exit
// status. Throws std::runtime_error naming the file and the PC on an
// undefined instruction, an abort or an unpredictable encoding.
int run_elf_app(AppEnvironment& env, const std::string& path);

}  // namespace tessera
