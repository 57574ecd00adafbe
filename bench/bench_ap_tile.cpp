// bench_ap_tile: the speed benchmark of the `ap-tile` back end (issue 10,
// item 6: simulating a teapot frame costs no more than 3 times the wall time
// of the same algorithm's functional code run natively). For each scene
// (default: the teapot) it runs, each in its own child process, in rounds
// that alternate them so that a change in the machine's load hits all:
//  - soc_sim --backend ap-tile, writing every frame as PNG (its default) and
//    with --no-frames: simulated time and wall time per frame;
//  - bench_ap_tile_native (the same scene, GL front end and ap-tile host
//    side, the array replaced by tile_reference on CMEM images in memory,
//    on a host that charges nothing): wall time per frame;
// and prints a Markdown table with the ratio soc_sim wall / native wall and
// whether it is within 3. See README.md for the method.
//
//   bench_ap_tile [--frames N] [--repeat R] [--scene NAME ...] [--config FILE ...]
//                 [--idle-cus run|skip] [--obj FILE] [--work-dir DIR] [--soc-sim PATH]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
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

// The bound on soc_sim wall / native wall.
constexpr double TARGET_RATIO = 3.0;

struct Options {
  unsigned frames = 10;
  unsigned repeat = 3;
  std::vector<std::string> scenes = {"teapot"};
  std::vector<std::string> config_files;
  std::string idle_cus = "run";
  std::string obj_file = TESSERA_BENCH_OBJ_FILE;
  std::string work_dir;
  std::string soc_sim;
  std::string native;
};

struct SceneResult {
  std::string scene;
  double simulated_per_frame_s = 0;
  std::vector<double> soc_sim_wall;  // per round: writing every frame as PNG
  std::vector<double> no_png_wall;   // with --no-frames
  std::vector<double> native;
};

class Bench {
 public:
  explicit Bench(Options options) : m_opt(std::move(options)) {}

  void run();

 private:
  std::vector<std::string> with_scene_args(const std::string& scene, std::vector<std::string> command) const;
  std::vector<std::string> soc_sim_command(const std::string& scene, unsigned frames, const fs::path& out,
                                           bool png) const;
  std::vector<std::string> native_command(const std::string& scene) const;
  SceneResult measure(const std::string& scene);
  void print_table(const std::vector<SceneResult>& results) const;

  Options m_opt;
  json m_config;
  fs::path m_work;
  unsigned m_run = 0;
};

std::vector<std::string> Bench::with_scene_args(const std::string& scene, std::vector<std::string> command) const {
  if (scene == "obj_viewer") command.insert(command.end(), {"--", m_opt.obj_file});
  return command;
}

std::vector<std::string> Bench::soc_sim_command(const std::string& scene, unsigned frames, const fs::path& out,
                                                bool png) const {
  std::vector<std::string> command = {m_opt.soc_sim};
  for (const auto& file : m_opt.config_files) command.insert(command.end(), {"--config", file});
  command.insert(command.end(), {"--backend", "ap-tile", "--app", scene, "--frames", std::to_string(frames), "--out",
                                 out.string(), "--quiet", "--force", "--wall-clock"});
  if (!png) command.push_back("--no-frames");
  return with_scene_args(scene, command);
}

std::vector<std::string> Bench::native_command(const std::string& scene) const {
  const auto& array = m_config["array"];
  const auto& display = m_config["display"];
  return with_scene_args(
      scene, {m_opt.native, "--scene", scene, "--frames", std::to_string(m_opt.frames), "--columns",
              std::to_string(array["columns"].get<unsigned>()), "--rows", std::to_string(array["rows"].get<unsigned>()),
              "--cmem-bytes", std::to_string(array["cmem_bytes"].get<unsigned>()), "--format",
              display["format"].get<std::string>(), "--dma", display["dma"].get<bool>() ? "true" : "false", "--mem-mib",
              std::to_string(m_config["mem"]["size_mib"].get<unsigned>()), "--idle-cus", m_opt.idle_cus});
}

SceneResult Bench::measure(const std::string& scene) {
  SceneResult result;
  result.scene = scene;
  const unsigned n = m_opt.frames;
  // R rounds of: soc_sim writing PNG frames, soc_sim with --no-frames, the
  // native run, in an order rotating from round to round; each soc_sim run
  // draws 2N frames with --wall-clock and frames N..2N-1 are timed within
  // it. Times: min and median over the rounds; ratios: the median of the
  // ratios within each round.
  const auto soc_sim = [&](bool png) {
    const fs::path out = m_work / ("soc_sim_" + std::to_string(m_run++));
    run_child(soc_sim_command(scene, 2 * n, out, png), m_work / "soc_sim.stdout");
    const json stats = read_json_file(out / "stats.json");
    if (stats["exit_status"] != 0 || stats["frames_written"] != (png ? 2 * n : 0))
      throw std::runtime_error("soc_sim " + scene + ": wrote " + stats["frames_written"].dump() + " of " +
                               std::to_string(2 * n) + " frames");
    (png ? result.soc_sim_wall : result.no_png_wall)
        .push_back(positive(per_frame_seconds(stats, n, "wall_ns"), "soc_sim wall per frame"));
    result.simulated_per_frame_s = per_frame_seconds(stats, n, "time_ns");
    fs::remove_all(out);
  };
  const auto native = [&] {
    const ChildResult child = run_child(native_command(scene), m_work / "native.stdout");
    result.native.push_back(
        positive(json::parse(child.output)["wall_per_frame_s"].get<double>(), "native wall per frame"));
  };
  const std::vector<std::function<void()>> steps = {[&] { soc_sim(true); }, [&] { soc_sim(false); }, native};
  for (unsigned r = 0; r < m_opt.repeat; ++r)
    for (size_t i = 0; i < steps.size(); ++i) steps[(i + r) % steps.size()]();
  return result;
}

