// bench_arm: the benchmark of the `arm` back end. For every built-in scene it
// measures, each in its own child process:
//  - soc_sim (the scene on the simulated SoC): simulated time and wall time
//    per frame, and the process's peak memory;
//  - bench_arm_native (the same scene, GL front end and arm renderer run
//    natively on a host that charges nothing): wall time per frame;
//  - bench_arm_mesa (the same scene on Mesa softpipe): wall time per frame;
// and prints one Markdown table with the ratios, then the peak memory of
// soc_sim's default demo. See README.md for the method.
//
//   bench_arm [--frames N] [--repeat R] [--scene NAME ...] [--config FILE ...]
//             [--obj FILE] [--work-dir DIR] [--soc-sim PATH]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
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
  unsigned frames = 100;
  unsigned repeat = 3;
  std::vector<std::string> scenes;
  std::vector<std::string> config_files;
  std::string obj_file = TESSERA_BENCH_OBJ_FILE;
  std::string work_dir;
  std::string soc_sim;
  std::string native;
  std::string mesa;
};

std::string format_mib(long kib) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f MiB", kib / 1024.0);
  return text;
}

// Every round's figures of one scene, in seconds per frame (frames N..2N-1).
struct SceneResult {
  std::string scene;
  double simulated_per_frame_s = 0;
  std::vector<double> soc_sim_wall;  // writing every frame as PNG, as soc_sim does by default
  std::vector<double> no_png_wall;   // with --no-frames
  std::vector<double> soc_sim_cpu;   // CPU time of the process (every thread) per frame, writing PNG
  std::vector<double> no_png_cpu;    // the same with --no-frames
  std::vector<double> native;
  std::vector<double> mesa;
  long soc_sim_max_rss_kib = 0;
};

class Bench {
 public:
  explicit Bench(Options options) : m_opt(std::move(options)) {}

  void run();

 private:
  std::vector<std::string> soc_sim_command(const std::string& scene, unsigned frames, const fs::path& out,
                                           bool png) const;
  std::vector<std::string> scene_args(const std::string& scene) const;
  SceneResult measure(const std::string& scene);
  void print_table(const std::vector<SceneResult>& results, long default_rss_kib) const;

  Options m_opt;
  json m_config;
  fs::path m_work;
  unsigned m_run = 0;
};

std::vector<std::string> Bench::scene_args(const std::string& scene) const {
  if (scene == "obj_viewer") return {m_opt.obj_file};
  return {};
}

std::vector<std::string> Bench::soc_sim_command(const std::string& scene, unsigned frames, const fs::path& out,
                                                bool png) const {
  std::vector<std::string> command = {m_opt.soc_sim};
  for (const auto& file : m_opt.config_files) command.insert(command.end(), {"--config", file});
  command.insert(command.end(), {"--app", scene, "--frames", std::to_string(frames), "--out", out.string(), "--quiet",
                                 "--force", "--wall-clock"});
  if (!png) command.push_back("--no-frames");
  const auto args = scene_args(scene);
  if (!args.empty()) {
    command.push_back("--");
    command.insert(command.end(), args.begin(), args.end());
  }
  return command;
}

