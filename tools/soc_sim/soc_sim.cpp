// soc_sim: builds the SoC from the configuration, runs an application on the
// host model, writes the displayed frames, statistics and (optionally) a VCD
// trace, and prints a summary. The command line is read by run_options.h,
// the run is a RunSession (run_session.h), and what is reported of it is
// run_report.h's.
#include <cstdlib>
#include <iostream>
#include <variant>

#include <systemc>

#include "run_options.h"
#include "run_session.h"

using namespace tessera;

int sc_main(int argc, char* argv[]) {
  try {
    std::variant<RunPlan, int> read = read_command_line(argc, argv);
    if (const int* status = std::get_if<int>(&read)) return *status;
    RunSession session(std::move(std::get<RunPlan>(read)));
    return session.run();
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_SIM_FAILED;
  }
}

// SystemC prints its banner before sc_main; our own main silences it so that
// stdout carries only soc_sim's output.
int main(int argc, char* argv[]) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  return sc_core::sc_elab_and_sim(argc, argv);
}