void Bench::print_table(const std::vector<SceneResult>& results) const {
  auto within = [](double ratio) { return ratio <= TARGET_RATIO ? "yes" : "**no**"; };
  std::printf(
      "| scene | simulated / frame | soc_sim wall / frame | (--no-frames) | native wall / frame "
      "| soc_sim / native | (--no-frames) | within 3x (PNG, --no-frames) |\n");
  std::printf("|---|--:|--:|--:|--:|--:|--:|---|\n");
  for (const auto& r : results) {
    const double ratio = paired_median(r.soc_sim_wall, r.native);
    const double no_png_ratio = paired_median(r.no_png_wall, r.native);
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %s, %s |\n", r.scene.c_str(),
                format_ms(r.simulated_per_frame_s).c_str(), format_min_median_ms(r.soc_sim_wall).c_str(),
                format_min_median_ms(r.no_png_wall).c_str(), format_min_median_ms(r.native).c_str(),
                format_ratio(ratio).c_str(), format_ratio(no_png_ratio).c_str(), within(ratio), within(no_png_ratio));
  }
  for (const auto& r : results)
    if (r.scene == "teapot") {
      const double ratio = paired_median(r.soc_sim_wall, r.native);
      const double no_png_ratio = paired_median(r.no_png_wall, r.native);
      std::printf(
          "\nteapot: soc_sim wall / native wall = %s writing PNG frames, %s with --no-frames (target: at "
          "most 3): %s\n",
          format_ratio(ratio).c_str(), format_ratio(no_png_ratio).c_str(),
          std::max(ratio, no_png_ratio) <= TARGET_RATIO ? "met" : "not met");
    }
  const auto& display = m_config["display"];
  const auto& array = m_config["array"];
  std::printf(
      "\nArray %ux%u CUs, display %ux%u %s, %s mode; native: every CU runs %s; per-frame values are frames %u..%u of "
      "runs of 2N=%u frames, timed within each run (soc_sim --wall-clock, the native run's presents); wall times min / "
      "median of %u rounds of soc_sim (PNG), soc_sim (--no-frames) and native in rotating order, ratios the median "
      "of the ratios within each round.\n",
      array["columns"].get<unsigned>(), array["rows"].get<unsigned>(), display["width"].get<unsigned>(),
      display["height"].get<unsigned>(), display["format"].get<std::string>().c_str(),
      display["dma"].get<bool>() ? "DMA" : "port",
      m_opt.idle_cus == "run" ? "every stage of every pass, as on the array"
                              : "the stages only in the passes it has a triangle in (--idle-cus skip)",
      m_opt.frames, 2 * m_opt.frames - 1, 2 * m_opt.frames, m_opt.repeat);
}

void Bench::run() {
  const WorkFolder folder(m_opt.work_dir, "bench_ap_tile");
  m_work = folder.path();

  std::vector<std::string> print_config = {m_opt.soc_sim};
  for (const auto& file : m_opt.config_files) print_config.insert(print_config.end(), {"--config", file});
  print_config.insert(print_config.end(), {"--backend", "ap-tile", "--print-config"});
  m_config = json::parse(run_child(print_config, m_work / "config.json").output);

  const std::string load_before = load_average();
  const auto start = std::chrono::steady_clock::now();
  std::vector<SceneResult> results;
  for (const auto& scene : m_opt.scenes) {
    std::fprintf(stderr, "bench_ap_tile: %s ...\n", scene.c_str());
    results.push_back(measure(scene));
  }
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  print_table(results);
  std::printf("%s\n", machine_summary(load_before, total_s).c_str());
}

}  // namespace

static int run_main(int argc, char** argv) {
  Options opt;
  CLI::App cli{"bench_ap_tile: speed of the simulated ap-tile back end against its functional code run natively"};
  cli.add_option("--frames", opt.frames, "N: runs of 2N frames, frames N..2N-1 timed")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cli.add_option("--repeat", opt.repeat, "rounds of the three runs; min and median are printed")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  cli.add_option("--scene", opt.scenes, "scene(s) to measure")->capture_default_str();
  cli.add_option("--config", opt.config_files, "soc_sim configuration file(s)")->check(CLI::ExistingFile);
  cli.add_option("--idle-cus", opt.idle_cus,
                 "the native run: run (every CU runs every stage, as on the array) or skip (only CUs with work)")
      ->check(CLI::IsMember({"run", "skip"}))
      ->capture_default_str();
  cli.add_option("--obj", opt.obj_file, "OBJ file for obj_viewer")->check(CLI::ExistingFile)->capture_default_str();
  cli.add_option("--work-dir", opt.work_dir, "folder for soc_sim's output (default: a temporary one, removed)");
  cli.add_option("--soc-sim", opt.soc_sim, "soc_sim to run (default: the one in this build tree)");
  CLI11_PARSE(cli, argc, argv);

  const fs::path here = own_directory();
  if (opt.soc_sim.empty()) opt.soc_sim = (here / "soc_sim").string();
  opt.native = (here / "bench_ap_tile_native").string();
  for (const auto& program : {opt.soc_sim, opt.native})
    if (!fs::exists(program)) {
      std::cerr << "bench_ap_tile: " << program << " not found (build the bench_ap_tile target)\n";
      return 2;
    }
  try {
    Bench(opt).run();
  } catch (const std::exception& e) {
    std::cerr << "bench_ap_tile: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_ap_tile", [&] { return run_main(argc, argv); });
}
