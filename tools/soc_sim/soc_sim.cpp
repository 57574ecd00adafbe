// soc_sim: builds the SoC from the configuration, runs an application on the
// host model, writes the displayed frames, statistics and (optionally) a VCD
// trace, and prints a summary.
#include <strings.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <systemc>

#include "apps/apps.h"
#include "apps/iss_app.h"
#include "build_info.h"
#include "common/activity_json.h"
#include "common/log.h"
#include "config/config.h"
#include "frame_stats_stream.h"
#include "host/iss/gdb_server.h"
#include "output_file.h"
#include "png_writer_thread.h"
#include "progress_line.h"
#include "renderers/backend_parameters.h"
#include "renderers/backends.h"
#include "run_outputs.h"
#include "run_watch.h"
#include "soc/soc.h"
#include "soc/software_layout.h"
#include "time_limit.h"
#include "trace_pipe.h"

namespace fs = std::filesystem;
using namespace tessera;

namespace {

constexpr int EXIT_USAGE = 2;       // bad option, configuration or input file
constexpr int EXIT_SIM_FAILED = 1;  // the simulation itself failed

struct Options {
  std::vector<std::string> config_files;
  std::vector<std::string> overrides;
  std::string app;
  std::string backend;
  int frames = 0;
  std::string out_dir = "out";
  std::string vcd;
  std::string stats;
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

// Creates `dir` if needed and proves it writable, or throws naming it.
void prepare_output_dir(const std::string& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw std::runtime_error("output folder '" + dir + "' cannot be created: " + error.message());
  const fs::path probe = fs::path(dir) / ".soc_sim_write_test";
  std::ofstream file(probe);
  if (!file) throw std::runtime_error("output folder '" + dir + "' is not writable");
  file.close();
  fs::remove(probe, error);
}

// Proves that `path` can be written without changing it: a file that was
// not there is removed again, so a run refused later leaves nothing behind.
void check_writable_file(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw std::runtime_error("cannot write '" + path + "': folder '" + parent.string() + "' does not exist");
  std::error_code error;
  const bool existed = fs::exists(path, error);
  if (!std::ofstream(path, std::ios::app)) throw std::runtime_error("cannot write '" + path + "'");
  if (!existed) fs::remove(path, error);
}

// Refuses to mix this run's outputs with an earlier run's (run_outputs.h);
// with --force removes the earlier ones. Throws with the message to print.
void clear_earlier_outputs(const OutputPaths& paths, bool force) {
  const EarlierOutputs earlier = find_earlier_outputs(paths);
  if (!earlier.foreign.empty()) {
    const fs::path& file = earlier.foreign.front();
    const bool stats = file == paths.stats;
    throw std::runtime_error("'" + file.string() + "' was not written by soc_sim (it is not " +
                             (stats ? "a statistics file" : "a VCD trace") + " of soc_sim), and this run would " +
                             "overwrite it with its " + (stats ? "statistics" : "trace") +
                             "; soc_sim never overwrites such a file, even with --force: move it, or choose another " +
                             (stats ? "path with --stats or --out" : "path with --vcd"));
  }
  if (earlier.empty()) return;
  if (!force)
    throw std::runtime_error("output folder '" + paths.out_dir.string() + "' already holds the outputs of an " +
                             "earlier run: " + describe_outputs(earlier, paths.out_dir) +
                             "; a new run would mix its outputs with them: add --force to remove them first, or " +
                             "choose another folder with --out");
  remove_earlier_outputs(earlier);
}

// The progress line on stderr (progress_line.h): redrawn at most every
// PROGRESS_REDRAW_SECONDS of wall time, at the terminal's current width, and
// once more at the end with the final state.
class Progress {
 public:
  Progress(bool enabled, unsigned total) : m_enabled(enabled), m_total(total) {}
  void update(unsigned frames, double simulated, double wall) {
    if (!m_enabled || (m_drawn && wall - m_last_draw < PROGRESS_REDRAW_SECONDS)) return;
    draw(frames, simulated, wall);
  }
  void finish(unsigned frames, double simulated, double wall) {
    if (!m_enabled) return;
    draw(frames, simulated, wall);
    std::fputc('\n', stderr);
  }

 private:
  void draw(unsigned frames, double simulated, double wall) {
    winsize size{};
    const unsigned reported = ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 ? size.ws_col : 0;
    const unsigned columns = choose_columns(reported, std::getenv("COLUMNS"));
    std::fprintf(stderr, "\r%s", progress_line({frames, m_total, simulated, wall}, columns).c_str());
    std::fflush(stderr);
    m_drawn = true;
    m_last_draw = wall;
  }

