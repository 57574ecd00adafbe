#include "reference/image_compare.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace tessera::reference {
namespace {

constexpr Rgba8 BACKGROUND{26, 26, 64, 255};

Image filled(unsigned width, unsigned height, Rgba8 colour) {
  Image image;
  image.width = width;
  image.height = height;
  for (unsigned i = 0; i < width * height; ++i)
    image.rgba.insert(image.rgba.end(), {colour.r, colour.g, colour.b, colour.a});
  return image;
}

void set_pixel(Image& image, unsigned x, unsigned y, Rgba8 colour) {
  uint8_t* p = &image.rgba[(size_t{y} * image.width + x) * 4];
  p[0] = colour.r;
  p[1] = colour.g;
  p[2] = colour.b;
  p[3] = colour.a;
}

CompareOptions options_for(PixelFormat format, unsigned tolerance) {
  CompareOptions options;
  options.format = format;
  options.clear_colour = BACKGROUND;
  options.tolerance = tolerance;
  return options;
}

TEST(ImageCompare, IdenticalImagesPass) {
  Image image = filled(8, 4, BACKGROUND);
  set_pixel(image, 3, 2, {200, 100, 50, 255});
  const CompareResult result = compare_images(image, image, options_for(PixelFormat::rgb565, 0));
  EXPECT_EQ(result.pixels, 32u);
  EXPECT_EQ(result.coverage_mismatches(), 0u);
  EXPECT_EQ(result.within_tolerance, 32u);
  EXPECT_EQ(result.max_colour_difference, 0u);
  EXPECT_DOUBLE_EQ(result.percent_within_tolerance(), 100.0);
  EXPECT_TRUE(result.passes(PassRule{}));
}

TEST(ImageCompare, OnePixelCoverageDifferenceIsCountedBothWays) {
  const Image reference = filled(8, 4, BACKGROUND);
  Image ours = reference;
  set_pixel(ours, 5, 1, {255, 255, 255, 255});
  const CompareOptions options = options_for(PixelFormat::rgb565, 8);

  const CompareResult extra = compare_images(ours, reference, options);
  EXPECT_EQ(extra.coverage_ours_only, 1u);
  EXPECT_EQ(extra.coverage_reference_only, 0u);
  EXPECT_EQ(extra.within_tolerance, 31u);
  EXPECT_EQ(extra.max_colour_difference, 0u) << "coverage differences are not colour differences";
  EXPECT_FALSE(extra.passes(PassRule{0, 0.0}));
  EXPECT_TRUE(extra.passes(PassRule{1, 95.0}));
  EXPECT_FALSE(extra.passes(PassRule{1, 99.0})) << "31 of 32 is 96.9%";

  const CompareResult missing = compare_images(reference, ours, options);
  EXPECT_EQ(missing.coverage_ours_only, 0u);
  EXPECT_EQ(missing.coverage_reference_only, 1u);
}

TEST(ImageCompare, ColourDifferenceBelowAndAboveTolerance) {
  Image reference = filled(4, 1, BACKGROUND);
  set_pixel(reference, 0, 0, {100, 100, 100, 255});
  set_pixel(reference, 1, 0, {100, 100, 100, 255});
  Image ours = reference;
  set_pixel(ours, 0, 0, {104, 100, 100, 255});  // 4 below the tolerance
  set_pixel(ours, 1, 0, {100, 100, 120, 255});  // 20 above it
  const CompareResult result = compare_images(ours, reference, options_for(PixelFormat::rgba8888, 8));
  EXPECT_EQ(result.coverage_mismatches(), 0u);
  EXPECT_EQ(result.within_tolerance, 3u);
  EXPECT_EQ(result.max_colour_difference, 20u);
  EXPECT_DOUBLE_EQ(result.percent_within_tolerance(), 75.0);

  const CompareResult looser = compare_images(ours, reference, options_for(PixelFormat::rgba8888, 20));
  EXPECT_EQ(looser.within_tolerance, 4u);
}

TEST(ImageCompare, AlphaIsComparedOnlyOnRequest) {
  Image reference = filled(2, 1, BACKGROUND);
  set_pixel(reference, 0, 0, {10, 200, 10, 128});
  Image ours = reference;
  set_pixel(ours, 0, 0, {10, 200, 10, 255});
  CompareOptions options = options_for(PixelFormat::rgba8888, 0);
  EXPECT_EQ(compare_images(ours, reference, options).max_colour_difference, 0u);
  options.compare_alpha = true;
  EXPECT_EQ(compare_images(ours, reference, options).max_colour_difference, 127u);
}

TEST(ImageCompare, Rgb565RoundsToNearestAndReplicatesBits) {
  EXPECT_EQ(reduce({0, 0, 0, 7}, PixelFormat::rgb565).r, 0);
  // 7 * 31 / 255 = 0.85 rounds to code 1, widened to 8 (truncation would give 0).
  EXPECT_EQ(reduce({7, 0, 0, 255}, PixelFormat::rgb565).r, 8);
  const Rgba8 white = reduce({255, 255, 255, 0}, PixelFormat::rgb565);
  EXPECT_EQ(white.r, 255);
  EXPECT_EQ(white.g, 255);
  EXPECT_EQ(white.b, 255);
  EXPECT_EQ(white.a, 255) << "the display has no alpha";
  // 0x87 = 135: 135 * 31 / 255 = 16.4, code 16 = 10000, expanded to 10000 100.
  EXPECT_EQ(reduce({0x87, 0, 0, 255}, PixelFormat::rgb565).r, 0x84);
  // 0x83 = 131: 131 * 63 / 255 = 32.4, code 32 = 100000, expanded to 100000 10.
  EXPECT_EQ(reduce({0, 0x83, 0, 255}, PixelFormat::rgb565).g, 0x82);
  EXPECT_EQ(reduce({1, 2, 3, 4}, PixelFormat::rgba8888).b, 3);
}

TEST(ImageCompare, ValuesSharingA565CodeCompareEqual) {
  Image reference = filled(3, 1, BACKGROUND);
  set_pixel(reference, 0, 0, {0x80, 0x80, 0x80, 255});
  set_pixel(reference, 1, 0, {0x80, 0x80, 0x80, 255});
  Image ours = reference;
  set_pixel(ours, 0, 0, {0x87, 0x83, 0x87, 255});  // same 5/6/5 codes
  set_pixel(ours, 1, 0, {0x88, 0x80, 0x80, 255});  // next red code: 0x84 vs 0x8c after expansion
  const CompareResult in565 = compare_images(ours, reference, options_for(PixelFormat::rgb565, 0));
  EXPECT_EQ(in565.within_tolerance, 2u);
  EXPECT_EQ(in565.max_colour_difference, 8u);
  const CompareResult in8888 = compare_images(ours, reference, options_for(PixelFormat::rgba8888, 0));
  EXPECT_EQ(in8888.within_tolerance, 1u);
}

TEST(ImageCompare, BackgroundIsJudgedAfterReduction) {
  // Within the background's 5/6/5 codes, so not drawn as far as the display can tell.
  Image ours = filled(2, 1, BACKGROUND);
  // Codes: red 27 * 31 / 255 = 3.3 (26: 3.2), green 25 * 63 / 255 = 6.2 (26: 6.4),
  // blue 65 * 31 / 255 = 7.9 (64: 7.8).
  set_pixel(ours, 0, 0, {BACKGROUND.r + 1, BACKGROUND.g - 1, BACKGROUND.b + 1, 255});
  const Image reference = filled(2, 1, BACKGROUND);
  EXPECT_EQ(compare_images(ours, reference, options_for(PixelFormat::rgb565, 0)).coverage_mismatches(), 0u);
  EXPECT_EQ(compare_images(ours, reference, options_for(PixelFormat::rgba8888, 0)).coverage_mismatches(), 1u);
}

TEST(ImageCompare, RejectsDifferentSizes) {
  EXPECT_THROW(compare_images(filled(4, 4, BACKGROUND), filled(4, 3, BACKGROUND), CompareOptions{}),
               std::invalid_argument);
  Image truncated = filled(4, 4, BACKGROUND);
  truncated.rgba.pop_back();
  EXPECT_THROW(compare_images(truncated, truncated, CompareOptions{}), std::invalid_argument);
  EXPECT_THROW(parse_output_format("rgb555"), std::invalid_argument);
  EXPECT_EQ(parse_output_format("rgba8888"), PixelFormat::rgba8888);
}

TEST(ImageCompare, WritesReadableDifferenceImage) {
  Image reference = filled(6, 5, BACKGROUND);
  set_pixel(reference, 2, 2, {100, 100, 100, 255});
  set_pixel(reference, 3, 2, {100, 100, 100, 255});
  Image ours = reference;
  set_pixel(ours, 0, 4, {255, 255, 255, 255});  // coverage
  set_pixel(ours, 2, 2, {104, 100, 100, 255});  // within tolerance (4 of 8)
  set_pixel(ours, 3, 2, {160, 100, 100, 255});  // beyond it
  const CompareOptions options = options_for(PixelFormat::rgba8888, 8);
  const CompareResult result = compare_images(ours, reference, options);

  const char* binary_dir = std::getenv("TESSERA_BINARY_DIR");
  const std::filesystem::path dir =
      std::filesystem::path(binary_dir ? binary_dir : std::filesystem::temp_directory_path().string()) / "test_output" /
      "image_compare";
  std::filesystem::remove_all(dir);
  write_comparison_images(dir.string(), "case_", ours, reference, result, options);

  EXPECT_TRUE(std::filesystem::exists(dir / "case_ours.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "case_reference.png"));
  const Image difference = read_image((dir / "case_difference.png").string());
  ASSERT_EQ(difference.width, 6u);
  ASSERT_EQ(difference.height, 5u);
  EXPECT_EQ(difference.rgba, result.difference.rgba);
  const auto pixel = [&](unsigned x, unsigned y) { return &difference.rgba[(size_t{y} * 6 + x) * 4]; };
  EXPECT_EQ(pixel(0, 4)[0], 255);  // red
  EXPECT_EQ(pixel(0, 4)[1], 0);
  EXPECT_EQ(pixel(3, 2)[0], 255);  // yellow
  EXPECT_EQ(pixel(3, 2)[1], 255);
  EXPECT_EQ(pixel(3, 2)[2], 0);
  EXPECT_EQ(pixel(2, 2)[0], 127);  // grey: 4 of a tolerance of 8
  EXPECT_EQ(pixel(2, 2)[2], 127);
  EXPECT_EQ(pixel(1, 1)[0], 0);  // identical
}

TEST(ImageCompare, DrawnColourWithinToleranceOfTheBackgroundIsJudgedByColour) {
  // One 5-bit red code above the background: after reduction, drawn in ours,
  // background in the reference, but only 8 apart.
  const Image reference = filled(2, 1, BACKGROUND);
  Image ours = reference;
  set_pixel(ours, 0, 0, {BACKGROUND.r + 8, BACKGROUND.g, BACKGROUND.b, 255});
  const CompareResult within = compare_images(ours, reference, options_for(PixelFormat::rgb565, 9));
  EXPECT_EQ(within.coverage_mismatches(), 0u);
  EXPECT_EQ(within.coverage_within_tolerance, 1u);
  EXPECT_EQ(within.within_tolerance, 2u);
  const CompareResult beyond = compare_images(ours, reference, options_for(PixelFormat::rgb565, 4));
  EXPECT_EQ(beyond.coverage_ours_only, 1u);
  EXPECT_EQ(beyond.coverage_within_tolerance, 0u);
}

TEST(ImageCompare, CoverageMismatchesAreOnEdgesOnlyNextToTheReferencesOtherSide) {
  // The reference covers columns 0..3 of an 8x4 image.
  Image reference = filled(8, 4, BACKGROUND);
  for (unsigned y = 0; y < 4; ++y)
    for (unsigned x = 0; x < 4; ++x) set_pixel(reference, x, y, {200, 200, 200, 255});
  Image ours = reference;
  set_pixel(ours, 4, 1, {200, 200, 200, 255});  // the edge moved right by one pixel: on the edge
  set_pixel(ours, 7, 2, {200, 200, 200, 255});  // a stray pixel: off the edges
  set_pixel(ours, 1, 1, BACKGROUND);            // a hole: off the edges
  const CompareResult result = compare_images(ours, reference, options_for(PixelFormat::rgb565, 9));
  EXPECT_EQ(result.coverage_ours_only, 2u);
  EXPECT_EQ(result.coverage_reference_only, 1u);
  EXPECT_EQ(result.coverage_off_edges, 2u);
  PassRule rule{3, 50.0};
  EXPECT_TRUE(result.passes(rule));
  rule.coverage_only_on_edges = true;
  EXPECT_FALSE(result.passes(rule));
}

TEST(PixelDifference, CountsPixelsWithAnyChannelDifferentAlphaIncluded) {
  const Image a = filled(4, 2, BACKGROUND);
  Image b = a;
  set_pixel(b, 0, 0, {BACKGROUND.r, BACKGROUND.g, BACKGROUND.b, 254});           // alpha only: 1
  set_pixel(b, 3, 1, {BACKGROUND.r + 40, BACKGROUND.g + 2, BACKGROUND.b, 255});  // 40
  const PixelDifference result = diff_pixels(a, b);
  EXPECT_EQ(result.width, 4u);
  EXPECT_EQ(result.height, 2u);
  EXPECT_EQ(result.pixels, 8u);
  EXPECT_EQ(result.differing, 2u);
  EXPECT_EQ(result.max_difference, 40u);
  EXPECT_DOUBLE_EQ(result.mean_difference, 41.0 / 8);
  EXPECT_DOUBLE_EQ(result.percent_differing(), 25.0);
  EXPECT_EQ(result.summary(), "4x2: 2 of 8 pixels differ (25.00%), max difference 40, mean 5.125 per pixel");
  EXPECT_EQ(diff_pixels(a, a).differing, 0u);
}

TEST(PixelDifference, DifferentSizesAreAnError) {
  EXPECT_THROW(diff_pixels(filled(4, 2, BACKGROUND), filled(2, 4, BACKGROUND)), std::invalid_argument);
  Image truncated = filled(4, 2, BACKGROUND);
  truncated.rgba.pop_back();
  EXPECT_THROW(diff_pixels(truncated, filled(4, 2, BACKGROUND)), std::invalid_argument);
}

}  // namespace
}  // namespace tessera::reference
