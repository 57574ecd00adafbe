// bench_speed: issue 13's speed table from one command. Every row runs the
// programs the other benchmarks use, as children, in paired rounds (each
// round runs the measured program and its reference one after the other,
// the order rotating from round to round, so that a change in the machine's
// load hits both), and prints min and median of each side and two ratios:
// that of the mins and the median of the ratios within each round. Then the
// scaling of a frame's wall time with triangles and pixels, fitted as a
// power law. See README.md for the method.
//
//   bench_speed [--rounds R] [--frames N] [--startup-runs S] [--no-scaling] [--only PART] [--work-dir DIR]
//               [--baseline OTHER_SOC_SIM]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "guarded_main.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace tessera::bench;

struct Options {
  unsigned rounds = 5;
  unsigned frames = 10;
  unsigned startup_runs = 11;
  unsigned bus_rounds = 31;
  unsigned rtl_vectors = 200000;
  bool scaling = true;
  std::string only;  // one part of the table alone: startup, arm, raster, array, bus, datapath, options
  unsigned scaling_frames = 3;
  unsigned scaling_rounds = 3;
  std::vector<unsigned> triangles = {80, 800, 8000, 80000};
  std::vector<std::string> sizes = {"320x240", "384x288", "448x336", "512x384", "512x512"};
  std::string work_dir;
  fs::path bin;
  // --baseline: another build's soc_sim, for the options part's rows of
  // this build against it with every option off.
  std::string baseline;
};

std::string format_duration(double seconds) {
  char text[32];
  if (seconds >= 1e-3) return format_ms(seconds);
  const double us = seconds * 1e6;
  if (us >= 1)
    std::snprintf(text, sizeof text, us >= 100 ? "%.0f us" : us >= 10 ? "%.1f us" : "%.2f us", us);
  else
    std::snprintf(text, sizeof text, seconds * 1e9 >= 10 ? "%.1f ns" : "%.2f ns", seconds * 1e9);
  return text;
}

// printf into a string.
template <typename... Args>
std::string text_of(const char* format, Args... args) {
  char text[512];
  std::snprintf(text, sizeof text, format, args...);
  return text;
}

std::string pair_text(const MinMedian& m, const std::function<std::string(double)>& format) {
  return format(m.min) + " / " + format(m.median);
}

// One row of the table: `measured` against `reference`, paired by round.
struct Row {
  Row() = default;
  Row(std::string description, std::string goal_text) : what(std::move(description)), goal(std::move(goal_text)) {}
  std::string what;
  std::string goal;
  std::vector<double> measured;
  std::vector<double> reference;  // empty: an absolute figure, no ratio
  // CPU time of the same runs (each process's own clock over the timed
  // frames), where both sides report it: a loaded machine inflates wall
  // times, hardly CPU times.
  std::vector<double> cpu_measured, cpu_reference;
  // true: the goal is a ratio at most goal_value (or a time at most it,
  // without a reference); false: at least goal_value.
  bool at_most = true;
  double goal_value = 0;
  bool invert = false;  // ratio is reference / measured (a speed-up)
  std::function<std::string(double)> format = format_duration;
  // What keeps the row from its goal, from figures of this run; printed
  // below the table when the goal is not met.
  std::function<std::string()> limit;
};

// "less than" or "no less than": a limit's text compares figures of its run.
const char* than(double a, double b) {
  return a < b ? "less than" : "no less than";
}

// The median of the ratios within rounds: the figure a row's goal is judged on.
double decisive_figure(const Row& row) {
  if (row.reference.empty()) return min_median(row.measured).median;
  std::vector<double> paired;
  for (size_t i = 0; i < row.measured.size() && i < row.reference.size(); ++i)
    paired.push_back(row.invert ? row.reference[i] / row.measured[i] : row.measured[i] / row.reference[i]);
  return min_median(paired).median;
}

bool goal_met(const Row& row) {
  const double decisive = decisive_figure(row);
  return row.at_most ? decisive <= row.goal_value : decisive >= row.goal_value;
}

std::string ratio_text(double ratio) {
  char text[32];
  std::snprintf(text, sizeof text, ratio >= 100 ? "%.0f" : ratio >= 10 ? "%.1f" : "%.2f", ratio);
  return text;
}

void print_row(const Row& row) {
  const MinMedian m = min_median(row.measured);
  std::string against = "-", ratios = "-";
  if (!row.reference.empty()) {
    const MinMedian r = min_median(row.reference);
    against = pair_text(r, row.format);
    const double mins = row.invert ? r.min / m.min : m.min / r.min;
    ratios = ratio_text(mins) + " / " + ratio_text(decisive_figure(row));
  }
  std::string cpu = "-";
  if (!row.cpu_measured.empty() && !row.cpu_reference.empty())
    cpu = ratio_text(paired_median(row.cpu_measured, row.cpu_reference));
  const bool met = goal_met(row);
  std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", row.what.c_str(), pair_text(m, row.format).c_str(),
              against.c_str(), ratios.c_str(), cpu.c_str(), row.goal.c_str(),
              row.goal == "-" ? "-"
              : met           ? "yes"
                              : "**no**");
}

class Bench {
 public:
  explicit Bench(Options options) : m_opt(std::move(options)) {}
  void run();

 private:
  fs::path program(const std::string& name) const { return m_opt.bin / name; }
  ChildResult child(const std::vector<std::string>& argv) {
    return run_child(argv, m_work / ("child_" + std::to_string(m_runs++) + ".stdout"));
  }
  // soc_sim for 2N frames with --wall-clock and --no-frames (or writing PNG
  // files); the wall time per frame of frames N..2N-1.
  double soc_sim_frame(const std::vector<std::string>& args, unsigned n, bool png,
                       const std::vector<std::string>& app_args = {}, const fs::path& soc_sim = {});
  // Runs the commands of one round in an order rotated by `round`.
  static void in_rotation(unsigned round, const std::vector<std::function<void()>>& steps) {
    for (size_t i = 0; i < steps.size(); ++i) steps[(i + round) % steps.size()]();
  }
  void arm_rows();
  void raster_row();
  void array_rows();
  void bus_row();
  void datapath_rows();
  void startup_rows();
  void option_rows();
  void scaling();
  void print_table() const;

