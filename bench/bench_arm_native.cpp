// bench_arm_native: runs a built-in scene through tessera's GL ES driver and
// the arm renderer natively, on a NativeHost (no SystemC, nothing charged),
// and prints the wall time per frame as one line of JSON. bench_arm runs it
// as a child process; it is not meant to be run by hand, but may be:
//
//   bench_arm_native --scene teapot --frames 20 [--width 320 --height 240
//                    --format rgb565 --dma false --mem-mib 16] [-- scene args]
//   bench_arm_native --list
//
// The scene draws 2N frames; the time reported is that of frames N..2N-1
// (from the N-th present to the 2N-th, divided by N), the same frames that
// bench_arm times on soc_sim and Mesa, so start-up and the scene's set-up
// are not counted.

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "guarded_main.h"
#include "host/native_host.h"
#include "native_scene.h"
#include "renderers/backends.h"
#include "scenes/scene.h"

namespace {

using namespace tessera;

int run(int argc, char** argv) {
  std::string scene_name;
  unsigned frames = 10;
  bench::NativeDisplay display;
  std::string format = "rgb565";
  unsigned memory_mib = 16;
  bool list = false;
  std::vector<std::string> scene_args;
  CLI::App cli{"bench_arm_native: a built-in scene on the arm renderer, natively, timed per frame"};
  cli.add_option("--scene", scene_name, "built-in scene");
  cli.add_option("--frames", frames, "N: 2N frames are drawn, frames N..2N-1 are timed")
      ->check(CLI::Range(1, 50000))
      ->capture_default_str();
  cli.add_option("--width", display.width, "display.width")->capture_default_str();
  cli.add_option("--height", display.height, "display.height")->capture_default_str();
  cli.add_option("--format", format, "display.format")
      ->check([](const std::string& name) {
        return pixel_format_from_name(name) ? "" : "expects one of " + pixel_format_names();
      })
      ->capture_default_str();
  cli.add_option("--dma", display.dma, "display.dma")->capture_default_str();
  cli.add_option("--mem-mib", memory_mib, "mem.size_mib")->check(CLI::Range(1, 256))->capture_default_str();
  cli.add_flag("--list", list, "print the built-in scenes' names and exit");
  cli.add_option("scene_args", scene_args, "arguments passed to the scene (after --)");
  CLI11_PARSE(cli, argc, argv);

  if (list) {
    for (const auto& scene : scenes::all_scenes()) std::printf("%s\n", scene.name);
    return 0;
  }
  const scenes::Scene* scene = scenes::find_scene(scene_name);
  if (!scene) {
    std::cerr << "bench_arm_native: no built-in scene '" << scene_name << "' (see --list)\n";
    return 2;
  }
  display.format = *pixel_format_from_name(format);

  bench::NativeHost host(memory_mib << 20, display);
  AppEnvironment env;
  env.host = &host;
  env.frames = 2 * frames;
  env.memory_bytes = memory_mib << 20;
  env.args = scene_args;
  backends::hand_over(backends::backend("arm"), env);
  bench::lay_out_memory(env, display);

  return bench::run_timed_scene("bench_arm_native", env, host, *scene, scene_name, frames);
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_arm_native", [&] { return run(argc, argv); });
}
