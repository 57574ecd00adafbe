// soc_sim: builds the SoC from the configuration, runs an application on the
// host model, writes the displayed frames, statistics and (optionally) a VCD
// trace, and prints a summary.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>
#include <systemc>

#include "apps/apps.h"
#include "common/activity_json.h"
#include "common/log.h"
#include "config/config.h"
#include "frame_writer.h"
#include "png_writer_thread.h"
#include "renderers/backend_parameters.h"
#include "renderers/backends.h"
#include "soc/soc.h"
#include "soc/software_layout.h"

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
  std::string log_level;
  bool print_config = false;
  bool config_reference = false;
  bool list_apps = false;
  std::vector<std::string> app_args;
};

std::string format_time(double seconds) {
  char buffer[32];
  if (seconds >= 1)
    std::snprintf(buffer, sizeof buffer, "%.3f s", seconds);
  else if (seconds >= 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.3f ms", seconds * 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%.3f us", seconds * 1e6);
  return buffer;
}

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

void check_writable_file(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw std::runtime_error("cannot write '" + path + "': folder '" + parent.string() + "' does not exist");
  std::ofstream file(path, std::ios::app);
  if (!file) throw std::runtime_error("cannot write '" + path + "'");
}

class Progress {
 public:
  Progress(bool enabled, unsigned total) : m_enabled(enabled), m_total(total) {}
  void update(unsigned frames, double simulated, double wall) {
    if (!m_enabled) return;
    const unsigned width = 30;
    const unsigned filled = m_total ? std::min(width, frames * width / m_total) : 0;
    std::string bar(filled, '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] frame %u/%u  simulated %s  %s simulated per second ", bar.c_str(), frames, m_total,
                 format_time(simulated).c_str(), format_time(wall > 0 ? simulated / wall : 0).c_str());
    std::fflush(stderr);
  }
  void finish() {
    if (m_enabled) std::fprintf(stderr, "\n");
  }

 private:
  bool m_enabled;
  unsigned m_total;
};

void print_summary(const Soc& soc, const nlohmann::json& stats, const std::string& app, double wall,
                   const std::vector<std::string>& outputs) {
  const double simulated = sc_core::sc_time_stamp().to_seconds();
  const auto& host = stats["host"];
  const auto& bus = stats["bus"];
  const auto& memory = stats["memory"];
  const auto& display = stats["display"];
  std::printf("\ntessera soc_sim: application '%s', display %s mode\n", app.c_str(),
              display["mode"].get<std::string>().c_str());
  std::printf("  simulated time  %s\n  wall time       %s (%s simulated per wall second)\n",
              format_time(simulated).c_str(), format_time(wall).c_str(),
              format_time(wall > 0 ? simulated / wall : 0).c_str());
  std::printf("\n  %-10s %14s %12s  %s\n", "block", "busy", "utilisation", "notes");
  std::printf("  %-10s %14s %11.1f%%  stalled on bus %s, idle %s\n", "host",
              format_time(host["busy_ns"].get<double>() * 1e-9).c_str(), host["utilisation"].get<double>() * 100,
              format_time(host["stalled_on_bus_ns"].get<double>() * 1e-9).c_str(),
              format_time(host["idle_ns"].get<double>() * 1e-9).c_str());
  const double bus_period = 1e-6 / bus["clock_mhz"].get<double>();
  std::printf("  %-10s %14s %11.1f%%  %s, %u-bit\n", "bus",
              format_time(bus["busy_cycles"].get<double>() * bus_period).c_str(),
              bus["utilisation"].get<double>() * 100, bus["arbitration"].get<std::string>().c_str(),
              bus["width_bits"].get<unsigned>());
  std::printf("  %-10s %14s %11.1f%%  %llu reads, %llu writes\n", "memory",
              format_time(memory["busy_ns"].get<double>() * 1e-9).c_str(), memory["utilisation"].get<double>() * 100,
              memory["reads"].get<unsigned long long>(), memory["writes"].get<unsigned long long>());
  std::printf("  %-10s %14s %12s  %llu frames shown, %.1f frames/s achieved, %llu underrun lines\n", "display", "-",
              "-", display["frames_shown"].get<unsigned long long>(), display["achieved_fps"].get<double>(),
              display["underrun_lines"].get<unsigned long long>());
  const auto& raster = stats["raster"];
  std::printf("  %-10s %14s %11.1f%%  %llu runs, %llu triangles, %llu tiles, %llu fragments (%llu written)\n", "raster",
              format_time(raster["busy_ns"].get<double>() * 1e-9).c_str(), raster["utilisation"].get<double>() * 100,
              raster["runs"].get<unsigned long long>(), raster["triangles"].get<unsigned long long>(),
              raster["tiles"].get<unsigned long long>(), raster["fragments"].get<unsigned long long>(),
              raster["fragments_written"].get<unsigned long long>());
  std::printf("\n  bus traffic per initiator\n  %-12s %12s %12s %12s %12s %12s\n", "initiator", "transactions", "bytes",
              "busy cycles", "wait cycles", "utilisation");
  for (const auto& [name, s] : bus["initiators"].items())
    std::printf("  %-12s %12llu %12llu %12llu %12llu %11.1f%%\n", name.c_str(),
                s["transactions"].get<unsigned long long>(), s["bytes"].get<unsigned long long>(),
                s["busy_cycles"].get<unsigned long long>(), s["wait_cycles"].get<unsigned long long>(),
                s["utilisation"].get<double>() * 100);
  std::printf("\n  outputs\n");
  for (const auto& line : outputs) std::printf("    %s\n", line.c_str());
  (void)soc;
}

