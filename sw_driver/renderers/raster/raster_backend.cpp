// The raster back end's entry points for the registry (backends.def).
#include <string>

#include "renderers/backend_entry_points.h"
#include "renderers/raster/raster_renderer.h"

namespace tessera::backends::raster {

std::unique_ptr<gl::Renderer> make_renderer(AppEnvironment& env) {
  return std::make_unique<raster_backend::RasterRenderer>(env);
}

void adjust_configuration(Config&) {}

// Nothing to check: the rasterizer draws straight into the display's frame
// buffers, and the SoC gives it the display's size (RasterRenderer reads
// both from the registers and refuses a mismatch all the same).
void check_configuration(const Config&) {}

// The rasterizer's keys (raster.*) are the block's; the back end has none.
ParamGroup parameters() {
  return {"raster", {}, {}};
}

}  // namespace tessera::backends::raster
