// Chooses the back end by name (--backend, driver.backend) and tells what
// each stores before one is made.
#include <stdexcept>

#include "gl/runtime.h"
#include "renderers/arm/arm_renderer.h"
#include "renderers/raster/raster_renderer.h"

namespace tessera::gl {

namespace {

std::invalid_argument unknown_back_end(const std::string& backend) {
  return std::invalid_argument("back end '" + backend + "' is not available (available: arm, raster)");
}

}  // namespace

std::unique_ptr<Renderer> make_renderer(const std::string& backend, AppEnvironment& env) {
  if (backend == "arm") return std::make_unique<arm::ArmRenderer>(env);
  if (backend == "raster") return std::make_unique<raster_backend::RasterRenderer>(env);
  throw unknown_back_end(backend);
}

RendererCapabilities renderer_capabilities(const std::string& backend) {
  if (backend == "arm") return arm::ArmRenderer::CAPABILITIES;
  if (backend == "raster") return raster_backend::RasterRenderer::CAPABILITIES;
  throw unknown_back_end(backend);
}

}  // namespace tessera::gl
