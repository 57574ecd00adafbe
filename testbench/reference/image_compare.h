// Compares a frame tessera displayed with the reference Mesa rendered.
//
// Both images are first reduced to the display's output format, so that
// precision our display does not have cannot count against us. Each pixel is
// then judged twice:
//  - coverage: is it background (equal to the clear colour after reduction)
//    in one image and drawn in the other? Such a pixel is a rasterization
//    difference (fill rule, clipping, culling), not a colour error, and is
//    counted on its own. A drawn pixel that happens to have exactly the
//    clear colour counts as background: scenes should avoid drawing in it.
//    Where the drawn colour is within the tolerance of the background, the
//    two cannot be told apart, and the pixel is judged by colour instead
//    (counted in coverage_within_tolerance): a dark face on a dark
//    background must not turn a rounding difference into a coverage one.
//    A coverage mismatch is "on an edge" when the reference has a pixel of
//    the coverage ours has among its 8 neighbours, i.e. an edge of the
//    reference moved by at most one pixel; anything else (a hole, a stray
//    pixel, a missing triangle) is "off the edges".
//  - colour: the largest absolute difference of its channels, on the 8-bit
//    scale after reduction.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/pixel_format.h"
#include "frame_writer.h"

namespace tessera::reference {

// The display format the images are compared in: the display's pixel
// formats (common/pixel_format.h). RGB565 ignores alpha; RGBA8888 compares
// alpha only if CompareOptions::compare_alpha.
// "rgb565" / "rgba8888"; throws std::invalid_argument otherwise.
PixelFormat parse_output_format(const std::string& name);

struct Rgba8 {
  uint8_t r = 0, g = 0, b = 0, a = 255;
};

// What our display would show for `colour`: the format's one rounding rule
// (pixel_format.h: round to nearest, as Mesa reduces colours, then bit
// replication back to 8 bits, so 0 -> 0 and 31 -> 255).
Rgba8 reduce(Rgba8 colour, PixelFormat format);

struct CompareOptions {
  PixelFormat format = PixelFormat::rgb565;
  Rgba8 clear_colour;          // the scene's background
  unsigned tolerance = 8;      // largest acceptable channel difference
  bool compare_alpha = false;  // rgba8888 only: our frames carry no alpha
};

// The pass rule is separate from the measurement so that a test can state
// documented exceptions (e.g. a known fill-rule difference on shared edges).
struct PassRule {
  size_t allowed_coverage_mismatches = 0;
  double min_percent_within_tolerance = 99.0;
  bool coverage_only_on_edges = false;  // no coverage mismatch may lie off the reference's edges
};

struct CompareResult {
  unsigned width = 0, height = 0;
  size_t pixels = 0;
  size_t coverage_ours_only = 0;         // drawn by us, background in the reference
  size_t coverage_reference_only = 0;    // background in ours, drawn by the reference
  size_t coverage_off_edges = 0;         // of the mismatches, those not next to an edge of the reference
  size_t coverage_within_tolerance = 0;  // background in one, drawn within tolerance of it in the other
  size_t within_tolerance = 0;           // colour difference <= tolerance (coverage_within_tolerance included)
  unsigned max_colour_difference = 0;    // over pixels whose coverage agrees
  // Red: coverage differs; yellow: colour beyond tolerance; grey: colour
  // difference within tolerance, scaled so that the tolerance is white.
  Image difference;

  size_t coverage_mismatches() const { return coverage_ours_only + coverage_reference_only; }
  double percent_within_tolerance() const;
  bool passes(const PassRule& rule) const;
  // One line for logs and ctest output.
  std::string summary() const;
};

// Throws std::invalid_argument if the sizes differ or an image is malformed.
CompareResult compare_images(const Image& ours, const Image& reference, const CompareOptions& options);

// How two images of the same size differ, pixel by pixel, as stored (no
// reduction, alpha included): for two renders of our own, where neither is a
// reference and there is no background to judge coverage by (image_diff).
// A pixel's difference is the largest absolute difference of its channels.
struct PixelDifference {
  unsigned width = 0, height = 0;
  size_t pixels = 0;
  size_t differing = 0;         // pixels whose difference is not 0
  unsigned max_difference = 0;  // over all pixels
  double mean_difference = 0;   // over all pixels

  double percent_differing() const;
  // One line for logs and ctest output.
  std::string summary() const;
};

// Throws std::invalid_argument if the sizes differ or an image is malformed.
PixelDifference diff_pixels(const Image& a, const Image& b);

// Writes <dir>/<prefix>ours.png, reference.png and difference.png (creating
// dir) for a person to look at; ours and reference as reduced to the output
// format, i.e. as they were compared. Returns the directory.
std::string write_comparison_images(const std::string& dir, const std::string& prefix, const Image& ours,
                                    const Image& reference, const CompareResult& result, const CompareOptions& options);

}  // namespace tessera::reference