SceneResult Bench::measure(const std::string& scene) {
  SceneResult result;
  result.scene = scene;
  const unsigned n = m_opt.frames;
  const auto& display = m_config["display"];
  const auto args = scene_args(scene);
  auto with_args = [&](std::vector<std::string> command) {
    if (!args.empty()) {
      command.push_back("--");
      command.insert(command.end(), args.begin(), args.end());
    }
    return command;
  };
  const std::string width = std::to_string(display["width"].get<unsigned>());
  const std::string height = std::to_string(display["height"].get<unsigned>());

  // soc_sim: runs of 2N frames with --wall-clock, writing PNG frames and
  // not (--no-frames); frames N..2N-1 timed within each run. Each round
  // runs soc_sim both ways, the native run and the Mesa run once, in an
  // order rotating from round to round, so that a change in the machine's
  // load hits all four alike and the ratios can be taken within a round.
  const auto soc_sim = [&](bool png) {
    const fs::path out = m_work / ("soc_sim_" + std::to_string(m_run++));
    const ChildResult child = run_child(soc_sim_command(scene, 2 * n, out, png), m_work / "soc_sim.stdout");
    const json stats = read_json_file(out / "stats.json");
    if (stats["exit_status"] != 0 || stats["frames_written"] != (png ? 2 * n : 0))
      throw std::runtime_error("soc_sim " + scene + ": wrote " + stats["frames_written"].dump() + " of " +
                               std::to_string(2 * n) + " frames");
    (png ? result.soc_sim_wall : result.no_png_wall)
        .push_back(positive(per_frame_seconds(stats, n, "wall_ns"), "soc_sim wall"));
    (png ? result.soc_sim_cpu : result.no_png_cpu)
        .push_back(positive(per_frame_seconds(stats, n, "cpu_ns"), "soc_sim CPU"));
    result.simulated_per_frame_s = per_frame_seconds(stats, n, "time_ns");
    result.soc_sim_max_rss_kib = std::max(result.soc_sim_max_rss_kib, child.max_rss_kib);
    fs::remove_all(out);
  };
  const auto native = [&] {
    const ChildResult child =
        run_child(with_args({m_opt.native, "--scene", scene, "--frames", std::to_string(n), "--width", width,
                             "--height", height, "--format", display["format"].get<std::string>(), "--dma",
                             display["dma"].get<bool>() ? "true" : "false", "--mem-mib",
                             std::to_string(m_config["mem"]["size_mib"].get<unsigned>())}),
                  m_work / "native.stdout");
    result.native.push_back(positive(json::parse(child.output)["wall_per_frame_s"].get<double>(), "native"));
  };
  const auto mesa = [&] {
    const ChildResult child = run_child(with_args({m_opt.mesa, "--scene", scene, "--frames", std::to_string(n),
                                                   "--repeat", "1", "--width", width, "--height", height}),
                                        m_work / "mesa.stdout");
    result.mesa.push_back(positive(json::parse(child.output)["wall_per_frame_s"].get<double>(), "Mesa"));
  };
  const std::vector<std::function<void()>> steps = {[&] { soc_sim(true); }, [&] { soc_sim(false); }, native, mesa};
  for (unsigned r = 0; r < m_opt.repeat; ++r)
    for (size_t i = 0; i < steps.size(); ++i) steps[(i + r) % steps.size()]();
  return result;
}

void Bench::print_table(const std::vector<SceneResult>& results, long default_rss_kib) const {
  const auto& display = m_config["display"];
  std::printf(
      "| scene | simulated / frame | soc_sim wall / frame | (--no-frames) | soc_sim CPU / frame | (--no-frames) "
      "| simulated : wall | native wall / frame | Mesa softpipe / frame | soc_sim / native | (--no-frames) "
      "| soc_sim (--no-frames) / Mesa | native / Mesa | soc_sim max RSS |\n");
  std::printf("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  for (const auto& r : results)
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r.scene.c_str(),
                format_ms(r.simulated_per_frame_s).c_str(), format_min_median_ms(r.soc_sim_wall).c_str(),
                format_min_median_ms(r.no_png_wall).c_str(), format_ms(min_median(r.soc_sim_cpu).median).c_str(),
                format_ms(min_median(r.no_png_cpu).median).c_str(),
                format_ratio(r.simulated_per_frame_s / min_median(r.no_png_wall).median).c_str(),
                format_min_median_ms(r.native).c_str(), format_min_median_ms(r.mesa).c_str(),
                format_ratio(paired_median(r.soc_sim_wall, r.native)).c_str(),
                format_ratio(paired_median(r.no_png_wall, r.native)).c_str(),
                format_ratio(paired_median(r.no_png_wall, r.mesa)).c_str(),
                format_ratio(paired_median(r.native, r.mesa)).c_str(), format_mib(r.soc_sim_max_rss_kib).c_str());
  std::printf(
      "\nsoc_sim default demo (`soc_sim` with no options: teapot, %u frames): max RSS %s "
      "(target < 200 MB)\n",
      m_config["sim"]["frames"].get<unsigned>(), format_mib(default_rss_kib).c_str());
  for (const auto& r : results)
    if (r.scene == "teapot")
      std::printf("teapot: soc_sim wall / native wall = %s writing PNG frames, %s with --no-frames (target <= 3)\n",
                  format_ratio(paired_median(r.soc_sim_wall, r.native)).c_str(),
                  format_ratio(paired_median(r.no_png_wall, r.native)).c_str());
  std::printf(
      "\nDisplay %ux%u %s, %s mode; per-frame values are frames %u..%u of runs of 2N=%u frames, timed within each "
      "run (soc_sim --wall-clock, the native run's presents, Mesa after each frame's glFinish). %u rounds, each "
      "running soc_sim with and without PNG, the native run and Mesa once, in rotating order: times are min / "
      "median over the rounds, CPU times and simulated : wall medians, ratios the median of the ratios within each "
      "round. CPU / frame is the soc_sim process's (every thread): the PNG writer's thread shows there, while on a "
      "machine with a spare core it costs little wall time.\n",
      display["width"].get<unsigned>(), display["height"].get<unsigned>(), display["format"].get<std::string>().c_str(),
      display["dma"].get<bool>() ? "DMA" : "port", m_opt.frames, 2 * m_opt.frames - 1, 2 * m_opt.frames, m_opt.repeat);
}