  bool m_enabled;
  unsigned m_total;
  bool m_drawn = false;
  double m_last_draw = 0;
};

// The back ends' own figures: for each driver section with a host-time
// split (the array back ends), where the host's time went, and the
// averages of the per-frame figures the back end gave (the frame records'
// "driver", summed as they were streamed to stats.json).
void print_driver_summary(const nlohmann::json& stats, const FrameStatsStream::Sums& sums) {
  const nlohmann::json& driver = stats["driver"];
  const double simulated = stats["simulated_ns"].get<double>() * 1e-9;
  for (const auto& [section, counters] : driver.items()) {
    if (!counters.is_object() || !counters.contains("host_compute_ns")) continue;
    std::printf("\n  %s: host time          total  of simulated\n", section.c_str());
    for (const char* part : {"compute", "write", "read", "wait", "frame_out"}) {
      const std::string key = std::string("host_") + part + "_ns";
      if (!counters.contains(key)) continue;
      const double seconds = counters[key].get<double>() * 1e-9;
      std::printf("    %-12s %14s %12s\n", part, format_duration(seconds).c_str(),
                  format_percent(simulated > 0 ? seconds / simulated : 0).c_str());
    }
    if (sums.driver_frames == 0) continue;
    std::printf("  %s: per frame (mean of %zu)\n", section.c_str(), sums.driver_frames);
    for (const auto& [name, sum] : sums.driver)
      std::printf("    %-28s %14.3f\n", name.c_str(), sum / static_cast<double>(sums.driver_frames));
  }
}

// The summary's width: it fits a terminal of 80 columns.
constexpr size_t SUMMARY_COLUMNS = 80;

// `text` in lines of at most `width` characters, broken after ", " (a part
// longer than `width` is a line of its own).
std::vector<std::string> wrap_at_commas(const std::string& text, size_t width) {
  std::vector<std::string> lines(1);
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find(", ", start);
    end = end == std::string::npos ? text.size() : end + 1;  // the comma ends the part, the space is dropped
    const std::string part = text.substr(start, end - start);
    const std::string joined = lines.back().empty() ? part : lines.back() + " " + part;
    if (!lines.back().empty() && joined.size() > width)
      lines.push_back(part);
    else
      lines.back() = joined;
    start = end < text.size() ? end + 1 : end;
  }
  return lines;
}

// Each energy unit's energy over the run, its average power and its mean
// energy per frame shown (tlm/power/); units that spent none are named on
// one line instead, as the blocks that did nothing are above.
void print_energy_summary(const nlohmann::json& stats, const FrameStatsStream::Sums& sums) {
  const nlohmann::json& energy = stats["energy"];
  std::printf("\n  %-18s %12s %12s %14s\n", "energy (1.2 V)", "total", "average", "per frame");
  const auto row = [&sums](const std::string& name, const nlohmann::json& unit, double frame_sum) {
    const std::string mean = sums.frames == 0 ? "-" : format_energy(frame_sum / static_cast<double>(sums.frames));
    std::printf("  %-18s %12s %12s %14s\n", name.c_str(), format_energy(unit["total_j"].get<double>()).c_str(),
                format_power(unit["average_w"].get<double>()).c_str(), mean.c_str());
  };
  std::string none;
  for (const auto& [name, unit] : energy["units"].items()) {
    if (unit["total_j"].get<double>() == 0) {
      none += (none.empty() ? "" : ", ") + name;
      continue;
    }
    const auto found = sums.energy_unit_j.find(name);
    row(name, unit, found == sums.energy_unit_j.end() ? 0.0 : found->second);
  }
  row("total", energy, sums.energy_total_j);
  if (!none.empty())
    for (const std::string& line : wrap_at_commas("no energy: " + none, SUMMARY_COLUMNS - 2))
      std::printf("  %s\n", line.c_str());
}

// A block that did nothing in the run: no busy time and every counter 0.
bool did_nothing(const Block& block, const SummaryRow& row) {
  if (row.busy && row.busy->value() != 0) return false;
  const auto& all = block.counters().all();
  return std::all_of(all.begin(), all.end(), [](const ActivityCounter& c) { return c.value == 0; });
}

// The summary: run, block table (each block's own row, its notes wrapped to
// SUMMARY_COLUMNS; the blocks that did nothing named on one line instead),
// the blocks' own tables (the bus's traffic per initiator), outputs. It
// names no block.
void print_summary(const Soc& soc, const nlohmann::json& stats, const FrameStatsStream::Sums& frame_sums,
                   const std::string& app, double wall, const TimeLimit& time_limit,
                   const std::vector<std::string>& outputs) {
  const sc_core::sc_time elapsed = sc_core::sc_time_stamp();
  const double simulated = elapsed.to_seconds();
  std::printf("\ntessera soc_sim: application '%s', display %s mode\n", app.c_str(),
              stats["display"]["mode"].get<std::string>().c_str());
  std::printf("  simulated time  %s\n  wall time       %s (%s simulated per wall second)\n",
              format_duration(simulated).c_str(), format_duration(wall).c_str(),
              format_duration(wall > 0 ? simulated / wall : 0).c_str());
  std::printf("  time limit      %s\n", time_limit.describe().c_str());
  // "  name          busy  utilisation  notes": 40 columns before the notes.
  constexpr int NOTES_COLUMN = 40;
  std::printf("\n  %-12s %11s %11s  %s\n", "block", "busy", "utilisation", "notes");
  std::vector<SummaryTable> tables;
  std::string idle;
  std::set<std::string> idle_blocks;
  for (const Block* block : soc.blocks()) {
    const SummaryRow row = block->summary_row(elapsed);
    if (did_nothing(*block, row)) {
      idle += (idle.empty() ? "" : ", ") + std::string(block->basename());
      idle_blocks.insert(block->basename());
      continue;
    }
    const std::vector<std::string> notes = wrap_at_commas(row.notes, SUMMARY_COLUMNS - NOTES_COLUMN);
    std::printf("  %-12s %11s %11s  %s\n", block->basename(),
                row.busy ? format_duration(row.busy->to_seconds()).c_str() : "-",
                row.utilisation ? format_percent(*row.utilisation).c_str() : "-", notes.front().c_str());
    for (size_t i = 1; i < notes.size(); ++i) std::printf("%*s%s\n", NOTES_COLUMN, "", notes[i].c_str());
    for (SummaryTable& table : block->summary_tables(elapsed)) tables.push_back(std::move(table));
  }
  if (!idle.empty())
    for (const std::string& line : wrap_at_commas("did nothing: " + idle, SUMMARY_COLUMNS - 2))
      std::printf("  %s\n", line.c_str());
  for (const SummaryTable& table : tables) {
    std::printf("\n  %s\n ", table.title.c_str());
    for (size_t i = 0; i < table.columns.size(); ++i)
      std::printf(i == 0 ? " %-12s" : " %12s", table.columns[i].c_str());
    std::printf("\n");
    for (const auto& row : table.rows) {
      if (!row.empty() && idle_blocks.count(row.front())) continue;  // named above, a row of zeros
      std::printf(" ");
      for (size_t i = 0; i < row.size(); ++i) std::printf(i == 0 ? " %-12s" : " %12s", row[i].c_str());
      std::printf("\n");
    }
  }
  print_energy_summary(stats, frame_sums);
  print_driver_summary(stats, frame_sums);
  std::printf("\n  outputs\n");
  for (const auto& line : outputs) std::printf("    %s\n", line.c_str());
}

// soc_sim's own parameters (sim.*): what to run and how the run is watched.
ParamGroup runner_parameters() {
  return {"soc_sim",
          {
              param::text("sim.app", "teapot", "application to run: a built-in name or a path to a shared library"),
              param::integer("sim.frames", 3, 1, 100000, "frames",
                             "frames the application draws before the simulation ends"),
              param::integer("sim.time_limit_ms", 0, 0, 3600000, "ms",
                             "simulated-time limit; a run that reaches it stops with an error (0: automatic, " +
                                 TimeLimit::automatic_rule() + ")"),
              param::integer("sim.stall_limit_s", 60, 0, 86400, "s",
                             "wall-clock time the simulation may go without simulated time advancing (an application "
                             "stuck in its own code) before the run stops with an error (0: no limit)"),
              param::integer("sim.wall_limit_s", 0, 0, 604800, "s",
                             "wall-clock limit of the simulation; a run that reaches it stops with an error and writes "
                             "what is complete (0: no limit)"),
              param::choice("sim.log_level", "warning", {"quiet", "error", "warning", "info", "debug"},
                            "lowest severity of the log lines printed on stderr"),
          },
          {}};
}

// Every parameter of a run: soc_sim's, the driver's and its back ends', the
// SoC's and its blocks'.
std::vector<ParamGroup> all_parameters() {
  std::vector<ParamGroup> groups = {runner_parameters()};
  for (ParamGroup& group : driver_parameter_groups()) groups.push_back(std::move(group));
  for (ParamGroup& group : Soc::parameter_groups()) groups.push_back(std::move(group));
  return groups;
}

int run(int argc, char* argv[]) {
  Options opt;
  CLI::App cli{"tessera soc_sim: run an application on the virtual mobile graphics SoC"};
  cli.add_option("--config", opt.config_files, "JSON configuration file(s), applied in order")
      ->check(CLI::ExistingFile);
  cli.add_option("--set", opt.overrides, "override one parameter: key=value (repeatable)");
  cli.add_option("--app,--scene", opt.app, "application: a built-in name (see --list-apps)");
  cli.add_option("--backend", opt.backend,
                 "renderer back end (driver.backend): " + backends::backend_names(", ", " or "));
  cli.add_option("--frames", opt.frames, "frames to draw (sim.frames)")->check(CLI::Range(1, 100000));
  cli.add_option("--out", opt.out_dir, "folder for frames and statistics")->capture_default_str();
  cli.add_option("--stats", opt.stats, "write statistics as JSON to FILE (default: <out>/stats.json)");
  cli.add_option("--vcd", opt.vcd, "write a VCD trace to FILE");
  cli.add_flag("--force", opt.force,
               "remove the outputs of an earlier run (frames, statistics, traces) from the output folder first");
  cli.add_flag("--no-frames", opt.no_frames, "write no PNG frames (they are still counted in the statistics)");
  cli.add_flag("--wall-clock", opt.wall_clock,
               "add each frame's wall-clock and CPU time (wall_ns, cpu_ns) to stats.json, for benchmarks; the file "
               "then differs from run to run");
  CLI::Option* gdb = cli.add_option("--gdb", opt.gdb_port,
                                    "serve GDB's remote protocol on 127.0.0.1:PORT (0: any free port) for the program "
                                    "on the ISS (host.model=iss), which waits for GDB before its first instruction")
                         ->check(CLI::Range(0, 65535));
  cli.add_option("--gdb-port-file", opt.gdb_port_file, "with --gdb: write the port to FILE once listening")->needs(gdb);
  cli.add_flag("--iss-profile", opt.iss_profile,
               "profile the program on the ISS (host.model=iss) per function: stats.json's host.iss.profile (the "
               "40 functions with the most cycles); off, the run is faster and every other figure the same");
  cli.add_flag("--quiet,-q", opt.quiet, "print nothing but errors");
  cli.add_option("--log-level", opt.log_level, "quiet, error, warning, info or debug (sim.log_level)");
  cli.add_flag("--print-config", opt.print_config, "print the effective configuration as JSON and exit");
  cli.add_flag("--config-reference", opt.config_reference, "print the configuration reference (Markdown) and exit");
  cli.add_flag("--list-apps", opt.list_apps, "list the built-in applications and exit");
  // Left-over arguments are rejected below, with advice for a stray word:
  // "soc_sim cubes" means "--app cubes" more often than not.
  cli.allow_extras();
  cli.set_version_flag("--version",
                       std::string("soc_sim (tessera) ") + build_info::version() + ", commit " + build_info::commit(),
                       "print the version and the git commit soc_sim was built from, and exit");
  const uint64_t default_frames = Config(all_parameters()).get_uint("sim.frames");
  cli.footer(
      "Arguments after -- go to the application, e.g. soc_sim --app obj_viewer -- model.obj\n"
      "(AppEnvironment::args); soc_sim itself takes no positional arguments.\n\n"
      "Simulated-time limit (sim.time_limit_ms): the value a --config file or --set gives;\n"
      "0 (the default): automatic, " +
      TimeLimit::automatic_rule() + " (" + std::to_string(choose_time_limit(default_frames, 0).ms / 1000) +
      " s for the default " + std::to_string(default_frames) +
      " frames).\nThe summary and stats.json show the limit in effect; reaching it is an error (status 1).\n\n"
      "A run that cannot finish ends by itself: sim.stall_limit_s (wall-clock seconds without\n"
      "simulated progress, default 60) and sim.wall_limit_s (wall-clock limit, default none)\n"
      "stop it with status 1. SIGINT or SIGTERM stops it at the next safe point with status\n"
      "128 + signal; a crash is reported with the frame reached. stats.json says how the run\n"
      "ended (run_status), and every output is whole or absent.");
  // CLI11 sees only what comes before the first "--": the rest belongs to
  // the application, so a word before it is an error, not an argument.
  int own_argc = argc;
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--") {
      own_argc = i;
      opt.app_args.assign(argv + i + 1, argv + argc);
      break;
    }
  try {
    cli.parse(own_argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e) == 0 ? 0 : EXIT_USAGE;
  }
  // An option given with an empty value is a mistake (an unset shell
  // variable, say), not a request for the default.
  const std::pair<const char*, const std::string*> valued_options[] = {
      {"--app", &opt.app}, {"--backend", &opt.backend}, {"--log-level", &opt.log_level}};
  for (const auto& [option, value] : valued_options)
    if (cli.count(option) > 0 && value->empty()) {
      std::cerr << "soc_sim: " << option << " was given an empty value: give one (soc_sim --help"
                << (std::string_view(option) == "--app" ? ", soc_sim --list-apps" : "")
                << "), or leave the option out for the default\n";
      return EXIT_USAGE;
    }
  if (!cli.remaining().empty()) {
    const std::string word = cli.remaining().front();
    if (word.size() > 1 && word[0] == '-') {
      std::cerr << "soc_sim: unknown option '" << word << "' (soc_sim --help lists the options)\n";
      return EXIT_USAGE;
    }
    std::cerr << "soc_sim: unexpected argument '" << word << "' before '--': ";
    if (builtin_apps().count(word))
      std::cerr << "to run the application '" << word << "', use --app " << word;
    else
      std::cerr << "choose the application with --app NAME (soc_sim --list-apps)";
    std::cerr << "; arguments for the application go after '--', e.g. soc_sim --app obj_viewer -- model.obj\n";
    return EXIT_USAGE;
  }

