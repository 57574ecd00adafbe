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
  // Every member has a value, also the units a vertex's maker leaves alone
  // (to_screen checks every unit's coordinates for finiteness).
  glm::vec4 position{0, 0, 0, 1};      // clip coordinates
  glm::vec4 color{0, 0, 0, 0};         // RGBA, [0, 1] after lighting or clamping
  glm::vec2 tex[MAX_TEXTURE_UNITS]{};  // per unit, after the unit's texture matrix
  glm::vec4 eye{0, 0, 0, 1};           // eye coordinates, for the user clip planes
  // The colour of a back-facing polygon's vertex under two-sided lighting
  // (lit with the reversed normal); the front colour otherwise.
  glm::vec4 back_color{0, 0, 0, 0};
  float fog = 0;  // fog coordinate, |z_eye| (ScreenVertex::fog)
};

// Clips a convex polygon against -w <= x, y, z <= w (and w > 0), one plane
// after the other (Sutherland-Hodgman), interpolating every attribute
// linearly in clip space. Returns the clipped polygon (empty if outside).
std::vector<ClipVertex> clip_polygon(const std::vector<ClipVertex>& polygon);

// True if every vertex is inside the view volume (no clipping needed).
bool inside_view_volume(const ClipVertex& v);

// User clip planes (glClipPlanef, GL ES 1.1 section 2.11), in eye
// coordinates: a vertex is inside plane p when dot(p, eye) >= 0. The driver
// offers MAX_USER_CLIP_PLANES of them (the profile asks for at least one).
inline constexpr unsigned MAX_USER_CLIP_PLANES = 6;

// GL_ALIASED_POINT_SIZE_RANGE (and the smooth one, and the line widths):
// the sizes a point is clamped to after distance attenuation.
inline constexpr float MIN_POINT_SIZE = 1, MAX_POINT_SIZE = 64;

// As clip_polygon, then against each of `user_planes` (eye space) in turn,
// interpolating the eye coordinates with the other attributes. With no
// user planes it is clip_polygon.
std::vector<ClipVertex> clip_polygon(const std::vector<ClipVertex>& polygon, const std::vector<glm::vec4>& user_planes);

// Clip-space planes (a vertex is inside when dot(plane, position) >= 0),
// at most four: the screen's edges when a viewport reaches past them.
struct ClipSpacePlanes {
  glm::vec4 plane[4];
  unsigned count = 0;
};

// True if the vertex is inside every one of `planes`.
bool inside_clip_space_planes(const ClipVertex& v, const ClipSpacePlanes& planes);

// As clip_polygon with user planes, then against `screen` (clip space).
std::vector<ClipVertex> clip_polygon(const std::vector<ClipVertex>& polygon, const std::vector<glm::vec4>& user_planes,
                                     const ClipSpacePlanes& screen);

// The vertex at t along a -> b (0 at a), every attribute interpolated
// linearly in clip space, as the clipper does.
ClipVertex interpolate(const ClipVertex& a, const ClipVertex& b, float t);

// True if the vertex is inside every one of `user_planes`.
bool inside_user_planes(const ClipVertex& v, const std::vector<glm::vec4>& user_planes);

// Clips the segment a-b (parameters 0 at a, 1 at b) against `user_planes`:
// false if nothing is left, else the parameters of the part inside.
bool clip_segment(const glm::vec4& eye_a, const glm::vec4& eye_b, const std::vector<glm::vec4>& user_planes, float* t0,
                  float* t1);

struct Viewport {
  int x = 0, y = 0, width = 0, height = 0;
  float near_depth = 0.0f, far_depth = 1.0f;  // glDepthRangef
};

// The edges of what the back ends can draw (window x and y from 0 to
// MAX_SCREEN_SIZE, the 9.4 range) that the viewport reaches past, as
// clip-space planes. glViewport may put the viewport partly off the screen
// (a negative x or y, or x + width beyond the screen); the picture is then
// the viewport's, cut at the screen. Empty for a viewport on the screen,
// whose view volume is inside it already.
ClipSpacePlanes screen_planes(const Viewport& viewport);

// A vertex's window coordinates before snapping: pixels, y up, computed in
// single precision from the float clip coordinates as to_screen does (its
// error bound is beside to_window in geometry.cpp).
struct WindowPoint {
  float x = 0, y = 0;
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
inline constexpr float DEGENERATE_HEIGHT = 1.0f / 64;  // pixels

// True when the convex polygon (window coordinates before snapping, fewer
// than three vertices included) has no area in the sense above.
bool is_degenerate(const std::vector<WindowPoint>& polygon);

// True when the snapped triangle's area is so large against its edges that
// the unsnapped triangle cannot be degenerate: a few integer operations
// that spare all but thin triangles the floating-point test on the host.
bool surely_has_area(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c);

// Window coordinates in 9.4 fixed point (rounded to nearest), depth in 0.24,
// colour in 0.8 (rounded to nearest, clamped). Returns false for a vertex
// whose coordinates are not finite or fall outside the 9.4 range (the caller
// drops the triangle).
bool to_screen(const ClipVertex& v, const Viewport& viewport, ScreenVertex* out);

// As to_screen, with `depth_offset` added to the window depth, which is then
// clamped to the depth range (polygon offset).
bool to_screen(const ClipVertex& v, const Viewport& viewport, float depth_offset, ScreenVertex* out);

// The window depth of a clip-space position (glDepthRangef), unclamped.
float window_depth(const glm::vec4& clip, const Viewport& viewport);

// Polygon offset (glPolygonOffset, GL ES 1.1 section 3.5.5) --------------------

// A polygon's vertex in window coordinates with its window depth (before
// snapping), for the depth slope.
struct WindowDepthPoint {
  float x = 0, y = 0, z = 0;
};

// The polygon's maximum depth slope m = max(|dz/dx|, |dz/dy|) in window
// coordinates, from the plane through its vertices (Newell's normal, so any
// convex polygon, clipped or not); 0 for a polygon seen edge-on.
float depth_slope(const std::vector<WindowDepthPoint>& polygon);

// The smallest resolvable difference r of a depth buffer of `depth_bits`
// bits: one step of its unsigned normalised codes, 1 / (2^bits - 1), as
// Mesa takes it (depth_bits 0, no depth buffer, counts as 24).
float minimum_resolvable_depth(unsigned depth_bits);

// o = m * factor + r * units.
float polygon_depth_offset(float slope, float factor, float units, unsigned depth_bits);

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
// clamped to [0, 1]. Alpha is the material's diffuse alpha. Attenuation
// applies to positional lights (w != 0) only; the spot factor to every
// light whose cutoff is not 180, a directional one taking its direction
// as the light's (as Mesa's fixed-function vertex program does). The back colour of two-sided lighting is the
// same call with the normal reversed (ES 1.1 has one material for both
// faces: glMaterial takes only GL_FRONT_AND_BACK).
glm::vec4 light_vertex(const LightingModel& model, const Material& material, const glm::vec4& eye,
                       const glm::vec3& normal);

}  // namespace tessera::gl