// soc_sim's own parameters (sim.*): what to run and how the run is watched.
ParamGroup runner_parameters() {
  return {"soc_sim",
          {
              param::text("sim.app", "teapot", "application to run: a built-in name or a path to a shared library"),
              param::integer("sim.frames", 3, 1, 100000, "frames",
                             "frames the application draws before the simulation ends"),
              param::integer("sim.time_limit_ms", 60000, 1, 3600000, "ms",
                             "simulated-time limit; a run that reaches it stops with an error"),
              param::choice("sim.log_level", "warning", {"quiet", "error", "warning", "info", "debug"},
                            "lowest severity of the log lines printed on stderr"),
          },
          {}};
}

// Every parameter of a run: soc_sim's, the driver's, the SoC's and its blocks'.
std::vector<ParamGroup> all_parameters() {
  std::vector<ParamGroup> groups = {runner_parameters(), driver_parameters()};
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
  cli.add_option("--vcd", opt.vcd, "write a VCD trace to FILE");
  cli.add_option("--stats", opt.stats, "write statistics as JSON to FILE (default: <out>/stats.json)");
  cli.add_flag("--quiet,-q", opt.quiet, "print nothing but errors");
  cli.add_option("--log-level", opt.log_level, "quiet, error, warning, info or debug (sim.log_level)");
  cli.add_flag("--print-config", opt.print_config, "print the effective configuration as JSON and exit");
  cli.add_flag("--config-reference", opt.config_reference, "print the configuration reference (Markdown) and exit");
  cli.add_flag("--list-apps", opt.list_apps, "list the built-in applications and exit");
  cli.add_option("app_args", opt.app_args, "arguments passed to the application (after --)");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e) == 0 ? 0 : EXIT_USAGE;
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
    config.validate();
  } catch (const ConfigError& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }
  if (opt.print_config) {
    std::cout << config.to_json().dump(2) << "\n";
    return 0;
  }

  AppInfo app;
  try {
    app = find_app(config.get_string("sim.app"));
  } catch (const std::invalid_argument& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }

  // SystemC appends ".vcd" to the name it is given.
  std::string vcd_base = opt.vcd;
  if (vcd_base.size() > 4 && vcd_base.substr(vcd_base.size() - 4) == ".vcd") vcd_base.resize(vcd_base.size() - 4);
  const std::string stats_path = opt.stats.empty() ? (fs::path(opt.out_dir) / "stats.json").string() : opt.stats;
  try {
    prepare_output_dir(opt.out_dir);
    check_writable_file(stats_path);
    if (!opt.vcd.empty()) check_writable_file(vcd_base + ".vcd");
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }

  log::install(log::parse_level(config.get_string("sim.log_level")));
  const unsigned frames = static_cast<unsigned>(config.get_uint("sim.frames"));
  Soc soc("soc", config);
  PngWriterThread png_writer;
  unsigned frames_shown = 0;
  soc.display.on_frame([&](const Frame& frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04u.png", frame.index);
    png_writer.write((fs::path(opt.out_dir) / name).string(), frame.width, frame.height, frame.rgba);
    ++frames_shown;
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
  ActivityCounters driver_counters;
  env.counters = &driver_counters;
  env.make_renderer = backends::backend(config.get_string("driver.backend")).make_renderer;
  soc.set_program([&env, &app](HostApi& host) {
    env.host = &host;
    return app.main(env);
  });

  if (!opt.vcd.empty()) soc.trace_to(vcd_base);

  Progress progress(!opt.quiet && isatty(STDERR_FILENO), frames);
  const auto wall_start = std::chrono::steady_clock::now();
  auto wall_seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };
  const sc_core::sc_time limit(static_cast<double>(config.get_uint("sim.time_limit_ms")), sc_core::SC_MS);
  const sc_core::sc_time slice(1, sc_core::SC_MS);
  try {
    while (!soc.done() && sc_core::sc_get_status() != sc_core::SC_STOPPED && sc_core::sc_time_stamp() < limit) {
      sc_core::sc_start(slice);
      progress.update(frames_shown, sc_core::sc_time_stamp().to_seconds(), wall_seconds());
    }
  } catch (const std::exception& e) {
    progress.finish();
    std::cerr << "soc_sim: simulation failed: " << e.what() << "\n";
    return EXIT_SIM_FAILED;
  }
  progress.finish();
  soc.close_trace();
  const std::string png_error = png_writer.finish();
  const unsigned frames_written = png_writer.written();
  const double wall = wall_seconds();

  int status = 0;
  if (!png_error.empty()) {
    std::cerr << "soc_sim: " << png_error << "\n";
    status = EXIT_SIM_FAILED;
  } else if (!soc.done()) {
    std::cerr << "soc_sim: simulated-time limit of " << config.get_uint("sim.time_limit_ms")
              << " ms reached before the application finished (sim.time_limit_ms)\n";
    status = EXIT_SIM_FAILED;
  } else if (soc.host.exit_code() != 0) {
    std::cerr << "soc_sim: application failed: " << soc.host.failure() << "\n";
    // An application reports bad input (an unreadable file, a bad argument)
    // with status 2, like soc_sim itself.
    status = soc.host.exit_code() == EXIT_USAGE ? EXIT_USAGE : EXIT_SIM_FAILED;
  }

  nlohmann::json stats = soc.stats_json();
  stats["driver"] = to_json(driver_counters);
  nlohmann::json document = {{"application", config.get_string("sim.app")},
                             {"frames_written", frames_written},
                             {"exit_status", status},
                             {"config", config.to_json()},
                             {"stats", stats}};
  std::ofstream(stats_path) << document.dump(2) << "\n";

  if (!opt.quiet) {
    std::vector<std::string> outputs;
    if (frames_written)
      outputs.push_back(std::to_string(frames_written) + " frame(s): " +
                        (fs::path(opt.out_dir) / "frame_0000.png").string() + (frames_written > 1 ? " ..." : ""));
    outputs.push_back("statistics: " + stats_path);
    if (!opt.vcd.empty()) outputs.push_back("VCD trace: " + vcd_base + ".vcd");
    print_summary(soc, stats, config.get_string("sim.app"), wall, outputs);
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
