// Finding the application soc_sim runs on the host, by name: a built-in one
// (host-compiled, or cross-compiled on the ISS with host.model=iss), an ARM
// executable for the ISS, or a host-compiled shared library loaded with
// dlopen.
#pragma once

#include <functional>
#include <string>

#include "apps/gl_apps.h"
#include "device/app_environment.h"
#include "launch/iss_launcher.h"

namespace tessera {

// An application ready to run on the host. `main` runs it with the
// application's environment; an ARM executable runs on the ISS over `iss_host`
// (the host's core interface and the GDB server), which the others ignore.
struct LaunchableApp {
  std::function<int(AppEnvironment& env, const IssHost& iss_host)> main;
  std::string description;
};

// The application `name`: a built-in one, an ARM executable (*.elf, on the
// ISS) or a shared library given by its path. With `on_iss`
// (host.model=iss) a built-in one runs cross-compiled on the ISS, from the
// image builtin_iss_image() names, and a shared library is refused. Throws
// std::invalid_argument listing the built-in ones, or naming what is wrong.
LaunchableApp find_app(const std::string& name, bool on_iss = false);

// The cluster platform's node program (sw_driver/cluster_node), every
// node's: host-compiled, or with `on_iss` its ARM executable beside
// tessera_apps.elf (tessera_cluster_node.elf; std::invalid_argument if it
// is missing).
LaunchableApp cluster_node_program(bool on_iss);

// The ARM executable of every built-in application, beside the running
// program (<its folder>/arm922t/tessera_apps.elf); std::invalid_argument if
// it is missing.
std::string builtin_iss_image();

// Loads a shared library and returns its tessera_app_main, or its main if
// it has none (defined in the library itself); throws
// std::invalid_argument naming the file and what is wrong with it.
GlMain load_app_library(const std::string& path);

}  // namespace tessera
