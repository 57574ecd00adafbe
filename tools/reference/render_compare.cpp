// render_compare: renders a built-in scene both ways, on the simulated SoC and
// with Mesa, and reports how the two frames differ.
//
//   render_compare --scene NAME [--soc-sim PATH] [--frame N] [--format rgb565|rgba8888]
//                  [--backend arm] [--tolerance T] [--min-percent P] [--allowed-coverage C]
//                  [--allow-coverage-off-edges] [--set KEY=VALUE ...] [--out DIR] [-- scene args]
//   render_compare --scene NAME --ours frame.png [...]
//
// Without --ours, soc_sim runs as a child process (`--app NAME --frames N+1
// --out DIR/ours --set display.format=F --backend B --force [--set KEY=VALUE ...] -- scene args`) and frame
// N is taken from what it wrote. It must stay a separate process: Mesa and
// our driver export the same gl* symbols. The soc_sim next to this program in
// the build tree is used unless --soc-sim names another.
//
// Exit status: 0 the frame passes the rule, 1 it does not, 2 bad usage or
// an error (soc_sim failed, a frame is missing).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "frame_writer.h"
#include "guarded_main.h"
#include "process/child_process.h"
#include "process/scratch_folder.h"
#include "reference/image_compare.h"
#include "reference/mesa_reference.h"

namespace {

namespace fs = std::filesystem;
using namespace tessera;

struct Options {
  std::string scene;
  std::string ours_png;
  std::string soc_sim;
  int frame = 0;
  std::string format = "rgb565";
  std::string backend = "arm";
  unsigned tolerance = 9;
  double min_percent = 99.0;
  size_t allowed_coverage = 0;
  bool allow_coverage_off_edges = false;
  std::string out_dir;
  std::vector<std::string> settings;           // --set key=value, passed on to soc_sim
  std::string config;                          // --config FILE, passed on to soc_sim (before the --set)
  std::vector<std::string> scene_args;         // after --
  std::vector<std::string> scene_arg_options;  // --scene-arg, the older spelling; these come first
};

std::string known_scene_names() {
  std::string names;
  for (const auto& scene : scenes::all_scenes()) names += (names.empty() ? "" : ", ") + std::string(scene.name);
  return names;
}

// The build tree and an installation both put render_compare and soc_sim
// side by side in bin/.
fs::path default_soc_sim() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) throw std::runtime_error("cannot find this program's path (/proc/self/exe): " + error.message());
  fs::path candidate = self.parent_path() / "soc_sim";
  if (fs::is_regular_file(candidate)) return candidate;
  throw std::runtime_error("no soc_sim next to " + self.string() + "; name one with --soc-sim");
}

std::string last_lines(const fs::path& file, size_t count) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::string text;
  for (size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i)
    text += "  " + lines[i] + "\n";
  return text;
}

// Runs soc_sim with its output in `log`; returns its exit status, or throws
// if it cannot be started or dies from a signal.
int run_process(const std::vector<std::string>& command, const fs::path& log) {
  test::ChildCommand child;
  child.argv = command;
  child.stdout_file = log;
  child.stderr_to = test::ChildCommand::Stderr::with_stdout;
  const test::ChildResult result = test::run_child(child);
  if (!result.started) throw std::runtime_error(result.start_error);
  if (result.signal != 0)
    throw std::runtime_error("soc_sim died from signal " + std::to_string(result.signal) +
                             "; the end of its output:\n" + last_lines(log, 20));
  return result.status;
}

std::string frame_file_name(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", frame);
  return name;
}

// Draws frames 0..N on the simulated SoC into `frames_dir` and reads frame N.
Image render_on_soc(const Options& options, const fs::path& frames_dir) {
  const fs::path soc_sim = options.soc_sim.empty() ? default_soc_sim() : fs::path(options.soc_sim);
  fs::create_directories(frames_dir);
  // A frame left by an earlier run must not stand in for one this run failed to write.
  const fs::path frame_png = frames_dir / frame_file_name(options.frame);
  fs::remove(frame_png);
  std::vector<std::string> command = {soc_sim.string(), "--app", options.scene, "--frames",
                                      std::to_string(options.frame + 1), "--out", frames_dir.string(), "--set",
                                      "display.format=" + options.format, "--backend", options.backend,
                                      // DIR/ours is render_compare's: a rerun replaces the frames it holds.
                                      "--force"};
  if (!options.config.empty()) command.insert(command.end(), {"--config", options.config});
  for (const std::string& setting : options.settings) command.insert(command.end(), {"--set", setting});
  if (!options.scene_args.empty()) {
    command.push_back("--");
    command.insert(command.end(), options.scene_args.begin(), options.scene_args.end());
  }
  std::string command_line;
  for (const std::string& word : command) command_line += (command_line.empty() ? "" : " ") + word;
  std::printf("ours: %s\n", command_line.c_str());
  std::fflush(stdout);

  const fs::path log = frames_dir / "soc_sim.log";
  const int status = run_process(command, log);
  if (status != 0)
    throw std::runtime_error("soc_sim exited with status " + std::to_string(status) + "; the end of its output:\n" +
                             last_lines(log, 20));
  if (!fs::is_regular_file(frame_png))
    throw std::runtime_error("soc_sim wrote no " + frame_png.string() + "; the end of its output:\n" +
                             last_lines(log, 20));
  return read_image(frame_png.string());
}

