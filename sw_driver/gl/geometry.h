// The geometry stage of the GL front end as plain functions: clipping in
// clip space against the whole view volume, perspective division, the
// viewport transform into the rasterizer's 9.4 / 0.24 / 0.8 formats, back-face
// orientation, and per-vertex lighting (OpenGL ES 1.1, section 2.12).
// No GL state and no host model here, so each step is unit-tested directly.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "common/screen_size.h"
#include "gl/renderer.h"

namespace tessera::gl {

struct ClipVertex {
  glm::vec4 position;                // clip coordinates
  glm::vec4 color;                   // RGBA, [0, 1] after lighting or clamping
  glm::vec2 tex[MAX_TEXTURE_UNITS];  // per unit, after the unit's texture matrix
};

// Clips a convex polygon against -w <= x, y, z <= w (and w > 0), one plane
// after the other (Sutherland-Hodgman), interpolating every attribute
// linearly in clip space. Returns the clipped polygon (empty if outside).
std::vector<ClipVertex> clip_polygon(const std::vector<ClipVertex>& polygon);

// True if every vertex is inside the view volume (no clipping needed).
bool inside_view_volume(const ClipVertex& v);

struct Viewport {
  int x = 0, y = 0, width = 0, height = 0;
  float near_depth = 0.0f, far_depth = 1.0f;  // glDepthRangef
};

// A vertex's window coordinates before snapping: pixels, y up, computed in
// double precision from the float clip coordinates as to_screen does.
struct WindowPoint {
  double x = 0, y = 0;
};

// False for a position that is not finite or has w <= 0.
bool to_window(const glm::vec4& clip, const Viewport& viewport, WindowPoint* out);

// Whether a polygon has no area is decided before snapping to 9.4: snapping
// moves each vertex by up to 1/32 pixel, which turns three collinear
// vertices into a sliver that covers pixels. A polygon counts as degenerate
// when its height across its longest edge (twice its area over that edge's
// length) is at most a quarter of the snapping step. The float transform
// leaves collinear vertices within about 1e-4 pixel of their line on a
// 512-pixel screen, far inside this; and a triangle thinner than it would
// only cover what rounding to 1/16 pixel makes of it.
inline constexpr double DEGENERATE_HEIGHT = 1.0 / 64;  // pixels

// True when the convex polygon (window coordinates before snapping, fewer
// than three vertices included) has no area in the sense above.
bool is_degenerate(const std::vector<WindowPoint>& polygon);

// True when the snapped triangle's area is so large against its edges that
// the unsnapped triangle cannot be degenerate: a few integer operations
// that spare all but thin triangles the floating-point test on the host.
bool surely_has_area(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c);
inline constexpr unsigned SURELY_HAS_AREA_ALU = 10;  // its cost beside signed_area

// Window coordinates in 9.4 fixed point (rounded to nearest), depth in 0.24,
// colour in 0.8 (rounded to nearest, clamped). Returns false for a vertex
// whose coordinates are not finite or fall outside the 9.4 range (the caller
// drops the triangle).
bool to_screen(const ClipVertex& v, const Viewport& viewport, ScreenVertex* out);

// Twice the signed area of a screen triangle in 9.4 units squared (> 0:
// counter-clockwise with y up).
int64_t signed_area(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c);

inline constexpr int SUBPIXEL_BITS = 4;
inline constexpr int32_t MAX_SCREEN_COORDINATE = (1 << (9 + SUBPIXEL_BITS)) - 1;  // 9.4 unsigned
static_assert(MAX_SCREEN_COORDINATE + 1 == int32_t{MAX_SCREEN_SIZE} << SUBPIXEL_BITS,
              "a screen of MAX_SCREEN_SIZE pixels ends one code past 9.4");

uint8_t to_unorm8(float value);
uint32_t to_unorm24(float value);

// Lighting -------------------------------------------------------------------

struct Light {
  bool enabled = false;
  glm::vec4 ambient{0, 0, 0, 1};
  glm::vec4 diffuse{0, 0, 0, 1};  // light 0 defaults to white (set by the context)
  glm::vec4 specular{0, 0, 0, 1};
  glm::vec4 position{0, 0, 1, 0};  // eye coordinates (transformed when specified)
  glm::vec3 spot_direction{0, 0, -1};
  float spot_exponent = 0;
  float spot_cutoff = 180;
  float constant_attenuation = 1, linear_attenuation = 0, quadratic_attenuation = 0;
};

struct Material {
  glm::vec4 ambient{0.2f, 0.2f, 0.2f, 1};
  glm::vec4 diffuse{0.8f, 0.8f, 0.8f, 1};
  glm::vec4 specular{0, 0, 0, 1};
  glm::vec4 emission{0, 0, 0, 1};
  float shininess = 0;
};

struct LightingModel {
  glm::vec4 ambient{0.2f, 0.2f, 0.2f, 1};
  std::vector<Light> lights;  // 8 in GL ES 1.1
};

// The lit colour of a vertex at eye position `eye` with unit eye-space
// normal `normal` (ES 1.1 eq. 2.1, local viewer false as ES mandates),
// clamped to [0, 1]. Alpha is the material's diffuse alpha.
glm::vec4 light_vertex(const LightingModel& model, const Material& material, const glm::vec4& eye,
                       const glm::vec3& normal);

// Counts of soft-float operations per step, for the host's cost model.
struct FloatCost {
  uint64_t add = 0, mul = 0, div = 0, sqrt = 0, cmp = 0, conv = 0, calls = 0;
  FloatCost& operator+=(const FloatCost& o) {
    add += o.add, mul += o.mul, div += o.div, sqrt += o.sqrt, cmp += o.cmp, conv += o.conv, calls += o.calls;
    return *this;
  }
};
FloatCost transform_cost();                  // one 4x4 matrix times a vector
FloatCost lighting_cost(unsigned lights);    // light_vertex with `lights` enabled lights
FloatCost clip_test_cost();                  // inside_view_volume
FloatCost screen_cost();                     // to_screen
FloatCost degeneracy_cost(size_t vertices);  // is_degenerate of a polygon of `vertices`

}  // namespace tessera::gl