  Options m_opt;
  fs::path m_work;
  json m_config;
  unsigned m_runs = 0;
  double m_last_cpu = 0;  // CPU time per frame of the last soc_sim_frame run (cpu_ns)
  // Bus transactions per frame of the last soc_sim_frame run, every
  // initiator's, averaged over its 2N frames (stats.json).
  double m_last_transactions = 0;
  // Bus requests per frame of the same run: the grants (the wait
  // histograms' counts, every initiator's), where a posted run of stores
  // is one request of many transfers.
  double m_last_requests = 0;
  double m_arm_transactions = 0, m_raster_transactions = 0;  // of the --no-frames runs
  double m_arm_requests = 0;
  // Array instructions broadcast per frame of the last soc_sim_frame run,
  // averaged over its 2N frames (stats.json; 0 without the array).
  double m_last_array_instructions = 0;
  std::vector<double> m_floor_s;  // bench_bus's bare b_transport, per round
  // Its median; 0 if bench_bus gave no 4-byte read.
  double floor_seconds() const { return m_floor_s.empty() ? 0 : min_median(m_floor_s).median; }
  // What a goal of `goal` times the reference frame leaves for everything
  // the simulation adds, in all and per bus transaction, against the floor.
  std::string transaction_budget(double transactions, double reference_frame, double goal,
                                 const char* unit = "transaction") const {
    const double allowed = (goal - 1) * reference_frame;
    const double each = allowed / std::max(1.0, transactions);
    const std::string budget =
        text_of("The goal leaves %.2g of the reference frame, %s, for all the simulation adds: %s per %s", goal - 1,
                format_duration(allowed).c_str(), format_duration(each).c_str(), unit);
    if (!floor_measured())
      return budget + " (the bus row's floor, a bare b_transport, was not measured: --only left the bus part out)";
    return budget + text_of(", %s one bare b_transport (%s, the floor of the bus row)", than(each, floor_seconds()),
                            format_duration(floor_seconds()).c_str());
  }
  // Whether this run measured the bus row's floor (not with --only naming
  // other rows): without it, the limits say so rather than compare with 0.
  bool floor_measured() const { return floor_seconds() > 0; }
  std::vector<Row> m_rows;
  std::vector<std::string> m_notes;
  std::string m_datapath_table;
  std::string m_scaling_text;
};

double Bench::soc_sim_frame(const std::vector<std::string>& args, unsigned n, bool png,
                            const std::vector<std::string>& app_args, const fs::path& soc_sim) {
  const fs::path out = m_work / ("soc_sim_" + std::to_string(m_runs));
  std::vector<std::string> command = {soc_sim.empty() ? program("soc_sim").string() : soc_sim.string()};
  command.insert(command.end(), args.begin(), args.end());
  command.insert(command.end(),
                 {"--frames", std::to_string(2 * n), "--out", out.string(), "--quiet", "--force", "--wall-clock"});
  if (!png) command.push_back("--no-frames");
  if (!app_args.empty()) {
    command.push_back("--");
    command.insert(command.end(), app_args.begin(), app_args.end());
  }
  child(command);
  const json stats = read_json_file(out / "stats.json");
  fs::remove_all(out);
  double transactions = 0;
  for (const auto& [name, initiator] : stats.at("stats").at("bus").at("initiators").items())
    transactions += initiator.at("transactions").get<double>();
  m_last_transactions = transactions / (2.0 * n);
  double requests = 0;
  for (const auto& [name, histogram] : stats.at("stats").at("bus").at("histograms").at("wait_cycles").items())
    requests += histogram.at("count").get<double>();
  m_last_requests = requests / (2.0 * n);
  m_last_cpu = positive(per_frame_seconds(stats, n, "cpu_ns"), "soc_sim CPU per frame");
  const json& array = stats.at("stats").contains("array") ? stats.at("stats").at("array") : json::object();
  m_last_array_instructions = array.contains("instructions") ? array.at("instructions").get<double>() / (2.0 * n) : 0;
  return positive(per_frame_seconds(stats, n, "wall_ns"), "soc_sim wall per frame");
}