void Bench::run() {
  const WorkFolder folder(m_opt.work_dir, "bench_arm");
  m_work = folder.path();

  std::vector<std::string> print_config = {m_opt.soc_sim};
  for (const auto& file : m_opt.config_files) print_config.insert(print_config.end(), {"--config", file});
  print_config.push_back("--print-config");
  m_config = json::parse(run_child(print_config, m_work / "config.json").output);

  std::vector<std::string> scenes = m_opt.scenes;
  if (scenes.empty()) {
    std::istringstream names(run_child({m_opt.native, "--list"}, m_work / "scenes.txt").output);
    for (std::string name; std::getline(names, name);)
      if (!name.empty()) scenes.push_back(name);
  }

  const std::string load_before = load_average();
  const auto start = std::chrono::steady_clock::now();
  std::vector<SceneResult> results;
  for (const auto& scene : scenes) {
    std::fprintf(stderr, "bench_arm: %s ...\n", scene.c_str());
    results.push_back(measure(scene));
  }
  std::vector<std::string> default_demo = {m_opt.soc_sim};
  for (const auto& file : m_opt.config_files) default_demo.insert(default_demo.end(), {"--config", file});
  default_demo.insert(default_demo.end(), {"--out", (m_work / "default_demo").string(), "--quiet", "--force"});
  const long default_rss_kib = run_child(default_demo, m_work / "default_demo.stdout").max_rss_kib;
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  print_table(results, default_rss_kib);
  std::printf("%s\n", machine_summary(load_before, total_s).c_str());
}

}  // namespace

static int run_main(int argc, char** argv) {
  Options opt;
  CLI::App cli{"bench_arm: benchmark of the arm back end (soc_sim, native core, Mesa softpipe)"};
  cli.add_option("--frames", opt.frames, "N: runs of 2N frames, frames N..2N-1 timed")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cli.add_option("--repeat", opt.repeat, "rounds: each runs every measurement once; min and median are printed")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  cli.add_option("--scene", opt.scenes, "scene(s) to measure (default: all built-in scenes)");
  cli.add_option("--config", opt.config_files, "soc_sim configuration file(s)")->check(CLI::ExistingFile);
  cli.add_option("--obj", opt.obj_file, "OBJ file for obj_viewer")->check(CLI::ExistingFile)->capture_default_str();
  cli.add_option("--work-dir", opt.work_dir, "folder for soc_sim's output (default: a temporary one, removed)");
  cli.add_option("--soc-sim", opt.soc_sim, "soc_sim to run (default: the one in this build tree)");
  CLI11_PARSE(cli, argc, argv);

  const fs::path here = own_directory();
  if (opt.soc_sim.empty()) opt.soc_sim = (here / "soc_sim").string();
  opt.native = (here / "bench_arm_native").string();
  opt.mesa = (here / "bench_arm_mesa").string();
  for (const auto& program : {opt.soc_sim, opt.native, opt.mesa})
    if (!fs::exists(program)) {
      std::cerr << "bench_arm: " << program << " not found (build the bench_arm target)\n";
      return 2;
    }
  try {
    Bench(opt).run();
  } catch (const std::exception& e) {
    std::cerr << "bench_arm: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_arm", [&] { return run_main(argc, argv); });
}
