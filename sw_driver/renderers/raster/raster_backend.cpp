// The raster back end's entry points for the registry (backends.def).
#include <string>

#include "renderers/backend_entry_points.h"
#include "renderers/raster/raster_renderer.h"

namespace tessera::backends::raster {

std::unique_ptr<gl::Renderer> make_renderer(AppEnvironment& env) {
  return std::make_unique<raster_backend::RasterRenderer>(env);
}

// The rasterizer's size is the user's to choose (the check below).
void adjust_configuration(Config&) {}

// The rasterizer draws straight into the display's frame buffers, so it
// must cover the display exactly (RasterRenderer checks it again against
// the registers).
void check_configuration(const Config& config) {
  if (config.get_uint("raster.width") != config.get_uint("display.width") ||
      config.get_uint("raster.height") != config.get_uint("display.height"))
    throw ConfigError(
        "configuration: impossible combination: driver.backend=raster draws the display's frame buffers, "
        "but raster.width x raster.height = " +
        std::to_string(config.get_uint("raster.width")) + " x " + std::to_string(config.get_uint("raster.height")) +
        " differs from display.width x display.height = " + std::to_string(config.get_uint("display.width")) + " x " +
        std::to_string(config.get_uint("display.height")));
}

// The rasterizer's keys (raster.*) are the block's; the back end has none.
ParamGroup parameters() {
  return {"raster", {}, {}};
}

}  // namespace tessera::backends::raster
