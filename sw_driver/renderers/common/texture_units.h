// The texture unit a back end with one unit and the hardware's three
// environments (MODULATE, REPLACE, DECAL) draws: raster, ap-tile and
// ap-pixel. They draw the first enabled unit of gl::RasterState; a further
// enabled unit and an environment they do not have are reported through
// UnsupportedState, never dropped silently (docs/es11_profile.md).
#pragma once

#include <string>

#include "gl/renderer.h"

namespace tessera::renderers {

struct SingleTextureUnit {
  int index = -1;  // -1: no unit is enabled
  gl::TexEnv env = gl::TexEnv::modulate;
};

inline const char* tex_env_name(gl::TexEnvMode env) {
  switch (env) {
    case gl::TexEnvMode::modulate: return "GL_MODULATE";
    case gl::TexEnvMode::replace: return "GL_REPLACE";
    case gl::TexEnvMode::decal: return "GL_DECAL";
    case gl::TexEnvMode::blend: return "GL_BLEND";
    case gl::TexEnvMode::add: return "GL_ADD";
    case gl::TexEnvMode::combine: return "GL_COMBINE";
  }
  return "?";
}

// The first enabled unit and its hardware environment; an environment
// without a hardware code is drawn as MODULATE. report(what) is called for
// what is not drawn (UnsupportedState::report's `what`).
template <typename Report>
SingleTextureUnit single_texture_unit(const gl::RasterState& state, Report&& report) {
  SingleTextureUnit drawn;
  for (unsigned u = 0; u < gl::MAX_TEXTURE_UNITS; ++u) {
    if (!state.unit[u].enabled) continue;
    if (drawn.index >= 0) {
      report("a second enabled texture unit (texture unit " + std::to_string(u) + "): drawn without it");
      continue;
    }
    drawn.index = static_cast<int>(u);
    if (!gl::hardware_tex_env(state.unit[u].env, &drawn.env))
      report(std::string("the ") + tex_env_name(state.unit[u].env) + " texture environment: drawn as GL_MODULATE");
  }
  return drawn;
}

}  // namespace tessera::renderers
