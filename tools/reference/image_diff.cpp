// image_diff: counts the pixels in which two images of the same size differ,
// as stored (no reduction to a display format, alpha included), and checks
// the count against stated bounds. For tests that compare two renders of our
// own, e.g. one reciprocal method against another, where render_compare's
// Mesa reference and coverage rules do not apply.
//
//   image_diff A.png B.png [--min-differing N] [--max-differing N]
//
// Prints one line (the sizes, the pixels that differ, the largest and the
// mean per-pixel difference) and the verdict. Exit status: 0 the count is
// within the bounds, 1 it is not, 2 bad usage or an image that is missing,
// cannot be decoded or has another size than the other.
#include <CLI/CLI.hpp>

#include <cstddef>
#include <exception>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>

#include "frame_writer.h"
#include "guarded_main.h"
#include "reference/image_compare.h"

namespace {

constexpr int EXIT_OUTSIDE_BOUNDS = 1;
constexpr int EXIT_USAGE = 2;

struct Options {
  std::string first;
  std::string second;
  size_t min_differing = 0;
  size_t max_differing = std::numeric_limits<size_t>::max();
};

int run(const Options& options) {
  const tessera::Image first = tessera::read_image(options.first);
  const tessera::Image second = tessera::read_image(options.second);
  tessera::reference::PixelDifference difference;
  try {
    difference = tessera::reference::diff_pixels(first, second);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(options.first + " vs " + options.second + ": " + e.what());
  }
  std::cout << "image_diff: " << options.first << " vs " << options.second << ": " << difference.summary() << "\n";
  if (difference.differing < options.min_differing) {
    std::cout << "image_diff: FAIL: " << difference.differing << " pixels differ, fewer than the "
              << options.min_differing << " required (--min-differing)\n";
    return EXIT_OUTSIDE_BOUNDS;
  }
  if (difference.differing > options.max_differing) {
    std::cout << "image_diff: FAIL: " << difference.differing << " pixels differ, more than the "
              << options.max_differing << " allowed (--max-differing)\n";
    return EXIT_OUTSIDE_BOUNDS;
  }
  std::cout << "image_diff: pass\n";
  return 0;
}

int run_main(int argc, char** argv) {
  Options options;
  CLI::App app{"Counts the pixels in which two images of the same size differ and checks the count"};
  app.add_option("first", options.first, "first image")->required();
  app.add_option("second", options.second, "second image")->required();
  app.add_option("--min-differing", options.min_differing, "fail if fewer pixels than this differ");
  app.add_option("--max-differing", options.max_differing, "fail if more pixels than this differ");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : EXIT_USAGE;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "image_diff: " << e.what() << "\n";
    return EXIT_USAGE;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::guarded_main(
      "image_diff", [&] { return run_main(argc, argv); }, EXIT_USAGE);
}
