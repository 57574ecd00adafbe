// What the ISS launcher (tools/soc_sim/launch/iss_launcher.cpp) hands an ARM program
// built with the bare-metal runtime, and the channels through which the
// program hands back what a host-compiled application gives soc_sim
// through its AppEnvironment (warnings, per-frame figures, counters). All of
// them are semihosting files (tlm/host/iss/semihosting.h): reading or
// writing them takes no simulated time, as a debugger's access would not.
// Compiled twice: natively into the launcher, for the ARM into the runtime;
// this file is the one place the encoding lives.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config/config.h"

namespace tessera::boot_info {

// The boot information, read once at start-up (JSON).
inline constexpr const char* BOOT_FILE = ":tessera/boot";
// Lines "source<TAB>message": AppEnvironment::warn.
inline constexpr const char* WARNINGS_FILE = ":tessera/warnings";
// One line per frame, "name=value" pairs separated by tabs:
// AppEnvironment::frame_statistics.
inline constexpr const char* FRAME_FIGURES_FILE = ":tessera/frame_figures";
// At exit, lines "name<TAB>value<TAB>description": AppEnvironment::counters.
inline constexpr const char* COUNTERS_FILE = ":tessera/counters";

struct BootInfo {
  std::string app;  // the built-in application to run, or the executable's own name
  std::vector<std::string> args;
  unsigned frames = 1;
  uint32_t frame_buffers[2] = {0, 0};
  uint32_t memory_bytes = 0;
  uint32_t heap_base = 0, heap_end = 0;
  // Where the program's C heap grows once the part of its own memory below
  // its stacks is used up (host.iss_heap_mib of the driver's heap); empty
  // if none.
  uint32_t program_heap_base = 0, program_heap_end = 0;
  std::string backend;  // driver.backend; empty: no GL back end
  // The run's configuration: every parameter with its type and effective
  // value (descriptions, ranges and choices left out).
  std::vector<ParamSpec> config;
};

// The configuration's parameters as BootInfo::config holds them.
std::vector<ParamSpec> effective_parameters(const Config& config);

std::string encode(const BootInfo& info);
// Throws std::runtime_error naming what is missing or malformed.
BootInfo decode(const std::string& text);

// One line of FRAME_FIGURES_FILE and back.
std::string encode_figures(const std::vector<std::pair<std::string, double>>& figures);
std::vector<std::pair<std::string, double>> decode_figures(const std::string& line);

}  // namespace tessera::boot_info
