// soc_sim's command line and the configuration it names: what a run is to
// do (RunPlan), or the answer to a question that needs no run (--help,
// --version, --list-apps, --print-config, --config-reference) or to bad
// input, with the status to exit with.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "config/config.h"
#include "launch/app_loading.h"
#include "time_limit.h"

namespace tessera {

constexpr int EXIT_USAGE = 2;       // bad option, configuration or input file
constexpr int EXIT_SIM_FAILED = 1;  // the simulation itself failed

// The command line as given.
struct Options {
  std::vector<std::string> config_files;
  std::vector<std::string> overrides;
  std::string platform;
  std::string app;
  std::string backend;
  int frames = 0;
  std::string out_dir = "out";
  std::string vcd;     // a VCD trace (any name but *.fst)
  std::string fst;     // an FST trace (*.fst)
  std::string report;  // the HTML run report (*.html)

  std::string timeline;                    // --timeline FILE ("": none)
  std::string timeline_detail = "blocks";  // frames, blocks or all (timeline_writer.h)
  std::string trace_transactions;          // --trace-transactions FILE[:FILTER] ("": none)
  std::string stats;
  std::string stats_schema;
  bool quiet = false;
  bool force = false;
  bool no_frames = false;
  bool wall_clock = false;
  std::string log_level;
  bool print_config = false;
  bool config_reference = false;
  bool list_apps = false;
  int gdb_port = -1;  // -1: no GDB
  std::string gdb_port_file;
  bool iss_profile = false;
  std::vector<std::string> app_args;
};

// A run to do: the command line, the effective configuration (validated),
// the simulated-time limit in effect and the application found.
struct RunPlan {
  Options options;
  Config config;
  TimeLimit time_limit;
  LaunchableApp app;
  std::vector<std::string> command_line;  // argv, for stats.json
};

// The parameters of a run on the SoC: soc_sim's (sim.*), the driver's and
// its back ends', the SoC's and its blocks'.
std::vector<ParamGroup> soc_parameters();
// Every parameter of a run: the SoC's, the platform's choice
// (sim.platform) and the cluster platform's (cluster.*, network.*, ni.*).
std::vector<ParamGroup> all_parameters();
// `config` restricted to soc_parameters(): what a program on the SoC is
// handed (on the ISS, its boot information), so that the cluster's
// parameters do not reach it.
Config soc_view(const Config& config);

// Reads the command line and the configuration it names. A question that
// needs no run is answered on stdout, bad input on stderr ("soc_sim: ..."),
// and what comes back is then the status to exit with (0, or EXIT_USAGE).
std::variant<RunPlan, int> read_command_line(int argc, char* argv[]);

}  // namespace tessera
