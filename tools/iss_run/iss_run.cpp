// iss_run: an ARM executable on the ISS alone (BareMachine: 1 MiB of RAM at
// 0, the console byte register at 0xf0000000, the exit register at
// 0xf0000004; no SystemC), optionally under GDB, optionally with the
// ARM922T's timing (--timing: cycles and CPI on stderr at exit).
//
//   iss_run program.elf [--limit N] [--timing] [--gdb PORT [--gdb-port-file FILE]]
//
// Prints the program's console output and exits with its exit status; an
// undefined instruction, an abort or a runaway program (--limit) is an error
// naming the file and the PC (exit status 3); bad input exits 2.
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "guarded_main.h"
#include "host/iss/arm922t_timing.h"
#include "host/iss/bare_machine.h"
#include "host/iss/cp15.h"
#include "host/iss/gdb_server.h"

int run_main(int argc, char** argv) {
  CLI::App app{"iss_run: an ARM executable on the instruction-set simulator alone"};
  std::string elf, port_file;
  uint64_t limit = 1'000'000'000;
  int gdb_port = -1;
  bool timed = false;
  app.add_option("program", elf, "the ARM executable (ELF)")->required();
  app.add_option("--limit", limit, "instructions before the run is stopped as runaway")->check(CLI::PositiveNumber);
  app.add_option("--gdb", gdb_port, "serve GDB's remote protocol on 127.0.0.1:PORT (0: any free port) and wait")
      ->check(CLI::Range(0, 65535));
  app.add_option("--gdb-port-file", port_file, "write the GDB port here once listening");
  app.add_flag("--timing", timed,
               "ARM922T timing (ARM9TDMI cycles, 8 KB instruction cache on from the start, data memory without wait "
               "states): instructions, cycles and CPI on stderr at exit");
  CLI11_PARSE(app, argc, argv);
  using namespace tessera::iss;
  try {
    BareMachine machine;
    Arm922tTiming timing;
    TimedFetch fetch_port(machine, timed ? &timing : nullptr);
    ArmCore core(fetch_port);
    Cp15 cp15(core, &timing);
    core.set_coprocessors(&cp15);
    timing.attach(&cp15);
    // As a boot loader would: the instruction cache on before the program starts.
    cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() | Cp15::CONTROL_I);
    machine.load(read_elf(elf), core);
    // Printed as it comes (a line, or 4 KiB without a newline), not kept to the end.
    machine.stream_console([](const std::string& text) { std::cout << text << std::flush; });
    core.on_exception([&](Exception exception, uint32_t pc) {
      if (const char* fault = fault_name(exception))
        throw ProgramFault(exception, elf + ": " + fault + " at pc " + address_text(pc));
    });
    try {
      const auto timed_step = [&] {
        core.step();
        timing.step(core.last_step());
      };
      if (gdb_port >= 0) {
        GdbServer server;
        const unsigned port = server.listen(static_cast<unsigned>(gdb_port));
        std::cerr << "iss_run: waiting for GDB on 127.0.0.1:" << port << "\n";
        if (!port_file.empty() && !(std::ofstream(port_file) << port << "\n"))
          throw std::runtime_error("cannot write the port to " + port_file);
        const GdbServer::Target target{core, machine,
                                       timed ? std::function<void()>(timed_step) : [&core] { core.step(); },
                                       [&] { return machine.exited(); }, [&] { return machine.status(); }};
        const GdbServer::End end = server.serve(target, limit);
        if (end == GdbServer::End::killed) {
          machine.flush_console();
          std::cerr << "iss_run: killed by GDB at pc " << address_text(core.reg(15)) << "\n";
          return 3;
        }
        if (end == GdbServer::End::disconnected) std::cerr << "iss_run: GDB went away; the program runs on\n";
      }
      bool exited;
      if (timed) {
        exited = machine.run(
            core, limit - std::min(limit, core.instructions()), [&]() __attribute__((always_inline)) {
              timing.step(core.last_step());
            });
      } else {
        exited = machine.run(core, limit - std::min(limit, core.instructions()));
      }
      machine.flush_console();
      if (timed) {
        char line[256];
        std::snprintf(line, sizeof line,
                      "iss_run: %llu instructions, %llu cycles, CPI %.3f (interlocks %llu, instruction fetch stalls "
                      "%llu; instruction cache %llu hits, %llu misses)\n",
                      static_cast<unsigned long long>(timing.instructions()),
                      static_cast<unsigned long long>(timing.cycles()),
                      timing.instructions() ? static_cast<double>(timing.cycles()) / timing.instructions() : 0.0,
                      static_cast<unsigned long long>(timing.interlock_cycles()),
                      static_cast<unsigned long long>(timing.fetch_stall_cycles()),
                      static_cast<unsigned long long>(timing.icache().hits()),
                      static_cast<unsigned long long>(timing.icache().misses()));
        std::cerr << line;
      }
      if (!exited) {
        std::cerr << "iss_run: " << elf << ": no exit after " << core.instructions() << " instructions (--limit), pc "
                  << address_text(core.reg(15)) << "\n";
        return 3;
      }
      return static_cast<int>(machine.status() & 0xffu);
    } catch (const IssError& error) {
      machine.flush_console();
      std::cerr << "iss_run: " << error.what() << "\n";
      return 3;
    }
  } catch (const std::exception& error) {
    std::cerr << "iss_run: " << error.what() << "\n";
    return 2;
  }
}

int main(int argc, char** argv) {
  return tessera::guarded_main(
      "iss_run", [&] { return run_main(argc, argv); }, 2);
}