  if (opt.config_reference) {
    std::cout << Config(all_parameters()).reference_markdown();
    return 0;
  }
  if (opt.list_apps) {
    for (const auto& [name, info] : builtin_apps()) std::cout << name << "  " << info.description << "\n";
    return 0;
  }

  Config config(all_parameters());
  try {
    for (const auto& file : opt.config_files) config.load_file(file);
    for (const auto& assignment : opt.overrides) config.apply_override(assignment);
    if (!opt.app.empty()) config.set("sim.app", opt.app, "--app");
    if (opt.frames > 0) config.set("sim.frames", opt.frames, "--frames");
    if (!opt.backend.empty()) config.set("driver.backend", opt.backend, "--backend");
    if (!opt.log_level.empty()) config.set("sim.log_level", opt.log_level, "--log-level");
    if (opt.quiet) config.set("sim.log_level", "error", "--quiet");
    // An ARM executable runs on the ISS: host.model follows the application
    // unless the user chose it.
    if (is_elf_app(config.get_string("sim.app"))) {
      if (!config.is_set("host.model"))
        config.set("host.model", "iss", "--app " + config.get_string("sim.app"));
      else if (config.get_string("host.model") != "iss")
        throw ConfigError(
            "configuration: impossible combination: sim.app=" + config.get_string("sim.app") +
            " is an ARM executable, which runs on the ISS, and host.model=" + config.get_string("host.model"));
    }
    // The chosen back end fills in what it needs that the user left unset.
    if (const backends::Backend* chosen = backends::find_backend(config.get_string("driver.backend")))
      chosen->adjust_configuration(config);
    config.validate();
  } catch (const ConfigError& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }
  const TimeLimit time_limit = choose_time_limit(config.get_uint("sim.frames"), config.get_uint("sim.time_limit_ms"));
  if (opt.print_config) {
    std::cout << config.to_json().dump(2) << "\n";
    return 0;
  }