void Bench::arm_rows() {
  const unsigned n = m_opt.frames;
  const json& display = m_config["display"];
  const std::string width = std::to_string(display["width"].get<unsigned>());
  const std::string height = std::to_string(display["height"].get<unsigned>());
  Row native{"`arm` teapot frame: soc_sim --no-frames / the renderer natively (bench_arm_native)", "<= 1.5x"};
  native.goal_value = 1.5;
  Row png{"`arm` teapot frame: soc_sim writing PNG frames / natively", "<= 1.5x"};
  png.goal_value = 1.5;
  Row mesa{"`arm` teapot frame: soc_sim --no-frames / Mesa softpipe (bench_arm_mesa)", "< 1x (faster)"};
  mesa.goal_value = 1.0;
  // The host-compiled model against the ISS it is measured on
  // (sw_driver/costs): the same frame, both --no-frames; fewer frames on
  // the ISS, whose frames take seconds.
  Row iss{"`arm` teapot frame: soc_sim with host.model=iss / host.model=native", ">= 20x (native faster)"};
  iss.goal_value = 20;
  iss.at_most = false;
  const unsigned iss_frames = std::max(1u, std::min(n, 2u));
  std::vector<double> sim, sim_png, native_s, mesa_s, sim_cpu, sim_png_cpu, native_cpu, mesa_cpu, iss_s, iss_cpu;
  for (unsigned r = 0; r < m_opt.rounds; ++r) {
    std::fprintf(stderr, "bench_speed: arm teapot, round %u of %u ...\n", r + 1, m_opt.rounds);
    in_rotation(r, {
                       [&] {
                         sim.push_back(soc_sim_frame({"--app", "teapot", "--backend", "arm"}, n, false));
                         sim_cpu.push_back(m_last_cpu);
                         m_arm_transactions = m_last_transactions;
                         m_arm_requests = m_last_requests;
                       },
                       [&] {
                         sim_png.push_back(soc_sim_frame({"--app", "teapot", "--backend", "arm"}, n, true));
                         sim_png_cpu.push_back(m_last_cpu);
                       },
                       [&] {
                         iss_s.push_back(soc_sim_frame(
                             {"--app", "teapot", "--backend", "arm", "--set", "host.model=iss"}, iss_frames, false));
                         iss_cpu.push_back(m_last_cpu);
                       },
                       [&] {
                         const ChildResult c = child({program("bench_arm_native").string(), "--scene", "teapot",
                                                      "--frames", std::to_string(n), "--width", width, "--height",
                                                      height, "--format", display["format"].get<std::string>(), "--dma",
                                                      display["dma"].get<bool>() ? "true" : "false", "--mem-mib",
                                                      std::to_string(m_config["mem"]["size_mib"].get<unsigned>())});
                         const json out = json::parse(c.output);
                         native_s.push_back(positive(out["wall_per_frame_s"].get<double>(), "native per frame"));
                         native_cpu.push_back(positive(out["cpu_per_frame_s"].get<double>(), "native CPU per frame"));
                       },
                       [&] {
                         const ChildResult c =
                             child({program("bench_arm_mesa").string(), "--scene", "teapot", "--frames",
                                    std::to_string(n), "--repeat", "1", "--width", width, "--height", height});
                         const json out = json::parse(c.output);
                         mesa_s.push_back(positive(out["wall_per_frame_s"].get<double>(), "Mesa per frame"));
                         mesa_cpu.push_back(positive(out["cpu_per_frame_s"].get<double>(), "Mesa CPU per frame"));
                       },
                   });
  }
  native.measured = sim;
  native.reference = native_s;
  native.cpu_measured = sim_cpu;
  native.cpu_reference = native_cpu;
  png.measured = sim_png;
  png.reference = native_s;
  png.cpu_measured = sim_png_cpu;
  png.cpu_reference = native_cpu;
  iss.measured = iss_s;
  iss.reference = sim;
  iss.cpu_measured = iss_cpu;
  iss.cpu_reference = sim_cpu;
  mesa.measured = sim;
  mesa.reference = mesa_s;
  mesa.cpu_measured = sim_cpu;
  mesa.cpu_reference = mesa_cpu;
  // What the goal leaves for everything the simulation adds, per bus
  // transaction, against the bare b_transport of the bus row's floor.
  const double native_frame = min_median(native_s).median;
  native.limit = [this, native_frame, goal = native.goal_value] {
    return text_of(
               "the host's memory traffic: %.0f bus requests a frame (stats.json's bus wait histograms, averaged "
               "over the run; %.0f transfers, a posted run of stores being one request): each cache line fill, "
               "victim written back, run of stores posted and burst to the display port, as the timing model "
               "requires, and each costs the host's model (cache, write buffer, quantum) and the bus's (its "
               "reservation and figures). ",
               m_arm_requests, m_arm_transactions) +
           transaction_budget(m_arm_requests, native_frame, goal, "request") +
           (floor_measured() ? text_of(", at whose cost the requests alone would take %s a frame",
                                       format_duration(m_arm_requests * floor_seconds()).c_str())
                             : std::string());
  };
  png.limit = [] {
    return std::string("the same traffic as the row above (its bus requests are the same), and the PNG files");
  };
  const double mesa_frame = min_median(mesa_s).median;
  mesa.limit = [this, mesa_frame] {
    const double floor = floor_seconds();
    if (!floor_measured())
      return text_of(
          "the same traffic: %.0f bus requests a frame, against Mesa's whole frame of %s (the bus "
          "row's floor, a bare b_transport, was not measured: --only left the bus part out)",
          m_arm_requests, format_duration(mesa_frame).c_str());
    return text_of(
        "the same traffic: %.0f bus requests a frame would take %s at the cost of one bare b_transport "
        "each (%s, the bus row's floor), against Mesa's whole frame of %s",
        m_arm_requests, format_duration(m_arm_requests * floor).c_str(), format_duration(floor).c_str(),
        format_duration(mesa_frame).c_str());
  };
  m_rows.push_back(native);
  m_rows.push_back(png);
  m_rows.push_back(mesa);
  m_rows.push_back(iss);
}

// What seeing a run costs (docs/usage.md, "Outputs"): with every option
// off, this build against --baseline's (a build from before the options:
// the goal is no cost, within the noise); and on, the teapot frame with a
// timeline and with a transaction trace against none, in this build.
void Bench::option_rows() {
  const unsigned n = m_opt.frames;
  const std::vector<std::string> arm = {"--app", "teapot", "--backend", "arm"};
  const std::vector<std::string> tile = {"--app", "teapot", "--backend", "ap-tile", "--set", "dma.enabled=true"};
  const fs::path timeline = m_work / "timeline.json", transactions = m_work / "transactions.csv";
  const auto with = [](std::vector<std::string> args, std::initializer_list<std::string> more) {
    args.insert(args.end(), more);
    return args;
  };
  std::vector<Row> rows;
  std::vector<std::function<void()>> steps;
  const auto pair = [&](Row row, const std::vector<std::string>& measured_args,
                        const std::vector<std::string>& reference_args, const fs::path& reference_program) {
    rows.push_back(std::move(row));
    const size_t i = rows.size() - 1;
    steps.push_back([&, i, measured_args, reference_args, reference_program] {
      rows[i].measured.push_back(soc_sim_frame(measured_args, n, false));
      rows[i].cpu_measured.push_back(m_last_cpu);
      rows[i].reference.push_back(soc_sim_frame(reference_args, n, false, {}, reference_program));
      rows[i].cpu_reference.push_back(m_last_cpu);
    });
  };
  if (!m_opt.baseline.empty()) {
    for (const auto& [name, args] : {std::pair{"arm", arm}, std::pair{"ap-tile", tile}}) {
      Row row{std::string("`") + name + "` teapot frame, every option off: this soc_sim / --baseline's", "<= 1.03x"};
      row.goal_value = 1.03;
      pair(row, args, args, m_opt.baseline);
    }
  }
  pair(Row{"`arm` teapot frame: with --timeline (blocks) / without", "-"}, with(arm, {"--timeline", timeline.string()}),
       arm, {});
  pair(Row{"`ap-tile` teapot frame: with --trace-transactions (all) / without", "-"},
       with(tile, {"--trace-transactions", transactions.string()}), tile, {});
  for (unsigned r = 0; r < m_opt.rounds; ++r) {
    std::fprintf(stderr, "bench_speed: options, round %u of %u ...\n", r + 1, m_opt.rounds);
    in_rotation(r, steps);
  }
  fs::remove(timeline);
  fs::remove(transactions);
  for (Row& row : rows) m_rows.push_back(std::move(row));
}

