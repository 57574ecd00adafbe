#include "reference/image_compare.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

namespace tessera::reference {

namespace {

Rgba8 pixel_at(const Image& image, size_t index) {
  const uint8_t* p = &image.rgba[index * 4];
  return {p[0], p[1], p[2], p[3]};
}

bool uses_alpha(const CompareOptions& options) {
  return options.format == PixelFormat::rgba8888 && options.compare_alpha;
}

bool same_colour(Rgba8 a, Rgba8 b, bool with_alpha) {
  return a.r == b.r && a.g == b.g && a.b == b.b && (!with_alpha || a.a == b.a);
}

unsigned colour_difference(Rgba8 a, Rgba8 b, bool with_alpha) {
  const auto channel = [](uint8_t x, uint8_t y) { return static_cast<unsigned>(std::abs(int{x} - int{y})); };
  unsigned difference = std::max({channel(a.r, b.r), channel(a.g, b.g), channel(a.b, b.b)});
  if (with_alpha) difference = std::max(difference, channel(a.a, b.a));
  return difference;
}

void check_image(const Image& image, const char* which) {
  if (image.rgba.size() != size_t{image.width} * image.height * 4)
    throw std::invalid_argument(std::string("image comparison: ") + which + " image has " +
                                std::to_string(image.rgba.size()) + " bytes for " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " RGBA pixels");
}

Image reduced(const Image& image, PixelFormat format) {
  Image out = image;
  for (size_t i = 0; i < size_t{image.width} * image.height; ++i) {
    const Rgba8 colour = reduce(pixel_at(image, i), format);
    uint8_t* p = &out.rgba[i * 4];
    p[0] = colour.r;
    p[1] = colour.g;
    p[2] = colour.b;
    p[3] = colour.a;
  }
  return out;
}

}  // namespace

PixelFormat parse_output_format(const std::string& name) {
  if (const std::optional<PixelFormat> format = pixel_format_from_name(name)) return *format;
  throw std::invalid_argument("unknown output format '" + name + "' (" + pixel_format_names() + ")");
}

Rgba8 reduce(Rgba8 colour, PixelFormat format) {
  const uint32_t word = colour.r | colour.g << 8 | colour.b << 16 | uint32_t{colour.a} << 24;
  const uint32_t shown = quantize_color(format, word);
  return {static_cast<uint8_t>(shown), static_cast<uint8_t>(shown >> 8), static_cast<uint8_t>(shown >> 16),
          static_cast<uint8_t>(shown >> 24)};
}

double CompareResult::percent_within_tolerance() const {
  return pixels == 0 ? 100.0 : 100.0 * static_cast<double>(within_tolerance) / static_cast<double>(pixels);
}

bool CompareResult::passes(const PassRule& rule) const {
  return coverage_mismatches() <= rule.allowed_coverage_mismatches &&
         (!rule.coverage_only_on_edges || coverage_off_edges == 0) &&
         percent_within_tolerance() >= rule.min_percent_within_tolerance;
}

std::string CompareResult::summary() const {
  char line[256];
  std::snprintf(line, sizeof line,
                "%ux%u: coverage mismatches %zu (ours only %zu, reference only %zu, off the edges %zu); "
                "within tolerance %zu of %zu (%.3f%%); max colour difference %u",
                width, height, coverage_mismatches(), coverage_ours_only, coverage_reference_only, coverage_off_edges,
                within_tolerance, pixels, percent_within_tolerance(), max_colour_difference);
  return line;
}

CompareResult compare_images(const Image& ours, const Image& reference, const CompareOptions& options) {
  check_image(ours, "our");
  check_image(reference, "reference");
  if (ours.width != reference.width || ours.height != reference.height)
    throw std::invalid_argument("image comparison: ours is " + std::to_string(ours.width) + "x" +
                                std::to_string(ours.height) + ", the reference " + std::to_string(reference.width) +
                                "x" + std::to_string(reference.height));

  const bool with_alpha = uses_alpha(options);
  const Rgba8 background = reduce(options.clear_colour, options.format);
  const unsigned grey_scale_divisor = std::max(options.tolerance, 1u);

  CompareResult result;
  result.width = ours.width;
  result.height = ours.height;
  result.pixels = size_t{ours.width} * ours.height;
  result.difference.width = ours.width;
  result.difference.height = ours.height;
  result.difference.rgba.assign(result.pixels * 4, 0);

  std::vector<bool> reference_coverage(result.pixels);
  for (size_t i = 0; i < result.pixels; ++i)
    reference_coverage[i] = !same_colour(reduce(pixel_at(reference, i), options.format), background, with_alpha);
  // Does the reference have a pixel covered as `covered` next to (x, y)?
  const auto reference_has_neighbour = [&](unsigned x, unsigned y, bool covered) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const long nx = long{x} + dx, ny = long{y} + dy;
        if ((dx || dy) && nx >= 0 && ny >= 0 && nx < long{ours.width} && ny < long{ours.height} &&
            reference_coverage[size_t(ny) * ours.width + size_t(nx)] == covered)
          return true;
      }
    return false;
  };

  for (size_t i = 0; i < result.pixels; ++i) {
    const Rgba8 mine = reduce(pixel_at(ours, i), options.format);
    const Rgba8 theirs = reduce(pixel_at(reference, i), options.format);
    const bool drawn_by_us = !same_colour(mine, background, with_alpha);
    const bool drawn_by_reference = reference_coverage[i];
    const unsigned difference = colour_difference(mine, theirs, with_alpha);
    uint8_t* out = &result.difference.rgba[i * 4];
    out[3] = 255;

    if (drawn_by_us != drawn_by_reference) {
      if (difference <= options.tolerance) {
        ++result.coverage_within_tolerance;
      } else {
        ++(drawn_by_us ? result.coverage_ours_only : result.coverage_reference_only);
        if (!reference_has_neighbour(unsigned(i % ours.width), unsigned(i / ours.width), drawn_by_us))
          ++result.coverage_off_edges;
        out[0] = 255;
        continue;
      }
    }
    result.max_colour_difference = std::max(result.max_colour_difference, difference);
    if (difference <= options.tolerance) {
      ++result.within_tolerance;
      const auto grey = static_cast<uint8_t>(std::min(255u, difference * 255u / grey_scale_divisor));
      out[0] = out[1] = out[2] = grey;
    } else {
      out[0] = out[1] = 255;
    }
  }
  return result;
}