// With --out, soc_sim's frames go to DIR/ours and stay there; without it, to
// a temporary folder that is removed afterwards.
class FramesFolder {
 public:
  explicit FramesFolder(const std::string& out_dir) {
    if (out_dir.empty())
      m_temporary = std::make_unique<test::ScratchFolder>("render_compare");
    else
      m_path = fs::path(out_dir) / "ours";
  }
  const fs::path& path() const { return m_temporary ? m_temporary->path() : m_path; }

 private:
  fs::path m_path;
  std::unique_ptr<test::ScratchFolder> m_temporary;
};

int run(const Options& options) {
  const scenes::Scene* scene = scenes::find_scene(options.scene);
  if (!scene) {
    std::fprintf(stderr, "render_compare: unknown scene '%s' (known: %s)\n", options.scene.c_str(),
                 known_scene_names().c_str());
    return 2;
  }
  Image ours;
  if (!options.ours_png.empty()) {
    ours = read_image(options.ours_png);
  } else {
    const FramesFolder frames(options.out_dir);
    ours = render_on_soc(options, frames.path());
  }

  reference::ReferenceRequest request;
  request.width = ours.width;
  request.height = ours.height;
  request.frame = options.frame;
  request.args = options.scene_args;
  const reference::ReferenceFrame mesa = reference::render_with_mesa(*scene, request);

  reference::CompareOptions compare;
  compare.format = reference::parse_output_format(options.format);
  compare.tolerance = options.tolerance;
  compare.clear_colour = {mesa.clear_colour[0], mesa.clear_colour[1], mesa.clear_colour[2], mesa.clear_colour[3]};
  const reference::CompareResult result = reference::compare_images(ours, mesa.image, compare);

  reference::PassRule rule;
  rule.allowed_coverage_mismatches = options.allowed_coverage;
  rule.min_percent_within_tolerance = options.min_percent;
  rule.coverage_only_on_edges = !options.allow_coverage_off_edges;
  const bool passed = result.passes(rule);

  std::printf("scene %s frame %d, %s, tolerance %u, reference %s\n", scene->name, options.frame,
              pixel_format_name(compare.format), compare.tolerance, mesa.renderer.c_str());
  std::printf("%s\n", result.summary().c_str());
  if (!options.out_dir.empty()) {
    reference::write_comparison_images(options.out_dir, "", ours, mesa.image, result, compare);
    const std::string dir = fs::absolute(options.out_dir).lexically_normal().string();
    std::printf("images (ours, reference, difference): %s/{ours,reference,difference}.png\n", dir.c_str());
  }
  std::printf("%s (rule: coverage mismatches <= %zu%s, within tolerance %u >= %.2f%%)\n", passed ? "PASS" : "FAIL",
              rule.allowed_coverage_mismatches, rule.coverage_only_on_edges ? " and all on edges" : "",
              compare.tolerance, rule.min_percent_within_tolerance);
  return passed ? 0 : 1;
}

}  // namespace

static int run_main(int argc, char** argv) {
  Options options;
  CLI::App app{"Renders a built-in scene on the simulated SoC and with Mesa, and compares the two frames"};
  app.add_option("--scene", options.scene, "built-in scene name")->required();
  app.add_option("--ours", options.ours_png, "our frame, a PNG written by soc_sim (instead of running soc_sim)")
      ->check(CLI::ExistingFile);
  app.add_option("--soc-sim", options.soc_sim, "soc_sim to run (default: the one in this build tree)")
      ->check(CLI::ExistingFile);
  app.add_option("--frame", options.frame, "frame to compare (frames 0..N are drawn)")->check(CLI::NonNegativeNumber);
  app.add_option("--format", options.format,
                 "display format: soc_sim's display.format, and what both images are reduced to")
      ->check(CLI::IsMember({"rgb565", "rgba8888"}))
      ->capture_default_str();
  app.add_option("--backend", options.backend, "soc_sim's renderer back end")->capture_default_str();
  app.add_option("--tolerance", options.tolerance, "largest acceptable channel difference (8-bit scale)")
      ->capture_default_str();
  app.add_option("--min-percent", options.min_percent, "pixels that must be within tolerance, in percent")
      ->capture_default_str();
  app.add_option("--allowed-coverage", options.allowed_coverage, "coverage mismatches allowed")->capture_default_str();
  app.add_flag("--allow-coverage-off-edges", options.allow_coverage_off_edges,
               "accept coverage mismatches away from the reference's edges (holes, stray pixels)");
  app.add_option("--out", options.out_dir,
                 "write ours.png, reference.png and difference.png (and soc_sim's frames in ours/) here");
  app.add_option("--set", options.settings,
                 "soc_sim parameter key=value (repeatable), e.g. display.width=512; Mesa draws the frame's size");
  app.add_option("--config", options.config, "a configuration file for soc_sim (a preset), applied before --set");
  app.add_option("--scene-arg", options.scene_arg_options, "argument passed to the scene's init (repeatable)");
  app.add_option("scene_args", options.scene_args, "arguments passed to the scene, after --");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  options.scene_args.insert(options.scene_args.begin(), options.scene_arg_options.begin(),
                            options.scene_arg_options.end());
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_compare: %s\n", e.what());
    return 2;
  }
}

int main(int argc, char** argv) {
  return tessera::guarded_main("render_compare", [&] { return run_main(argc, argv); });
}