void Bench::raster_row() {
  const unsigned n = m_opt.frames;
  Row row{"`raster` teapot frame: soc_sim --no-frames / its core natively (bench_raster --native-core)", "<= 1.2x"};
  row.goal_value = 1.2;
  std::vector<double> per_fragment;
  for (unsigned r = 0; r < m_opt.rounds; ++r) {
    std::fprintf(stderr, "bench_speed: raster teapot, round %u of %u ...\n", r + 1, m_opt.rounds);
    in_rotation(r, {
                       [&] {
                         row.measured.push_back(soc_sim_frame({"--app", "teapot", "--backend", "raster"}, n, false));
                         row.cpu_measured.push_back(m_last_cpu);
                         m_raster_transactions = m_last_transactions;
                       },
                       [&] {
                         const json out = json::parse(child({program("bench_raster").string(), "--native-core",
                                                             "teapot", "--frames", std::to_string(n)})
                                                          .output);
                         const double seconds = positive(out["seconds"].get<double>(), "native core time");
                         const double cpu = positive(out["cpu_seconds"].get<double>(), "native core CPU time");
                         row.reference.push_back(seconds / n);
                         row.cpu_reference.push_back(cpu / n);
                         // The core's own speed: its thread's CPU time, which a loaded machine inflates least.
                         per_fragment.push_back(cpu / positive(out["fragments"].get<double>(), "fragments"));
                       },
                   });
  }
  const double core_frame = min_median(row.reference).median;
  row.limit = [this, core_frame, goal = row.goal_value] {
    return text_of(
               "around the core, the host model and the bus: %.0f bus transactions a frame (the rasterizer's bursts "
               "and the host's, each arbitrated; stats.json, averaged over the run). ",
               m_raster_transactions) +
           transaction_budget(m_raster_transactions, core_frame, goal);
  };
  m_rows.push_back(row);
  Row fragment{"`raster` core natively: CPU time per fragment", "4x faster than 215 ns: <= 54 ns"};
  fragment.measured = per_fragment;
  fragment.goal_value = 215e-9 / 4;
  fragment.limit = [fast = min_median(per_fragment).min, goal = fragment.goal_value] {
    if (fast <= goal)
      return text_of(
          "the machine's noise: the fastest round took %s per fragment, within the goal of %s (the core's "
          "stages run in batches: tlm/raster/core/README.md)",
          format_duration(fast).c_str(), format_duration(goal).c_str());
    return text_of(
        "the core's own work: its fastest round took %s per fragment against the goal of %s (the stages "
        "already run in batches: tlm/raster/core/README.md)",
        format_duration(fast).c_str(), format_duration(goal).c_str());
  };
  m_rows.push_back(fragment);
}