  if (opt.iss_profile && config.get_string("host.model") != "iss") {
    std::cerr << "soc_sim: impossible combination: --iss-profile profiles a program on the ISS, and host.model="
              << config.get_string("host.model")
              << " runs the application host-compiled (set host.model=iss, or run an ARM executable with --app "
                 "program.elf)\n";
    return EXIT_USAGE;
  }
  if (opt.gdb_port >= 0 && config.get_string("host.model") != "iss") {
    std::cerr << "soc_sim: impossible combination: --gdb debugs a program on the ISS, and host.model="
              << config.get_string("host.model")
              << " runs the application host-compiled (set host.model=iss, or run an ARM executable with --app "
                 "program.elf)\n";
    return EXIT_USAGE;
  }

  AppInfo app;
  try {
    app = find_app(config.get_string("sim.app"), config.get_string("host.model") == "iss");
  } catch (const std::invalid_argument& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }

  // The trace is written under exactly the name given (TracePipe copies
  // SystemC's output there, whatever SystemC appends to its own name); the
  // functions' names go beside it, named after it without a ".vcd" in any
  // case.
  std::string vcd_base = opt.vcd;
  if (const fs::path extension = fs::path(vcd_base).extension();
      extension.string().size() == 4 && strcasecmp(extension.c_str(), ".vcd") == 0)
    vcd_base.resize(vcd_base.size() - 4);
  const std::string stats_path = opt.stats.empty() ? (fs::path(opt.out_dir) / "stats.json").string() : opt.stats;
  // Held to the end of the run: no other run checks or writes this folder
  // meanwhile (run_outputs.h).
  std::optional<OutputFolderClaim> folder_claim;
  try {
    prepare_output_dir(opt.out_dir);
    folder_claim.emplace(opt.out_dir);
    check_writable_file(stats_path);
    if (!opt.vcd.empty()) check_writable_file(opt.vcd);
    clear_earlier_outputs({opt.out_dir, stats_path, opt.vcd.empty() ? fs::path() : fs::path(opt.vcd)}, opt.force);
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }

