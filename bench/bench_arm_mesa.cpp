// bench_arm_mesa: the same built-in scene rendered by Mesa's softpipe through
// the reference harness (mesa_reference.h), timed per frame, printed as one
// line of JSON. A separate program from bench_arm_native because Mesa and
// tessera's driver export the same gl* symbols.
//
//   bench_arm_mesa --scene teapot --frames 20 [--repeat 3] [--width 320 --height 240] [-- scene args]
//
// render_with_mesa draws frames 0..2N-1 in a fresh context, finishing each
// (glFinish) and noting the time; frames N..2N-1 are timed within the call
// (from the end of frame N-1 to the end of frame 2N-1, divided by N), as
// bench_arm times them on soc_sim and natively, the best of R calls after a
// warm-up call (which pays Mesa's one-time start-up). Mesa always renders
// RGBA8 with a 24-bit depth buffer, whatever the display format.
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "guarded_main.h"
#include "reference/mesa_reference.h"
#include "scenes/scene.h"

namespace {

using namespace tessera;

int run(int argc, char** argv) {
  std::string scene_name;
  int frames = 10;
  unsigned repeat = 3;
  reference::ReferenceRequest request;
  CLI::App cli{"bench_arm_mesa: a built-in scene on Mesa softpipe, timed per frame"};
  cli.add_option("--scene", scene_name, "built-in scene")->required();
  cli.add_option("--frames", frames, "N: frames N..2N-1 are timed")->check(CLI::Range(1, 50000))->capture_default_str();
  cli.add_option("--repeat", repeat, "R: timed runs, the best kept")->check(CLI::Range(1, 20))->capture_default_str();
  cli.add_option("--width", request.width, "image width")->capture_default_str();
  cli.add_option("--height", request.height, "image height")->capture_default_str();
  cli.add_option("scene_args", request.args, "arguments passed to the scene (after --)");
  CLI11_PARSE(cli, argc, argv);

  const scenes::Scene* scene = scenes::find_scene(scene_name);
  if (!scene) {
    std::cerr << "bench_arm_mesa: no built-in scene '" << scene_name << "'\n";
    return 2;
  }
  using Clock = std::chrono::steady_clock;
  Clock::time_point frame_n_minus_1, frame_2n_minus_1;
  // And the process's CPU time at the same points: what a loaded machine
  // does not inflate.
  const auto cpu_seconds = [] {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
  };
  double cpu_n_minus_1 = 0, cpu_2n_minus_1 = 0;
  request.after_frame = [&](int frame) {
    if (frame == frames - 1) {
      frame_n_minus_1 = Clock::now();
      cpu_n_minus_1 = cpu_seconds();
    }
    if (frame == 2 * frames - 1) {
      frame_2n_minus_1 = Clock::now();
      cpu_2n_minus_1 = cpu_seconds();
    }
  };
  request.frame = 2 * frames - 1;
  const std::string renderer = reference::render_with_mesa(*scene, request).renderer;  // warm-up
  double best = std::numeric_limits<double>::max();
  double best_cpu = std::numeric_limits<double>::max();
  for (unsigned r = 0; r < repeat; ++r) {
    reference::render_with_mesa(*scene, request);
    best = std::min(best, std::chrono::duration<double>(frame_2n_minus_1 - frame_n_minus_1).count() / frames);
    best_cpu = std::min(best_cpu, (cpu_2n_minus_1 - cpu_n_minus_1) / frames);
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const nlohmann::json result = {{"scene", scene_name},         {"renderer", renderer},
                                 {"timed_frames", frames},      {"wall_per_frame_s", best},
                                 {"cpu_per_frame_s", best_cpu}, {"max_rss_kib", usage.ru_maxrss}};
  std::printf("%s\n", result.dump().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_arm_mesa", [&] { return run(argc, argv); });
}