// The array back ends against arm on the same teapot frame, at the
// study's 192x144 (one 8x36 tile per CU), and each with the array's idle
// CUs run (array.skip_idle_cus=false) against skipped: its speed-up.
void Bench::array_rows() {
  const unsigned n = m_opt.frames;
  const auto run = [this, n](const std::string& backend, bool skip) {
    return soc_sim_frame(
        {"--app", "teapot", "--backend", backend, "--set", "display.width=192", "--set", "display.height=144", "--set",
         std::string("array.skip_idle_cus=") + (skip ? "true" : "false")},
        n, false);
  };
  Row tile{"`ap-tile` teapot frame at 192x144: soc_sim --no-frames / `arm`'s (the same frame)", "<= 5x"};
  tile.goal_value = 5;
  Row pixel{"`ap-pixel` teapot frame at 192x144: soc_sim --no-frames / `arm`'s", "<= 3x"};
  pixel.goal_value = 3;
  Row tile_skip{"`ap-tile` teapot frame at 192x144: array.skip_idle_cus=false / true (the skip's speed-up)", "-"};
  Row pixel_skip{"`ap-pixel` teapot frame at 192x144: array.skip_idle_cus=false / true", "-"};
  std::vector<double> arm, arm_cpu;
  double arm_transactions = 0;
  double tile_instructions = 0, tile_transactions = 0, pixel_instructions = 0, pixel_transactions = 0;
  for (unsigned r = 0; r < m_opt.rounds; ++r) {
    std::fprintf(stderr, "bench_speed: ap-tile and ap-pixel teapot at 192x144, round %u of %u ...\n", r + 1,
                 m_opt.rounds);
    in_rotation(r, {
                       [&] {
                         arm.push_back(run("arm", true));
                         arm_cpu.push_back(m_last_cpu);
                         arm_transactions = m_last_transactions;
                       },
                       [&] {
                         tile.measured.push_back(run("ap-tile", true));
                         tile.cpu_measured.push_back(m_last_cpu);
                         tile_instructions = m_last_array_instructions;
                         tile_transactions = m_last_transactions;
                       },
                       [&] {
                         pixel.measured.push_back(run("ap-pixel", true));
                         pixel.cpu_measured.push_back(m_last_cpu);
                         pixel_instructions = m_last_array_instructions;
                         pixel_transactions = m_last_transactions;
                       },
                       [&] {
                         tile_skip.measured.push_back(run("ap-tile", false));
                         tile_skip.cpu_measured.push_back(m_last_cpu);
                       },
                       [&] {
                         pixel_skip.measured.push_back(run("ap-pixel", false));
                         pixel_skip.cpu_measured.push_back(m_last_cpu);
                       },
                   });
  }
  for (Row* row : {&tile, &pixel}) {
    row->reference = arm;
    row->cpu_reference = arm_cpu;
  }
  tile_skip.reference = tile.measured;
  tile_skip.cpu_reference = tile.cpu_measured;
  pixel_skip.reference = pixel.measured;
  pixel_skip.cpu_reference = pixel.cpu_measured;
  const double arm_frame = min_median(arm).median;
  const double tile_speedup = decisive_figure(tile_skip), pixel_speedup = decisive_figure(pixel_skip);
  tile.limit = [=, goal = tile.goal_value] {
    return text_of(
        "the array's instructions: %.0f broadcast a frame (stats.json), each one still dispatched once for the "
        "CUs that differ from their last run of the stage (about 10 of 96 on the teapot), so skipping the others "
        "makes the frame only %.2fx faster (the skip's row); and around the array, the host's set-up and its %.0f "
        "bus transactions a frame (the CIU's records and read-back). The goal leaves %s a frame for all of it, "
        "%s per array instruction",
        tile_instructions, tile_speedup, tile_transactions, format_duration(goal * arm_frame).c_str(),
        format_duration(goal * arm_frame / std::max(1.0, tile_instructions)).c_str());
  };
  pixel.limit = [=, goal = pixel.goal_value] {
    return text_of(
        "the host's traffic to the array: %.0f bus transactions a frame (stats.json; CIU writes of every block's "
        "attributes and reads of its results), against arm's %.0f; the array's own %.0f instructions a frame are "
        "a small part (skipping, whose blocks fill nearly every CU, makes the frame %.2fx faster: its row). The "
        "goal leaves %s a frame, %s per transaction",
        pixel_transactions, arm_transactions, pixel_instructions, pixel_speedup,
        format_duration(goal * arm_frame).c_str(),
        format_duration(goal * arm_frame / std::max(1.0, pixel_transactions)).c_str());
  };
  for (const Row& row : {tile, pixel, tile_skip, pixel_skip}) m_rows.push_back(row);
}

void Bench::bus_row() {
  std::fprintf(stderr, "bench_speed: bus and memory (bench_bus) ...\n");
  const json out = json::parse(
      child({program("bench_bus").string(), "--rounds", std::to_string(m_opt.bus_rounds), "--json"}).output);
  for (const json& kind : out["transactions"]) {
    if (kind["name"] != "4-byte read") continue;
    Row row{"one LT 4-byte read through bus + memory / a bare tlm_quantumkeeper b_transport (bench_bus)", "<= 2x"};
    row.goal_value = 2.0;
    for (const json& v : kind["memory_ns"]) row.measured.push_back(positive(v.get<double>(), "bus + memory") * 1e-9);
    for (const json& v : kind["floor_ns"]) row.reference.push_back(positive(v.get<double>(), "floor") * 1e-9);
    Row bus{"the same through the bus alone / the floor", "<= 2x"};
    bus.goal_value = 2.0;
    for (const json& v : kind["bus_ns"]) bus.measured.push_back(positive(v.get<double>(), "bus") * 1e-9);
    bus.reference = row.reference;
    m_floor_s = row.reference;
    row.limit = [bus_ratio = decisive_figure(bus), bus_s = min_median(bus.measured).median,
                 memory_s = min_median(row.measured).median] {
      return text_of(
          "the bus: alone it is already %.2fx the floor (the next row), so the memory's b_transport behind it "
          "cannot fit in the 2x; through both a read takes %s, through the bus alone %s (same rounds)",
          bus_ratio, format_duration(memory_s).c_str(), format_duration(bus_s).c_str());
    };
    bus.limit = [] {
      return std::string(
          "the bus's own b_transport per access: decoding, arbitration and the reservation of its cycles, "
          "statistics (tlm/bus/README.md, \"The hot path\")");
    };
    m_rows.push_back(row);
    m_rows.push_back(bus);
  }
}

// A figure of bench_rtl's table: ns per operation, a plain number.
double parse_ns(const std::string& text) {
  std::istringstream in(text);
  double value = 0;
  in >> value;
  return value;
}

std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  std::string cell;
  std::getline(in, cell, '|');  // before the first bar
  while (std::getline(in, cell, '|')) {
    const size_t first = cell.find_first_not_of(' ');
    const size_t last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  if (!cells.empty() && cells.back().empty()) cells.pop_back();
  return cells;
}

