// The bare-metal runtime of a program cross-compiled for the ARM922T and
// run on the ISS (sw_driver/runtime/README.md). ARM only.
#pragma once

#include <cstdint>

#include "device/app_environment.h"
#include "runtime/boot_info.h"

namespace tessera::runtime {

// The console as stdin, stdout and stderr (syscalls.cpp).
void open_standard_streams();
// The core's cycles since the program started, and its clock (semihosting).
uint64_t cycles_since_start();
uint32_t clock_hz();
// Where the C heap continues once the memory below the stacks is used up.
void set_second_heap(uint32_t base, uint32_t end);

}  // namespace tessera::runtime

// Runs the application in the environment the launcher described: the
// program's tessera_app_main, or its main (run_application.cpp, the
// library tessera_runtime_app), or the built-in application boot.app
// (run_builtin.cpp, tessera_runtime_builtin, in tessera_apps.elf).
int tessera_runtime_run(tessera::AppEnvironment& env, const tessera::boot_info::BootInfo& boot);
