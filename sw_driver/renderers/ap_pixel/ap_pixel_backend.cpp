// The ap-pixel back end's entry points for the registry (backends.def).
#include <cstdint>
#include <iterator>
#include <string>

#include "renderers/ap_pixel/ap_pixel_renderer.h"
#include "renderers/backend_entry_points.h"
#include "renderers/common/study_frame.h"

namespace tessera::backends::ap_pixel {

namespace {

// A CU's block offsets are signed bytes (check_configuration).
constexpr unsigned MAX_FRAME = 256;

}  // namespace

ParamGroup parameters() {
  return {"ap-pixel",
          {
              param::integer("ap.pixel.block", 1, 1, 5, "pixels",
                             "ap-pixel: each CU shades a block of k x k pixels (one full evaluation, the others "
                             "by adding gradients)"),
              param::choice("ap.pixel.program", "tuned",
                            {std::begin(tessera::ap_pixel::PROGRAM_VARIANT_NAMES),
                             std::end(tessera::ap_pixel::PROGRAM_VARIANT_NAMES)},
                            "ap-pixel's array program: tuned (16.8 values kept in registers between statements) or "
                            "study (the study's program as its compiler emitted it: 8.8 values, every statement "
                            "loading its operands from CMEM and storing its result there)"),
          },
          {}};
}

std::unique_ptr<gl::Renderer> make_renderer(AppEnvironment& env) {
  const Config defaults({parameters()});
  const Config& config = env.config != nullptr ? *env.config : defaults;
  return std::make_unique<tessera::ap_pixel::ApPixelRenderer>(
      env, static_cast<unsigned>(config.get_uint("ap.pixel.block")),
      tessera::ap_pixel::program_variant(config.get_string("ap.pixel.program")));
}

// The display shows the study's frame (192 x 144 for the 24 x 4 array)
// unless the user chose its size. A grid whose frame ap-pixel cannot draw
// is refused here, naming the array's keys (array.rows 15 and 16 would
// otherwise fail display.height's range, naming a key the user never set).
void adjust_configuration(Config& config) {
  const auto [width, height] = renderers::study_frame(config);
  if ((!config.is_set("display.width") && width > MAX_FRAME) ||
      (!config.is_set("display.height") && height > MAX_FRAME))
    throw ConfigError("configuration: impossible combination: driver.backend=ap-pixel draws frames of at most " +
                      std::to_string(MAX_FRAME) + " x " + std::to_string(MAX_FRAME) +
                      " pixels, but the array's frame (array.columns x array.rows tiles of 8 x 36) is " +
                      std::to_string(width) + " x " + std::to_string(height) +
                      "; set display.width and display.height, or use at most array.columns=" +
                      std::to_string(MAX_FRAME / renderers::STUDY_TILE_WIDTH) +
                      " and array.rows=" + std::to_string(MAX_FRAME / renderers::STUDY_TILE_HEIGHT));
  if (!config.is_set("display.width")) config.set("display.width", width, "driver.backend=ap-pixel");
  if (!config.is_set("display.height")) config.set("display.height", height, "driver.backend=ap-pixel");
}

// A CU's block offsets are signed bytes: frames up to 256 x 256.
void check_configuration(const Config& config) {
  const uint64_t width = config.get_uint("display.width"), height = config.get_uint("display.height");
  if (width > MAX_FRAME || height > MAX_FRAME)
    throw ConfigError("configuration: impossible combination: driver.backend=ap-pixel draws frames of at most " +
                      std::to_string(MAX_FRAME) + " x " + std::to_string(MAX_FRAME) +
                      " pixels (a CU's block offsets from the triangle's origin are signed bytes), but "
                      "display.width x display.height = " +
                      std::to_string(width) + " x " + std::to_string(height));
}

}  // namespace tessera::backends::ap_pixel
