// The arm back end's entry points for the registry (backends.def).
#include "renderers/arm/arm_renderer.h"
#include "renderers/backend_entry_points.h"

namespace tessera::backends::arm {

std::unique_ptr<gl::Renderer> make_renderer(AppEnvironment& env) {
  return std::make_unique<tessera::arm::ArmRenderer>(env);
}

// The arm back end draws into the display's frame buffers with buffers of
// its own in system memory: every configuration the SoC accepts suits it,
// and it needs nothing set. It has no keys of its own.
void adjust_configuration(Config&) {}
void check_configuration(const Config&) {}
ParamGroup parameters() {
  return {"arm", {}, {}};
}

}  // namespace tessera::backends::arm