void Bench::datapath_rows() {
  // bench_rtl: each unit in C++ (its batch form) and in Verilated RTL on
  // the same vectors; one process per round, one pass each (--rounds 1),
  // read from its table by the columns' names (the first "C++ ... ns/op"
  // and "RTL ... ns/op" ones, the mins: of one pass, its time).
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> units;  // C++ s/op, RTL s/op
  std::vector<std::string> order;
  for (unsigned r = 0; r < m_opt.rounds; ++r) {
    std::fprintf(stderr, "bench_speed: datapath units (bench_rtl), round %u of %u ...\n", r + 1, m_opt.rounds);
    const std::string output =
        child({program("bench_rtl").string(), "--vectors", std::to_string(m_opt.rtl_vectors), "--rounds", "1"}).output;
    std::istringstream lines(output);
    int unit_column = -1, cpp_column = -1, rtl_column = -1;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind('|', 0) != 0) continue;
      const std::vector<std::string> cells = table_cells(line);
      if (unit_column < 0) {
        for (size_t i = 0; i < cells.size(); ++i) {
          if (cells[i] == "unit") unit_column = static_cast<int>(i);
          if (cpp_column < 0 && cells[i].rfind("C++", 0) == 0 && cells[i].find("ns/op") != std::string::npos)
            cpp_column = static_cast<int>(i);
          if (rtl_column < 0 && cells[i].rfind("RTL", 0) == 0 && cells[i].find("ns/op") != std::string::npos)
            rtl_column = static_cast<int>(i);
        }
        continue;
      }
      if (cpp_column < 0 || rtl_column < 0 || cells.size() <= static_cast<size_t>(std::max(cpp_column, rtl_column)) ||
          cells[0].rfind("---", 0) == 0)
        continue;
      const std::string& unit = cells[unit_column];
      if (!units.count(unit)) order.push_back(unit);
      units[unit].first.push_back(positive(parse_ns(cells[cpp_column]), unit + " C++ ns/op") * 1e-9);
      units[unit].second.push_back(positive(parse_ns(cells[rtl_column]), unit + " RTL ns/op") * 1e-9);
    }
  }
  if (units.empty()) throw std::runtime_error("bench_rtl printed no table with 'C++ ... ns/op' and 'RTL ... ns/op'");
  Row worst;
  double worst_speedup = 0;
  std::ostringstream table;
  table << "| unit | C++ per op (min / median) | RTL per op (min / median) | RTL / C++ (mins / median of pairs) |\n"
        << "|---|--:|--:|--:|\n";
  for (const std::string& unit : order) {
    Row row{"C++ datapath unit / its Verilated RTL, the slowest: " + unit + " (bench_rtl)", "RTL / C++ >= 50x"};
    row.measured = units[unit].first;
    row.reference = units[unit].second;
    row.invert = true;
    row.at_most = false;
    row.goal_value = 50;
    std::vector<double> paired;
    for (size_t i = 0; i < row.measured.size(); ++i) paired.push_back(row.reference[i] / row.measured[i]);
    const double speedup = min_median(paired).median;
    const MinMedian c = min_median(row.measured), v = min_median(row.reference);
    table << "| " << unit << " | " << pair_text(c, format_duration) << " | " << pair_text(v, format_duration) << " | "
          << ratio_text(v.min / c.min) << " / " << ratio_text(speedup) << " |\n";
    row.limit = [c, v] {
      return text_of(
          "the C++: its batch form takes %s per operation (branch-free, vectorised for the widest instruction "
          "set the processor has), the Verilated RTL %s; 50x needs %s per operation",
          format_duration(c.median).c_str(), format_duration(v.median).c_str(), format_duration(v.median / 50).c_str());
    };
    if (worst.measured.empty() || speedup < worst_speedup) {
      worst = row;
      worst_speedup = speedup;
    }
  }
  m_rows.push_back(worst);
  m_datapath_table = table.str();
}

void Bench::startup_rows() {
  // Start-up: the whole process, from spawn to exit, of soc_sim listing
  // its applications and of a one-frame run of the smallest scene writing
  // no image (its simulation takes a few ms of it), its CPU time (user +
  // system, every thread: what a loaded machine does not inflate) and its
  // peak memory; and the same run writing its frame. The three alternate.
  const auto mib = [](double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", bytes / (1 << 20));
    return std::string(text);
  };
  Row list{"soc_sim --list-apps: wall time of the process", "<= 50 ms"};
  list.goal_value = 50e-3;
  Row list_cpu{"soc_sim --list-apps: CPU time", "-"};
  Row frame{"soc_sim --app triangle --frames 1 --no-frames: wall time of the process", "<= 50 ms"};
  frame.goal_value = 50e-3;
  Row frame_cpu{"soc_sim --app triangle --frames 1 --no-frames: CPU time", "-"};
  Row rss{"soc_sim --app triangle --frames 1 --no-frames: peak RSS", "-"};
  rss.format = mib;
  Row png{"the same writing its frame as PNG: wall time", "-"};
  Row rss_png{"the same writing its frame as PNG: peak RSS", "-"};
  rss_png.format = mib;
  std::fprintf(stderr, "bench_speed: soc_sim start-up, %u runs each ...\n", m_opt.startup_runs);
  const std::string soc_sim = program("soc_sim").string();
  for (unsigned r = 0; r < m_opt.startup_runs; ++r) {
    in_rotation(r, {
                       [&] {
                         const ChildResult c = child({soc_sim, "--list-apps"});
                         list.measured.push_back(c.wall_s);
                         list_cpu.measured.push_back(c.cpu_s);
                       },
                       [&] {
                         const fs::path out = m_work / "startup";
                         const ChildResult c = child({soc_sim, "--app", "triangle", "--frames", "1", "--no-frames",
                                                      "--quiet", "--force", "--out", out.string()});
                         frame.measured.push_back(c.wall_s);
                         frame_cpu.measured.push_back(c.cpu_s);
                         rss.measured.push_back(static_cast<double>(c.max_rss_kib) * 1024);
                       },
                       [&] {
                         const fs::path out = m_work / "startup_png";
                         const ChildResult c = child({soc_sim, "--app", "triangle", "--frames", "1", "--quiet",
                                                      "--force", "--out", out.string()});
                         png.measured.push_back(c.wall_s);
                         rss_png.measured.push_back(static_cast<double>(c.max_rss_kib) * 1024);
                       },
                   });
  }
  for (const Row& row : {list, list_cpu, frame, frame_cpu, rss, png, rss_png}) m_rows.push_back(row);
}

// Least-squares slope of log(y) against log(x): the exponent of y ~ x^k.
double exponent(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    mx += std::log(x[i]);
    my += std::log(y[i]);
  }
  mx /= static_cast<double>(x.size());
  my /= static_cast<double>(x.size());
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxx > 0 ? sxy / sxx : 0;
}

