// Fog for the software back ends and the raster back end's command writer:
// a vertex's fog coordinate (gl::ScreenVertex::fog, the eye distance) turned
// into the 16.16 fog argument that is interpolated per fragment, and the
// per-fragment factor and blend of common/fog.h (the arithmetic the
// rasterizer's fog unit computes bit for bit).
#pragma once

#include <cstdint>

#include "common/fog.h"
#include "gl/renderer.h"

namespace tessera::renderers {

// argument = c * scale + bias, in units of the fog argument (not yet 16.16),
// in single precision: the back ends run it on the ARM922T, which has no
// FPU (1 / ln 2 and 1 / sqrt(ln 2) as float constants, one division per
// draw for linear fog). Linear fog with end == start has no slope; it uses
// scale -1 and bias end, as Mesa does (its fog scale is 1 there), so f is 1
// up to c = end - 1 and 0 from c = end.
struct FogCoefficientsF {
  float scale = 0, bias = 0;
};

inline FogCoefficientsF fog_coefficients_f(const gl::RasterState& state) {
  constexpr float INV_LN2 = 1.44269504f, INV_SQRT_LN2 = 1.20112241f;
  switch (state.fog_mode) {
    case FogMode::linear: {
      const float range = state.fog_end - state.fog_start;
      const float scale = range == 0 ? 1.0f : 1.0f / range;
      return {-scale, state.fog_end * scale};
    }
    case FogMode::exp: return {state.fog_density * INV_LN2, 0.0f};
    case FogMode::exp2: return {state.fog_density * INV_SQRT_LN2, 0.0f};
  }
  return {0.0f, 1.0f};
}

// The 16.16 fog argument of fog coordinate c in single precision (one
// multiply, one add, one conversion), rounded to nearest and saturated to
// +-limit (a non-finite c gives 0).
inline int32_t fog_argument_f(const FogCoefficientsF& k, float c, int32_t limit) {
  const float a = (c * k.scale + k.bias) * 65536.0f;
  if (!(a == a) || a - a != 0.0f) return 0;  // NaN or infinite, without libm
  const float bound = static_cast<float>(limit);
  if (a >= bound) return limit;
  if (a <= -bound) return -limit;
  return static_cast<int32_t>(a >= 0 ? a + 0.5f : a - 0.5f);
}

// The fog colour as r | g << 8 | b << 16 | a << 24.
inline uint32_t fog_rgba(const gl::RasterState& state) {
  return uint32_t{state.fog_color[0]} | uint32_t{state.fog_color[1]} << 8 | uint32_t{state.fog_color[2]} << 16 |
         uint32_t{state.fog_color[3]} << 24;
}

}  // namespace tessera::renderers