  // Listening before the SoC is built: a port in use is bad input, found
  // before anything runs.
  std::unique_ptr<iss::GdbServer> gdb_server;
  if (opt.gdb_port >= 0) {
    try {
      gdb_server = std::make_unique<iss::GdbServer>();
      const unsigned port = gdb_server->listen(static_cast<unsigned>(opt.gdb_port));
      if (!opt.gdb_port_file.empty() && !(std::ofstream(opt.gdb_port_file) << port << "\n"))
        throw std::runtime_error("cannot write the GDB port to '" + opt.gdb_port_file + "'");
      if (!opt.quiet) std::cerr << "soc_sim: waiting for GDB on 127.0.0.1:" << port << "\n";
    } catch (const std::exception& e) {
      std::cerr << "soc_sim: --gdb: " << e.what() << "\n";
      return EXIT_USAGE;
    }
  }

  log::install(log::parse_level(config.get_string("sim.log_level")));
  install_run_signal_handlers();
  const unsigned frames = static_cast<unsigned>(config.get_uint("sim.frames"));
  const std::string& vcd_path = opt.vcd;
  // Declared before the SoC, whose destructor closes the trace: the pipe's
  // copier ends when SystemC closes its end.
  std::unique_ptr<TracePipe> trace_pipe;
  try {
    if (!vcd_path.empty()) trace_pipe = std::make_unique<TracePipe>(vcd_path);
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_SIM_FAILED;
  }
  Soc soc("soc", config);
  PngWriterThread png_writer;
  std::unique_ptr<RunWatch> watch;
  unsigned frames_shown = 0;
  // The wall clock from the start of the simulation; each frame's reading is
  // its wall_ns in stats.json with --wall-clock, so a benchmark times frames
  // N..2N-1 within one run instead of subtracting one run from another.
  auto wall_start = std::chrono::steady_clock::now();
  auto wall_seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };
  // And the process's CPU time (every thread: the simulation and the PNG
  // writer), cpu_ns with --wall-clock: on a machine with a core to spare the
  // PNG thread costs little wall time, but its work shows here.
  const auto cpu_seconds = [] {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
  };
  // stats.json's frame records go to side files as the frames are shown and
  // are merged into stats.json at the end (frame_stats_stream.h): nothing
  // per frame is kept in memory.
  std::unique_ptr<FrameStatsStream> frame_stream;
  try {
    frame_stream = std::make_unique<FrameStatsStream>(opt.out_dir);
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_SIM_FAILED;
  }
  soc.recorder().stream_frames([&frame_stream](const nlohmann::json& record) { frame_stream->add_frame(record); });
  soc.display.keep_pixels(!opt.no_frames);
  soc.display.on_frame([&](const Frame& frame) {
    if (opt.wall_clock) frame_stream->add_timing(wall_seconds(), cpu_seconds());
    if (!opt.no_frames)
      png_writer.write((fs::path(opt.out_dir) / frame_file_name(frame.index)).string(), frame.width, frame.height,
                       frame.rgba);
    ++frames_shown;
    if (watch) watch->frame_shown(frames_shown);
  });

  AppEnvironment env;
  env.frames = frames;
  const software_layout::Layout layout = software_layout::layout(soc.memory.size(), soc.display.frame_bytes());
  env.frame_buffers[0] = layout.frame_buffers[0];
  env.frame_buffers[1] = layout.frame_buffers[1];
  env.heap_base = layout.heap_base;
  env.heap_end = layout.heap_end;
  env.memory_bytes = static_cast<uint32_t>(soc.memory.size());
  env.args = opt.app_args;
  env.config = &config;
  ActivityCounters driver_counters;
  env.counters = &driver_counters;
  env.warn = [](const std::string& source, const std::string& message) { log::warning(source, message); };
  env.frame_statistics = [&frame_stream](const std::vector<std::pair<std::string, double>>& figures) {
    nlohmann::json record = nlohmann::json::object();
    for (const auto& [name, value] : figures) record[name] = value;
    frame_stream->add_driver(record);
  };
  backends::hand_over(backends::backend(config.get_string("driver.backend")), env);
  env.core = &soc.host;
  env.gdb = gdb_server.get();
  soc.host.set_profiling_program(opt.iss_profile);
  soc.set_program([&env, &app](HostApi& host) {
    env.host = &host;
    return app.main(env);
  });

  if (trace_pipe) soc.recorder().trace_to(trace_pipe->systemc_base());

  // stats.json: what soc_sim knows of the run, and the SoC's statistics
  // (null when the run was stopped from outside the simulation).
  const nlohmann::json config_json = config.to_json();
  const auto statistics_document = [&](int status, RunEnd end, const std::string& error, unsigned shown,
                                       unsigned written, nlohmann::json stats) {
    nlohmann::json document = {{"application", config.get_string("sim.app")},
                               {"version", build_info::version()},
                               {"commit", build_info::commit()},
                               {"command_line", std::vector<std::string>(argv, argv + argc)},
                               {"time_limit_ms", time_limit.ms},
                               {"time_limit_automatic", time_limit.automatic},
                               {"frames_shown", shown},
                               {"frames_written", written},
                               {"exit_status", status},
                               {"run_status", run_end_name(end)},
                               {"config", config_json},
                               {"stats", std::move(stats)}};
    if (!error.empty()) document["error"] = error;
    return document.dump(2) + "\n";
  };

  const bool show_progress = !opt.quiet && isatty(STDERR_FILENO);
  Progress progress(show_progress, frames);
  // A stop from the watching thread (run_watch.h): the application holds
  // the simulation, so the SoC is not touched; the frames already shown are
  // written, the trace is dropped (it is not whole) and stats.json says how
  // the run ended.
  const auto stop_from_outside = [&](const RunStop& stop) {
    if (stop.end != RunEnd::crashed)
      std::fprintf(stderr, "%ssoc_sim: %s\n", show_progress ? "\n" : "", stop.message.c_str());
    png_writer.finish();
    if (trace_pipe) trace_pipe->abandon_from_other_thread();
    try {
      write_file_atomically(stats_path, statistics_document(stop.exit_status, stop.end, stop.message,
                                                            watch->frames_shown(), png_writer.written(), nullptr));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "soc_sim: %s\n", e.what());
    }
    // The run exits with _exit: no destructor removes the side files or the
    // lock file (the kernel drops the lock itself).
    frame_stream->unlink_from_other_thread();
    folder_claim->unlink_from_other_thread();
  };
  // Under GDB simulated time stands still while GDB holds the program, for
  // as long as the user likes: that is no stall.
  const uint64_t stall_limit_s = gdb_server ? 0 : config.get_uint("sim.stall_limit_s");
  watch = std::make_unique<RunWatch>(WatchLimits{stall_limit_s, config.get_uint("sim.wall_limit_s")}, frames,
                                     stop_from_outside);
  wall_start = std::chrono::steady_clock::now();
  const sc_core::sc_time limit(static_cast<double>(time_limit.ms), sc_core::SC_MS);
  const sc_core::sc_time slice(1, sc_core::SC_MS);
  // The reasons the run failed, the first deciding run_status and the exit status.
  std::vector<RunStop> failures;
  const auto fail = [&failures](RunEnd end, int status, const std::string& message) {
    failures.push_back({end, status, message});
  };
  std::optional<RunStop> stopped;
  try {
    while (!soc.done() && sc_core::sc_get_status() != sc_core::SC_STOPPED && sc_core::sc_time_stamp() < limit) {
      sc_core::sc_start(slice);
      watch->progress(static_cast<uint64_t>(sc_core::sc_time_stamp().to_seconds() * 1e12));
      progress.update(frames_shown, sc_core::sc_time_stamp().to_seconds(), wall_seconds());
      stopped = watch->stop_request();
      if (stopped || png_writer.failed()) break;
    }
  } catch (const std::exception& e) {
    fail(RunEnd::failed, EXIT_SIM_FAILED, std::string("simulation failed: ") + e.what());
  }
  watch->finish();
  // The run ended with the program still running under GDB (the time
  // limit, say): GDB is told, not left waiting.
  if (gdb_server) gdb_server->abandon();
  progress.finish(frames_shown, sc_core::sc_time_stamp().to_seconds(), wall_seconds());
  soc.recorder().close_trace();
  std::string trace_error = trace_pipe ? trace_pipe->finish() : "";
  // A program on the ISS: its functions' names by soc.host.function's value,
  // as a GTKWave translate-filter file beside the VCD.
  if (trace_pipe && trace_error.empty() && !soc.host.function_names().empty()) {
    std::string names;
    for (size_t i = 0; i < soc.host.function_names().size(); ++i)
      names += std::to_string(i) + " " + soc.host.function_names()[i] + "\n";
    try {
      write_file_atomically(vcd_base + ".functions.txt", names);
    } catch (const std::exception& e) {
      trace_error = e.what();
    }
  }
  const std::string png_error = png_writer.finish();
  const unsigned frames_written = png_writer.written();
  const double wall = wall_seconds();

  if (!failures.empty()) {
    // An exception from the simulation: reported above all else.
  } else if (stopped) {
    failures.push_back(*stopped);
  } else if (!png_error.empty()) {
    // Reported below; the run stopped at it.
  } else if (!soc.done() && sc_core::sc_time_stamp() >= limit) {
    fail(RunEnd::failed, EXIT_SIM_FAILED,
         "simulated-time limit reached: sim.time_limit_ms = " + std::to_string(time_limit.ms) + " ms (" +
             (time_limit.automatic ? "automatic, " + TimeLimit::automatic_rule() : std::string("given")) + ") " +
             "stopped the run after " + std::to_string(frames_shown) + " of " + std::to_string(frames) + " frames; " +
             (time_limit.automatic ? "set sim.time_limit_ms to a larger value (--set sim.time_limit_ms=N)"
                                   : "raise it, or leave sim.time_limit_ms unset for the automatic limit"));
  } else if (!soc.done()) {
    fail(RunEnd::failed, EXIT_SIM_FAILED,
         "the simulation stopped after " + std::to_string(frames_shown) + " of " + std::to_string(frames) +
             " frames, before the application finished");
  } else if (soc.host.exit_code() != 0) {
    // An application reports bad input (an unreadable file, a bad argument)
    // with status 2, like soc_sim itself.
    fail(RunEnd::failed, soc.host.exit_code() == EXIT_USAGE ? EXIT_USAGE : EXIT_SIM_FAILED,
         "application failed: " + soc.host.failure());
  }
  if (!png_error.empty())
    fail(RunEnd::failed, EXIT_SIM_FAILED,
         png_error + "; the run stopped after " + std::to_string(frames_shown) + " of " + std::to_string(frames) +
             " frames were shown, " + std::to_string(frames_written) + " written");
  if (!trace_error.empty()) fail(RunEnd::failed, EXIT_SIM_FAILED, trace_error + " (the VCD trace is not kept)");
  if (failures.empty() && frames_shown == 0)
    log::warning("soc_sim", "the application '" + config.get_string("sim.app") +
                                "' finished without showing a frame (" + std::to_string(frames) +
                                " requested): nothing was drawn");
  for (const RunStop& failure : failures) std::cerr << "soc_sim: " << failure.message << "\n";
  int status = failures.empty() ? 0 : failures.front().exit_status;
  const RunEnd end = failures.empty() ? RunEnd::completed : failures.front().end;

  nlohmann::json stats = soc.recorder().stats_json();
  stats["driver"] = to_json(driver_counters);
  // The frames streamed (every one: streaming began before the first) are
  // merged in where the placeholder is.
  stats["frames"] = FrameStatsStream::placeholder();
  bool stats_written = true;
  FrameStatsStream::Sums frame_sums;
  try {
    frame_sums = frame_stream->write(stats_path,
                                     statistics_document(status, end, failures.empty() ? "" : failures.front().message,
                                                         frames_shown, frames_written, stats),
                                     opt.wall_clock);
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << " (statistics)\n";
    stats_written = false;
    if (status == 0) status = EXIT_SIM_FAILED;
  }

  if (!opt.quiet) {
    std::vector<std::string> outputs;
    if (frames_written)
      outputs.push_back(std::to_string(frames_written) + " frame(s): " +
                        (fs::path(opt.out_dir) / frame_file_name(0)).string() + (frames_written > 1 ? " ..." : ""));
    if (opt.no_frames) outputs.push_back(std::to_string(frames_shown) + " frame(s) shown, none written (--no-frames)");
    outputs.push_back(stats_written ? "statistics: " + stats_path : "statistics: none (" + stats_path + " failed)");
    if (!vcd_path.empty()) outputs.push_back(trace_error.empty() ? "VCD trace: " + vcd_path : "VCD trace: none");
    print_summary(soc, stats, frame_sums, config.get_string("sim.app"), wall, time_limit, outputs);
  }
  // The summary (and anything the application printed) must have arrived.
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || !std::cout) {
    std::cerr << "soc_sim: cannot write to standard output: " << std::strerror(errno) << "\n";
    if (status == 0) status = EXIT_SIM_FAILED;
  }
  return status;
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  try {
    return run(argc, argv);
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