// An OBJ grid of `triangles` triangles (2 per cell of a nearly square
// grid), gently curved so that it is lit unevenly; obj_viewer fits it to
// the view, so every size covers the same pixels.
unsigned write_grid_obj(const fs::path& path, unsigned triangles) {
  // rows x columns cells, rows the largest divisor of the cell count up to
  // its square root: exactly `triangles` triangles when it is even.
  const unsigned cells = std::max(1u, triangles / 2);
  unsigned rows = 1;
  for (unsigned r = 1; r * r <= cells; ++r)
    if (cells % r == 0) rows = r;
  const unsigned columns = cells / rows;
  std::ofstream out(path);
  for (unsigned y = 0; y <= rows; ++y)
    for (unsigned x = 0; x <= columns; ++x) {
      const double u = static_cast<double>(x) / columns, v = static_cast<double>(y) / rows;
      out << "v " << u * 2 - 1 << " " << v * 2 - 1 << " " << 0.2 * std::sin(3 * u) * std::cos(3 * v) << "\n";
    }
  const auto index = [columns](unsigned x, unsigned y) { return y * (columns + 1) + x + 1; };
  for (unsigned y = 0; y < rows; ++y)
    for (unsigned x = 0; x < columns; ++x) {
      out << "f " << index(x, y) << " " << index(x + 1, y) << " " << index(x + 1, y + 1) << "\n";
      out << "f " << index(x, y) << " " << index(x + 1, y + 1) << " " << index(x, y + 1) << "\n";
    }
  if (!out) throw std::runtime_error("cannot write " + path.string());
  return 2 * rows * columns;
}

void Bench::scaling() {
  const unsigned n = m_opt.scaling_frames;
  std::ostringstream text;
  // Triangles: obj_viewer on grids of 80 to 80,000 triangles.
  std::vector<unsigned> counts;
  std::vector<fs::path> files;
  for (const unsigned t : m_opt.triangles) {
    files.push_back(m_work / ("grid_" + std::to_string(t) + ".obj"));
    counts.push_back(write_grid_obj(files.back(), t));
  }
  std::vector<std::vector<double>> tri_times(counts.size()), tri_cpu(counts.size());
  for (unsigned r = 0; r < m_opt.scaling_rounds; ++r) {
    std::fprintf(stderr, "bench_speed: scaling with triangles, round %u of %u ...\n", r + 1, m_opt.scaling_rounds);
    std::vector<std::function<void()>> steps;
    for (size_t i = 0; i < counts.size(); ++i)
      steps.emplace_back([&, i] {
        tri_times[i].push_back(
            soc_sim_frame({"--app", "obj_viewer", "--backend", "arm"}, n, false, {files[i].string()}));
        tri_cpu[i].push_back(m_last_cpu);
      });
    in_rotation(r, steps);
  }
  // Pixels: fullscreen_rect (every pixel drawn) at display sizes up to the largest.
  std::vector<double> pixels;
  std::vector<std::vector<double>> pix_times(m_opt.sizes.size()), pix_cpu(m_opt.sizes.size());
  for (const std::string& size : m_opt.sizes) {
    const size_t x = size.find('x');
    pixels.push_back(std::stod(size.substr(0, x)) * std::stod(size.substr(x + 1)));
  }
  for (unsigned r = 0; r < m_opt.scaling_rounds; ++r) {
    std::fprintf(stderr, "bench_speed: scaling with pixels, round %u of %u ...\n", r + 1, m_opt.scaling_rounds);
    std::vector<std::function<void()>> steps;
    for (size_t i = 0; i < m_opt.sizes.size(); ++i)
      steps.emplace_back([&, i] {
        const std::string& size = m_opt.sizes[i];
        const size_t x = size.find('x');
        pix_times[i].push_back(
            soc_sim_frame({"--app", "fullscreen_rect", "--backend", "arm", "--set",
                           "display.width=" + size.substr(0, x), "--set", "display.height=" + size.substr(x + 1)},
                          n, false));
        pix_cpu[i].push_back(m_last_cpu);
      });
    in_rotation(r, steps);
  }
  // The exponent k of time ~ x^k, least squares on log-log over every
  // point, and between the two largest points (the trend where the fixed
  // cost of a frame matters least).
  const auto fit = [](const std::vector<double>& x, const std::vector<double>& y) {
    const size_t last = x.size() - 1;
    return std::pair{exponent(x, y), std::log(y[last] / y[last - 1]) / std::log(x[last] / x[last - 1])};
  };
  const auto report = [&text, &fit](const char* title, const std::vector<double>& x,
                                    const std::vector<std::vector<double>>& wall,
                                    const std::vector<std::vector<double>>& cpu) {
    std::vector<double> wall_medians, cpu_medians;
    text << "| " << title << " | wall / frame (min / median) | CPU / frame (min / median) |\n|--:|--:|--:|\n";
    for (size_t i = 0; i < x.size(); ++i) {
      wall_medians.push_back(min_median(wall[i]).median);
      cpu_medians.push_back(min_median(cpu[i]).median);
      char value[32];
      std::snprintf(value, sizeof value, "%.0f", x[i]);
      text << "| " << value << " | " << pair_text(min_median(wall[i]), format_duration) << " | "
           << pair_text(min_median(cpu[i]), format_duration) << " |\n";
    }
    const auto [k_wall, top_wall] = fit(x, wall_medians);
    const auto [k_cpu, top_cpu] = fit(x, cpu_medians);
    char line[400];
    std::snprintf(line, sizeof line,
                  "\ntime ~ %s^k, fitted to the medians: wall k = %.2f (%.2f between the two largest), CPU k = %.2f "
                  "(%.2f); goal: k over every point <= 1.05: %s\n\n",
                  title, k_wall, top_wall, k_cpu, top_cpu, std::max(k_wall, k_cpu) <= 1.05 ? "met" : "**not met**");
    text << line;
  };
  std::vector<double> tri_x(counts.begin(), counts.end());
  text << "Triangles: `soc_sim --app obj_viewer --backend arm --no-frames` on a grid of T triangles (written by "
          "bench_speed), fitted to the view:\n\n";
  report("triangles", tri_x, tri_times, tri_cpu);
  text << "Pixels: `soc_sim --app fullscreen_rect --backend arm --no-frames` at display sizes " << m_opt.sizes.front()
       << " to " << m_opt.sizes.back() << ":\n\n";
  report("pixels", pixels, pix_times, pix_cpu);
  m_scaling_text = text.str();
}

