#include "renderers/backend_parameters.h"

#include <string>

namespace tessera {

ParamGroup driver_parameters() {
  return {"driver",
          {
              param::choice("driver.backend", "arm", {"arm", "raster"},
                            "renderer back end of the GL ES driver: arm (software on the host) or raster (the "
                            "rasterizer block)"),
          },
          [](const Config& config) {
            if (config.get_string("driver.backend") == "raster" &&
                (config.get_uint("raster.width") != config.get_uint("display.width") ||
                 config.get_uint("raster.height") != config.get_uint("display.height")))
              throw ConfigError(
                  "configuration: impossible combination: driver.backend=raster draws the display's frame buffers, "
                  "but raster.width x raster.height = " +
                  std::to_string(config.get_uint("raster.width")) + " x " +
                  std::to_string(config.get_uint("raster.height")) +
                  " differs from display.width x display.height = " + std::to_string(config.get_uint("display.width")) +
                  " x " + std::to_string(config.get_uint("display.height")));
          }};
}

}  // namespace tessera
