// Chooses the back end by name (--backend, driver.backend).
#include <stdexcept>

#include "gl/runtime.h"
#include "renderers/arm/arm_renderer.h"
#include "renderers/raster/raster_renderer.h"

namespace tessera::gl {

std::unique_ptr<Renderer> make_renderer(const std::string& backend, AppEnvironment& env) {
  if (backend == "arm") return std::make_unique<arm::ArmRenderer>(env);
  if (backend == "raster") return std::make_unique<raster_backend::RasterRenderer>(env);
  throw std::invalid_argument("back end '" + backend + "' is not available (available: arm, raster)");
}

}  // namespace tessera::gl