void Bench::print_table() const {
  std::printf(
      "| what | measured (min / median) | against (min / median) | ratio (mins / median of pairs) | CPU ratio "
      "(median of pairs) | goal | met (median of pairs) |\n|---|--:|--:|--:|--:|---|---|\n");
  for (const Row& row : m_rows) print_row(row);
  bool first_limit = true;
  for (const Row& row : m_rows) {
    if (row.goal == "-" || goal_met(row) || !row.limit) continue;
    if (first_limit)
      std::printf("\nWhat keeps each row that is not met from its goal (figures of this run, medians):\n\n");
    first_limit = false;
    std::printf("- %s: %s.\n", row.what.c_str(), row.limit().c_str());
  }
  std::printf(
      "\nPer-frame figures are of frames %u..%u of runs of %u frames, timed within each run; %u paired rounds (%u "
      "for start-up), the order rotating from round to round. Ratios: \"mins\" of the two min columns, \"median of "
      "pairs\" the median of the ratios within each round (for the datapath, RTL / C++: a speed-up).\n",
      m_opt.frames, 2 * m_opt.frames - 1, 2 * m_opt.frames, m_opt.rounds, m_opt.startup_runs);
  if (!m_datapath_table.empty())
    std::printf(
        "\nDatapath units, C++ batch forms against Verilated RTL (bench_rtl --vectors %u --rounds 1, once per "
        "round):\n\n%s",
        m_opt.rtl_vectors, m_datapath_table.c_str());
  if (!m_scaling_text.empty())
    std::printf("\n### Scaling (%u frames timed, %u rounds)\n\n%s", m_opt.scaling_frames, m_opt.scaling_rounds,
                m_scaling_text.c_str());
}

void Bench::run() {
  const WorkFolder folder(m_opt.work_dir, "bench_speed");
  m_work = folder.path();
  m_config = json::parse(child({program("soc_sim").string(), "--print-config"}).output);
  const std::string load_before = load_average();
  const auto start = std::chrono::steady_clock::now();
  const auto part = [this](const char* name) { return m_opt.only.empty() || m_opt.only == name; };
  if (part("startup")) startup_rows();
  if (part("arm")) arm_rows();
  if (part("raster")) raster_row();
  if (part("array")) array_rows();
  if (part("bus")) bus_row();
  if (part("datapath")) datapath_rows();
  if (part("options")) option_rows();
  if (m_opt.scaling && m_opt.only.empty()) scaling();
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  print_table();
  std::printf("\n%s\n", machine_summary(load_before, total_s).c_str());
}

int run_main(int argc, char** argv) {
  Options opt;
  CLI::App cli{"bench_speed: the simulation-speed table (paired rounds, min and median) and the scaling exponents"};
  cli.add_option("--rounds", opt.rounds, "paired rounds of each frame and datapath measurement")
      ->check(CLI::Range(1, 101))
      ->capture_default_str();
  cli.add_option("--frames", opt.frames, "N: runs of 2N frames, frames N..2N-1 timed")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cli.add_option("--startup-runs", opt.startup_runs, "runs of each start-up measurement")
      ->check(CLI::Range(1, 1001))
      ->capture_default_str();
  cli.add_option("--bus-rounds", opt.bus_rounds, "rounds of bench_bus")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_option("--rtl-vectors", opt.rtl_vectors, "vectors per datapath unit (bench_rtl)")
      ->check(CLI::Range(1000, 100000000))
      ->capture_default_str();
  cli.add_flag("!--no-scaling", opt.scaling, "skip the scaling with triangles and pixels");
  cli.add_option("--only", opt.only, "one part of the table alone, no scaling")
      ->check(CLI::IsMember({"startup", "arm", "raster", "array", "bus", "datapath", "options"}));
  cli.add_option("--baseline", opt.baseline,
                 "another build's soc_sim: the options part compares this build with every option off against it")
      ->check(CLI::ExistingFile);
  cli.add_option("--scaling-frames", opt.scaling_frames, "N of the scaling runs")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_option("--scaling-rounds", opt.scaling_rounds, "rounds of the scaling runs")
      ->check(CLI::Range(1, 101))
      ->capture_default_str();
  cli.add_option("--triangles", opt.triangles, "triangle counts of the scaling grids")
      ->check(CLI::Range(2, 120000))
      ->capture_default_str();
  cli.add_option("--sizes", opt.sizes, "display sizes WxH of the pixel scaling")->capture_default_str();
  cli.add_option("--work-dir", opt.work_dir, "folder for the children's output (default: a temporary one, removed)");
  CLI11_PARSE(cli, argc, argv);
  for (const std::string& size : opt.sizes) {
    const size_t x = size.find('x');
    if (x == std::string::npos || x == 0 || x + 1 == size.size() ||
        size.find_first_not_of("0123456789x") != std::string::npos) {
      std::cerr << "bench_speed: --sizes: '" << size << "' is not WIDTHxHEIGHT\n";
      return 2;
    }
  }
  if (opt.triangles.size() < 2 || opt.sizes.size() < 2) {
    std::cerr << "bench_speed: --triangles and --sizes need at least two values each to fit an exponent\n";
    return 2;
  }
  opt.bin = own_directory();
  for (const char* name : {"soc_sim", "bench_arm_native", "bench_arm_mesa", "bench_raster", "bench_bus", "bench_rtl"})
    if (!fs::exists(opt.bin / name)) {
      std::cerr << "bench_speed: " << (opt.bin / name).string() << " not found (build the bench_speed target)\n";
      return 2;
    }
  try {
    Bench(opt).run();
  } catch (const std::exception& e) {
    std::cerr << "bench_speed: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_speed", [&] { return run_main(argc, argv); });
}
