// The toy back end's entry points for the registry (backends.def).
#include "renderers/backend_entry_points.h"
#include "renderers/toy/toy_renderer.h"

namespace tessera::backends::toy {

std::unique_ptr<gl::Renderer> make_renderer(AppEnvironment& env) {
  return std::make_unique<tessera::toy::ToyRenderer>(env);
}

// The toy clears the display's own frame buffers, whatever their size and
// format: it needs nothing set and suits every configuration. It has no
// keys of its own.
void adjust_configuration(Config&) {}
void check_configuration(const Config&) {}
ParamGroup parameters() {
  return {"toy", {}, {}};
}

}  // namespace tessera::backends::toy
