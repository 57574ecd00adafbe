// render_compare: renders a built-in scene with Mesa at the size of one of
// our frames and reports how the two differ.
//
//   render_compare --scene NAME --ours frame.png [--frame N] [--format rgb565|rgba8888]
//                  [--tolerance T] [--min-percent P] [--allowed-coverage C] [--out DIR]
//
// Exit status: 0 the frame passes the rule, 1 it does not, 2 bad usage or
// an error. Our frame comes from a PNG that soc_sim wrote; running soc_sim
// from here is planned as another source of that image (see load_our_frame):
// it must stay a separate process, because Mesa and our driver export the
// same gl* symbols.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "frame_writer.h"
#include "image_compare.h"
#include "mesa_reference.h"
#include "test_scene.h"

namespace {

using namespace tessera;

struct Options {
  std::string scene;
  std::string ours_png;
  int frame = 0;
  std::string format = "rgb565";
  unsigned tolerance = 8;
  double min_percent = 99.0;
  size_t allowed_coverage = 0;
  std::string out_dir;
  std::vector<std::string> scene_args;
};

const scenes::Scene* find_reference_scene(const std::string& name) {
  if (name == reference::test_scene().name) return &reference::test_scene();
#if defined(TESSERA_HAVE_SCENE_REGISTRY)
  return scenes::find_scene(name);
#else
  return nullptr;
#endif
}

std::string known_scene_names() {
  std::string names = reference::test_scene().name;
#if defined(TESSERA_HAVE_SCENE_REGISTRY)
  for (const auto& scene : scenes::all_scenes()) names += std::string(", ") + scene.name;
#endif
  return names;
}

Image load_our_frame(const Options& options) { return read_image(options.ours_png); }

int run(const Options& options) {
  const scenes::Scene* scene = find_reference_scene(options.scene);
  if (!scene) {
    std::fprintf(stderr, "render_compare: unknown scene '%s' (known: %s)\n", options.scene.c_str(),
                 known_scene_names().c_str());
    return 2;
  }
  const Image ours = load_our_frame(options);

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
  const bool passed = result.passes(rule);

  std::printf("scene %s frame %d, %s, tolerance %u, reference %s\n", scene->name, options.frame,
              reference::to_string(compare.format), compare.tolerance, mesa.renderer.c_str());
  std::printf("%s\n", result.summary().c_str());
  if (!options.out_dir.empty()) {
    reference::write_comparison_images(options.out_dir, "", ours, mesa.image, result, compare);
    std::printf("images written to %s\n", options.out_dir.c_str());
  }
  std::printf("%s (rule: coverage mismatches <= %zu, within tolerance >= %.2f%%)\n", passed ? "PASS" : "FAIL",
              rule.allowed_coverage_mismatches, rule.min_percent_within_tolerance);
  return passed ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"Compares one of tessera's frames with Mesa's rendering of the same scene"};
  app.add_option("--scene", options.scene, "built-in scene name")->required();
  app.add_option("--ours", options.ours_png, "our frame (PNG written by soc_sim)")->required()->check(CLI::ExistingFile);
  app.add_option("--frame", options.frame, "frame number the PNG shows (frames 0..N are drawn)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--format", options.format, "output format both images are reduced to")
      ->check(CLI::IsMember({"rgb565", "rgba8888"}));
  app.add_option("--tolerance", options.tolerance, "largest acceptable channel difference (8-bit scale)");
  app.add_option("--min-percent", options.min_percent, "pixels that must be within tolerance, in percent");
  app.add_option("--allowed-coverage", options.allowed_coverage, "coverage mismatches allowed");
  app.add_option("--out", options.out_dir, "write ours.png, reference.png and difference.png here");
  app.add_option("--scene-arg", options.scene_args, "argument passed to the scene's init (repeatable)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_compare: %s\n", e.what());
    return 2;
  }
}
