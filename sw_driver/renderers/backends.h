// The registry of renderer back ends: backends.def's lines as a table of
// names, descriptions, static capabilities and entry points. The launchers
// (soc_sim, the benchmarks) look a back end up here by driver.backend and
// hand its factory to the GL driver through AppEnvironment; the front end
// itself knows no back end.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "config/config.h"
#include "costs/host_cost.h"
#include "device/app_environment.h"
#include "gl/renderer.h"
#include "renderers/backend_entry_points.h"

namespace tessera::backends {

struct Backend {
  const char* id;    // folder, library tessera_backend_<id>, namespace
  const char* name;  // driver.backend, --backend
  const char* description;
  gl::RendererCapabilities capabilities;
  std::unique_ptr<gl::Renderer> (*make_renderer)(AppEnvironment& env);
  void (*adjust_configuration)(Config& config);
  void (*check_configuration)(const Config& config);
  ParamGroup (*parameters)();
};

inline constexpr Backend BACKENDS[] = {
#define TESSERA_BACKEND(id, name, depth_bits, stencil_bits, description) \
  {#id,                                                                  \
   name,                                                                 \
   description,                                                          \
   id::CAPABILITIES,                                                     \
   &id::make_renderer,                                                   \
   &id::adjust_configuration,                                            \
   &id::check_configuration,                                             \
   &id::parameters},
#include "renderers/backends.def"
#undef TESSERA_BACKEND
};

// The back end called `name`, or nullptr.
const Backend* find_backend(std::string_view name);
// The back end called `name`; throws std::invalid_argument naming it and
// listing the known ones.
const Backend& backend(std::string_view name);

// Hands the back end to an application: its factory and what its buffers
// hold, for the GL driver's EGL.
inline void hand_over(const Backend& backend, AppEnvironment& env) {
  // The back end's own set-up as it makes its renderer (its array programs
  // loaded, its buffers laid out) is the measured cost table's row
  // backend_start_<id>, where the table has one.
  const std::optional<costs::HostCost> start = costs::find_host_cost(std::string("backend_start_") + backend.id);
  env.make_renderer = [make = backend.make_renderer, start](AppEnvironment& e) {
    std::unique_ptr<gl::Renderer> renderer = make(e);
    if (start && e.host != nullptr) costs::charge(*e.host, *start);
    return renderer;
  };
  env.capabilities = backend.capabilities;
}

// The names in the table's order: "arm, raster" (with `last_separator`,
// the last two are joined by it: "arm or raster").
std::string backend_names(const char* separator = ", ", const char* last_separator = nullptr);

}  // namespace tessera::backends
