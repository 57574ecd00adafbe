// What each back end's folder defines for the registry (backends.h), four
// functions per line of backends.def, in namespace tessera::backends::<id>,
// beside CAPABILITIES, the table's depth and stencil bits, which the back
// end's renderer also reports:
//  - make_renderer: builds the back end's renderer for an application
//    (the factory the launcher hands to the GL driver in AppEnvironment);
//  - adjust_configuration: sets what the back end needs where the user set
//    nothing (Config::is_set), before the configuration is validated (the
//    array back ends: the display's size to the array's frame);
//  - check_configuration: throws ConfigError for a configuration the back
//    end cannot run with (called when driver.backend names it);
//  - parameters: the back end's own keys (ap-tile: ap.tile.*), declared
//    once with their defaults and put in every configuration beside
//    driver.backend; a back end without any returns an empty group. Its
//    make_renderer reads them from AppEnvironment::config.
// A back end that forgets one fails to link, naming the function.
#pragma once

#include <memory>

#include "config/config.h"
#include "device/app_environment.h"
#include "gl/renderer.h"

#define TESSERA_BACKEND(id, name, depth_bits, stencil_bits, description)            \
  namespace tessera::backends::id {                                                 \
  inline constexpr gl::RendererCapabilities CAPABILITIES{depth_bits, stencil_bits}; \
  std::unique_ptr<gl::Renderer> make_renderer(AppEnvironment& env);                 \
  void adjust_configuration(Config& config);                                        \
  void check_configuration(const Config& config);                                   \
  ParamGroup parameters();                                                          \
  }
#include "renderers/backends.def"
#undef TESSERA_BACKEND
