// The ap-object back end's entry points for the registry (backends.def).
#include <algorithm>
#include <cstdint>
#include <iterator>
#include <string>

#include "renderers/ap_object/ap_object_renderer.h"
#include "renderers/backend_entry_points.h"
#include "renderers/common/study_frame.h"

namespace tessera::backends::ap_object {

namespace {

// Frames up to 1024 x 1024 (check_configuration).
constexpr unsigned MAX_FRAME = 1024;

}  // namespace

ParamGroup parameters() {
  return {"ap-object",
          {
              param::choice("ap.object.unit", "half",
                            {std::begin(tessera::ap_object::UNIT_NAMES), std::end(tessera::ap_object::UNIT_NAMES)},
                            "ap-object: what a CU walks per batch: half (one half of a triangle, split at its middle "
                            "vertex: the MorphoSys paper's strategy 3) or triangle (a whole triangle, its two halves "
                            "one after the other: strategy 1)"),
              param::choice("ap.object.zpath", "host",
                            {std::begin(tessera::ap_object::ZPATH_NAMES), std::end(tessera::ap_object::ZPATH_NAMES)},
                            "ap-object: where the CUs' pixels go: host (into CMEM slots the host reads back and "
                            "z-tests) or unit (zsend to the z-buffer unit, which needs zbuf.enabled=true and "
                            "array.features.zsend=true; frames needing more than GL_LESS on 16-bit depth and RGB565 "
                            "colour are drawn on the host path)"),
          },
          {}};
}

std::unique_ptr<gl::Renderer> make_renderer(AppEnvironment& env) {
  const Config defaults({parameters()});
  const Config& config = env.config != nullptr ? *env.config : defaults;
  return std::make_unique<tessera::ap_object::ApObjectRenderer>(
      env, tessera::ap_object::unit_named(config.get_string("ap.object.unit")),
      tessera::ap_object::zpath_named(config.get_string("ap.object.zpath")));
}

// The display shows the study's frame unless the user chose its size.
void adjust_configuration(Config& config) {
  const auto [width, height] = renderers::study_frame(config);
  if (!config.is_set("display.width"))
    config.set("display.width", std::min<uint64_t>(width, MAX_FRAME), "driver.backend=ap-object");
  if (!config.is_set("display.height"))
    config.set("display.height", std::min<uint64_t>(height, MAX_FRAME), "driver.backend=ap-object");
}

// A pixel's x is a signed 16-bit value and the set-up's vertices lie within
// +-1024 pixels: frames up to 1024 x 1024.
void check_configuration(const Config& config) {
  const uint64_t width = config.get_uint("display.width"), height = config.get_uint("display.height");
  if (width > MAX_FRAME || height > MAX_FRAME)
    throw ConfigError("configuration: impossible combination: driver.backend=ap-object draws frames of at most " +
                      std::to_string(MAX_FRAME) + " x " + std::to_string(MAX_FRAME) +
                      " pixels, but display.width x display.height = " + std::to_string(width) + " x " +
                      std::to_string(height));
  if (!config.has("ap.object.zpath") || config.get_string("ap.object.zpath") != "unit") return;
  // The z path through the unit: the unit and its instruction, an RGB565
  // frame (the unit's colour), whole frame rows in the unit's window.
  for (const char* key : {"zbuf.enabled", "array.features.zsend"})
    if (!config.get_bool(key))
      throw ConfigError(std::string("configuration: impossible combination: ap.object.zpath=unit sends the pixels to "
                                    "the z-buffer unit, but ") +
                        key + "=false");
  if (config.get_string("display.format") != "rgb565")
    throw ConfigError(
        "configuration: impossible combination: ap.object.zpath=unit writes the z-buffer unit's RGB565 "
        "colour, but display.format=" +
        config.get_string("display.format"));
  if (config.get_uint("zbuf.entries") < width)
    throw ConfigError(
        "configuration: impossible combination: ap.object.zpath=unit draws whole frame rows in the "
        "z-buffer unit's window, but zbuf.entries=" +
        std::to_string(config.get_uint("zbuf.entries")) + " < display.width=" + std::to_string(width));
}

}  // namespace tessera::backends::ap_object