double PixelDifference::percent_differing() const {
  return pixels == 0 ? 0.0 : 100.0 * static_cast<double>(differing) / static_cast<double>(pixels);
}

std::string PixelDifference::summary() const {
  char line[160];
  std::snprintf(line, sizeof line, "%ux%u: %zu of %zu pixels differ (%.2f%%), max difference %u, mean %.3f per pixel",
                width, height, differing, pixels, percent_differing(), max_difference, mean_difference);
  return line;
}

PixelDifference diff_pixels(const Image& a, const Image& b) {
  check_image(a, "first");
  check_image(b, "second");
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("image comparison: the first image is " + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + ", the second " + std::to_string(b.width) + "x" +
                                std::to_string(b.height));
  PixelDifference result;
  result.width = a.width;
  result.height = a.height;
  result.pixels = size_t{a.width} * a.height;
  uint64_t total = 0;
  for (size_t i = 0; i < result.pixels; ++i) {
    const unsigned difference = colour_difference(pixel_at(a, i), pixel_at(b, i), true);
    result.differing += difference != 0;
    result.max_difference = std::max(result.max_difference, difference);
    total += difference;
  }
  result.mean_difference = result.pixels == 0 ? 0.0 : static_cast<double>(total) / static_cast<double>(result.pixels);
  return result;
}

std::string write_comparison_images(const std::string& dir, const std::string& prefix, const Image& ours,
                                    const Image& reference, const CompareResult& result,
                                    const CompareOptions& options) {
  std::filesystem::create_directories(dir);
  const std::filesystem::path base(dir);
  write_png((base / (prefix + "ours.png")).string(), ours.width, ours.height, reduced(ours, options.format).rgba);
  write_png((base / (prefix + "reference.png")).string(), reference.width, reference.height,
            reduced(reference, options.format).rgba);
  write_png((base / (prefix + "difference.png")).string(), result.difference.width, result.difference.height,
            result.difference.rgba);
  return dir;
}

}  // namespace tessera::reference
