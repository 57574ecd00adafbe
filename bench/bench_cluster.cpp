// bench_cluster: the cluster platform's simulation speed. The paper's
// standard scene (100,000 random triangles of 10 pixels at 512 x 512) on
// p native nodes, one soc_sim --platform cluster run per p as a child, in
// rounds: for each p, the wall time and CPU time of the run, its peak
// memory, the simulated frame time, and the wall time per simulated node
// frame. The scaling in nodes is the wall time's ratio to p = the smallest.
//
//   bench_cluster [--nodes 1,8,32,128] [--triangles N] [--frames F] [--rounds R] [--work-dir DIR]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "guarded_main.h"

namespace {

namespace fs = std::filesystem;
using namespace tessera::bench;

struct Options {
  std::vector<unsigned> nodes = {8, 32, 128};
  unsigned triangles = 100000;
  unsigned frames = 2;
  unsigned rounds = 2;
  std::string depth = "auto";
  std::string work_dir;
};

struct Measurement {
  std::vector<double> wall, cpu;
  long max_rss_kib = 0;
  double frame_s = 0;  // the last frame's simulated time
};

Measurement measure(const Options& options, unsigned nodes, const fs::path& work) {
  Measurement m;
  for (unsigned round = 0; round < options.rounds; ++round) {
    const fs::path out = work / ("p" + std::to_string(nodes) + "_r" + std::to_string(round));
    fs::remove_all(out);
    const std::vector<std::string> argv = {(own_directory() / "soc_sim").string(),
                                           "--platform",
                                           "cluster",
                                           "--quiet",
                                           "--no-frames",
                                           "--frames",
                                           std::to_string(options.frames),
                                           "--out",
                                           out.string(),
                                           "--set",
                                           "cluster.nodes=" + std::to_string(nodes),
                                           "--set",
                                           "cluster.triangles=" + std::to_string(options.triangles),
                                           "--set",
                                           "cluster.buffer_depth=" + options.depth};
    fs::create_directories(work);
    const ChildResult result = run_child(argv, work / "soc_sim.stdout");
    m.wall.push_back(positive(result.wall_s, "wall time"));
    m.cpu.push_back(result.cpu_s);
    m.max_rss_kib = std::max(m.max_rss_kib, result.max_rss_kib);
    const nlohmann::json stats = read_json_file(out / "stats.json");
    const nlohmann::json& frames = stats.at("stats").at("frames");
    const double last = frames.back().at("time_ns").get<double>();
    const double before = frames.size() > 1 ? frames[frames.size() - 2].at("time_ns").get<double>() : 0.0;
    m.frame_s = (last - before) * 1e-9;
  }
  return m;
}

int run(int argc, char** argv) {
  Options options;
  CLI::App cli{"bench_cluster: the cluster platform's simulation speed against its node count"};
  cli.add_option("--nodes", options.nodes, "node counts")->delimiter(',');
  cli.add_option("--triangles", options.triangles, "triangles of the random scene");
  cli.add_option("--frames", options.frames, "frames per run");
  cli.add_option("--rounds", options.rounds, "runs per node count");
  cli.add_option("--depth", options.depth, "cluster.buffer_depth");
  cli.add_option("--work-dir", options.work_dir, "folder for the runs' outputs (default: a temporary one, removed)");
  CLI11_PARSE(cli, argc, argv);
  const WorkFolder folder(options.work_dir, "bench_cluster");
  const fs::path& work = folder.path();
  const std::string load_before = load_average();
  const auto start = std::chrono::steady_clock::now();
  std::printf(
      "| nodes | wall s (min / median) | CPU s (median) | peak MiB | simulated frame | wall per node-frame |\n");
  std::printf("| ---: | ---: | ---: | ---: | ---: | ---: |\n");
  double first_wall = 0;
  for (const unsigned nodes : options.nodes) {
    const Measurement m = measure(options, nodes, work);
    const MinMedian wall = min_median(m.wall);
    const MinMedian cpu = min_median(m.cpu);
    if (first_wall == 0) first_wall = wall.median;
    std::printf("| %u | %.2f / %.2f | %.2f | %.0f | %s | %s |\n", nodes, wall.min, wall.median, cpu.median,
                static_cast<double>(m.max_rss_kib) / 1024.0, format_ms(m.frame_s).c_str(),
                format_ms(wall.median / (nodes * options.frames)).c_str());
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("\n%u triangles at 512 x 512, %u frames a run, cluster.buffer_depth=%s, host.model=native.\n",
              options.triangles, options.frames, options.depth.c_str());
  std::printf("%s\n", machine_summary(load_before, total).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_cluster", [&] { return run(argc, argv); });
}
