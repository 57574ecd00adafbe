#include "gl/geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace tessera::gl {

namespace {

// Signed distance-like value of v from clip plane `plane` (>= 0: inside).
float plane_value(const glm::vec4& p, int plane) {
  switch (plane) {
    case 0: return p.w + p.x;     // left
    case 1: return p.w - p.x;     // right
    case 2: return p.w + p.y;     // bottom
    case 3: return p.w - p.y;     // top
    case 4: return p.w + p.z;     // near
    case 5: return p.w - p.z;     // far
    default: return p.w - 1e-6f;  // w > 0: keeps the perspective division finite
  }
}

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, float t) {
  ClipVertex v = a;
  v.position = a.position + (b.position - a.position) * t;
  v.color = a.color + (b.color - a.color) * t;
  for (unsigned u = 0; u < MAX_TEXTURE_UNITS; ++u) v.tex[u] = a.tex[u] + (b.tex[u] - a.tex[u]) * t;
  v.eye = a.eye + (b.eye - a.eye) * t;
  v.back_color = a.back_color + (b.back_color - a.back_color) * t;
  v.fog = a.fog + (b.fog - a.fog) * t;
  return v;
}

// One Sutherland-Hodgman pass against the plane whose signed value at a
// vertex `distance` gives (>= 0: inside).
template <typename Distance>
void clip_against(std::vector<ClipVertex>& current, std::vector<ClipVertex>& next, Distance distance) {
  next.clear();
  for (size_t i = 0; i < current.size(); ++i) {
    const ClipVertex& a = current[i];
    const ClipVertex& b = current[(i + 1) % current.size()];
    const float da = distance(a);
    const float db = distance(b);
    if (da >= 0) next.push_back(a);
    // An edge crossing the plane contributes its intersection; computing t
    // from the inside end keeps shared edges of neighbours identical.
    if ((da >= 0) != (db >= 0)) {
      if (da >= 0)
        next.push_back(lerp(a, b, da / (da - db)));
      else
        next.push_back(lerp(b, a, db / (db - da)));
    }
  }
  current.swap(next);
}

}  // namespace

bool inside_view_volume(const ClipVertex& v) {
  for (int plane = 0; plane < 7; ++plane)
    if (!(plane_value(v.position, plane) >= 0)) return false;
  return true;
}

std::vector<ClipVertex> clip_polygon(const std::vector<ClipVertex>& polygon) {
  return clip_polygon(polygon, {});
}

std::vector<ClipVertex> clip_polygon(const std::vector<ClipVertex>& polygon,
                                     const std::vector<glm::vec4>& user_planes) {
  return clip_polygon(polygon, user_planes, ClipSpacePlanes{});
}

std::vector<ClipVertex> clip_polygon(const std::vector<ClipVertex>& polygon, const std::vector<glm::vec4>& user_planes,
                                     const ClipSpacePlanes& screen) {
  std::vector<ClipVertex> current = polygon, next;
  for (int plane = 0; plane < 7 && !current.empty(); ++plane)
    clip_against(current, next, [plane](const ClipVertex& v) { return plane_value(v.position, plane); });
  for (const glm::vec4& plane : user_planes) {
    if (current.empty()) break;
    clip_against(current, next, [&plane](const ClipVertex& v) { return glm::dot(plane, v.eye); });
  }
  for (unsigned i = 0; i < screen.count && !current.empty(); ++i) {
    const glm::vec4& plane = screen.plane[i];
    clip_against(current, next, [&plane](const ClipVertex& v) { return glm::dot(plane, v.position); });
  }
  if (current.size() < 3) current.clear();
  return current;
}

ClipSpacePlanes screen_planes(const Viewport& viewport) {
  // Window x = (x_c / w_c + 1) W / 2 + x0, so x >= 0 is
  // x_c + (1 + 2 x0 / W) w_c >= 0 and x <= S is (2 (S - x0) / W - 1) w_c - x_c >= 0
  // (w_c > 0 inside the view volume); y alike.
  // Each w coefficient is one float division of integers computed exactly
  // in 64 bits (x0 is any GLint, W at most MAX_SCREEN_SIZE): (W + 2 x0) / W
  // and (2 (S - x0) - W) / W.
  ClipSpacePlanes planes;
  if (viewport.width <= 0 || viewport.height <= 0) return planes;
  const int64_t s = MAX_SCREEN_SIZE;
  const int64_t x = viewport.x, y = viewport.y, w = viewport.width, h = viewport.height;
  const auto ratio = [](int64_t numerator, int64_t denominator) {
    return static_cast<float>(numerator) / static_cast<float>(denominator);
  };
  if (x < 0) planes.plane[planes.count++] = {1, 0, 0, ratio(w + 2 * x, w)};
  if (x + w > s) planes.plane[planes.count++] = {-1, 0, 0, ratio(2 * (s - x) - w, w)};
  if (y < 0) planes.plane[planes.count++] = {0, 1, 0, ratio(h + 2 * y, h)};
  if (y + h > s) planes.plane[planes.count++] = {0, -1, 0, ratio(2 * (s - y) - h, h)};
  return planes;
}

bool inside_clip_space_planes(const ClipVertex& v, const ClipSpacePlanes& planes) {
  for (unsigned i = 0; i < planes.count; ++i)
    if (!(glm::dot(planes.plane[i], v.position) >= 0)) return false;
  return true;
}

ClipVertex interpolate(const ClipVertex& a, const ClipVertex& b, float t) {
  return lerp(a, b, t);
}

bool inside_user_planes(const ClipVertex& v, const std::vector<glm::vec4>& user_planes) {
  for (const glm::vec4& plane : user_planes)
    if (!(glm::dot(plane, v.eye) >= 0)) return false;
  return true;
}

bool clip_segment(const glm::vec4& eye_a, const glm::vec4& eye_b, const std::vector<glm::vec4>& user_planes, float* t0,
                  float* t1) {
  float start = 0, end = 1;
  for (const glm::vec4& plane : user_planes) {
    const float da = glm::dot(plane, eye_a), db = glm::dot(plane, eye_b);
    const bool a_in = da >= 0, b_in = db >= 0;
    if (!a_in && !b_in) return false;
    if (a_in && b_in) continue;
    const float t = da / (da - db);  // where the value crosses 0
    if (a_in)
      end = std::min(end, t);
    else
      start = std::max(start, t);
    if (!(start <= end)) return false;
  }
  *t0 = start, *t1 = end;
  return true;
}

uint8_t to_unorm8(float value) {
  if (!(value > 0)) return 0;
  if (value >= 1) return 255;
  return static_cast<uint8_t>(std::lround(value * 255.0f));
}

// value * (2^24 - 1) rounded to nearest, half away from zero, exactly in
// integers: value = m 2^(e - 24) with a 24-bit integer m and e <= 0, so the
// product is m (2^24 - 1) (below 2^48) shifted right by 24 - e.
uint32_t to_unorm24(float value) {
  constexpr uint32_t MAX = (1u << 24) - 1;
  if (!(value > 0)) return 0;
  if (value >= 1) return MAX;
  int exponent = 0;
  const float fraction = std::frexp(value, &exponent);                  // [0.5, 1)
  const auto mantissa = static_cast<uint64_t>(fraction * 16777216.0f);  // exact: a power of two
  const int shift = 24 - exponent;
  if (shift >= 64) return 0;  // below 2^-40: rounds to 0
  return static_cast<uint32_t>((mantissa * MAX + (uint64_t{1} << (shift - 1))) >> shift);
}

// Single precision, as Mesa's viewport transform: x_w = x_c (1 / w_c) W/2 +
// (x0 + W/2), with W/2 and x0 + W/2 exact (W <= 512; an x0 beyond 2^24,
// which float rounds, puts the viewport far off the screen, where
// to_screen rejects the vertex). For a vertex inside the view volume
// (|x_c / w_c| <= 1) the error is a few float steps of the result: below
// 1e-4 pixel up to 512, against the 1/16 pixel of the 9.4 step
// (Viewport.FloatWindowCoordinatesAtTheExtremes).
namespace {

bool window_point(const glm::vec4& p, float inv_w, const Viewport& viewport, WindowPoint* out) {
  const float half_width = static_cast<float>(viewport.width) * 0.5f;
  const float half_height = static_cast<float>(viewport.height) * 0.5f;
  out->x = p.x * inv_w * half_width + (static_cast<float>(viewport.x) + half_width);
  out->y = p.y * inv_w * half_height + (static_cast<float>(viewport.y) + half_height);
  return std::isfinite(out->x) && std::isfinite(out->y);
}

bool is_valid_clip_position(const glm::vec4& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w) && p.w > 0;
}

}  // namespace

bool to_window(const glm::vec4& p, const Viewport& viewport, WindowPoint* out) {
  return is_valid_clip_position(p) && window_point(p, 1.0f / p.w, viewport, out);
}

// In single precision. The vertices passed to_screen's range check, so each
// coordinate lies in [-1/32, 512 + 1/32]. Relative to the first vertex a
// triangle's coordinate differences are at most its longest edge L (<= 725
// on a 512x512 screen), so the twice area's rounding error is a few float
// steps of L^2, below 2^-21 L^2: a height error below 2^-21 L < 4e-4 pixel,
// 2 % of DEGENERATE_HEIGHT; the window coordinates add 1e-4 pixel per
// vertex. The test then differs from an exact one only for triangles whose
// height is within 1e-3 pixel of DEGENERATE_HEIGHT, which snapping to 1/16
// pixel moves by far more (Degeneracy.SliversAtTheThresholdOnA512PixelScreen).
// The squares stay below 2^40, far inside float's range.
bool is_degenerate(const std::vector<WindowPoint>& polygon) {
  if (polygon.size() < 3) return true;
  const WindowPoint& origin = polygon[0];
  float twice_area = 0, longest_squared = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const WindowPoint& a = polygon[i];
    const WindowPoint& b = polygon[(i + 1) % polygon.size()];
    const float dx = b.x - a.x, dy = b.y - a.y;
    longest_squared = std::max(longest_squared, dx * dx + dy * dy);
    if (i > 0 && i + 1 < polygon.size())
      twice_area += (a.x - origin.x) * (b.y - origin.y) - (b.x - origin.x) * (a.y - origin.y);
  }
  // height = |twice_area| / longest <= DEGENERATE_HEIGHT, without the square root.
  return twice_area * twice_area <= DEGENERATE_HEIGHT * DEGENERATE_HEIGHT * longest_squared;
}

// In units of 1/16 pixel: snapping moves each vertex by at most 1/2 in x and
// in y, so each snapped edge e' = e + d with |d|max <= 1. The unsnapped twice
// area T = cross(e1' - d1, e2' - d2) differs from the snapped T' by at most
// |e1'|1 + |e2'|1 + 2 (|cross(u, v)| <= |u|1 |v|max). The unsnapped
// triangle is degenerate when |T| <= H L with H = 1/64 pixel = 1/4 unit and
// L its longest edge, at most max |e'|1 + 2 <= |e1'|1 + |e2'|1 + 2. So
// 4 |T'| > 5 (|e1'|1 + |e2'|1) + 10 rules degeneracy out.
bool surely_has_area(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c) {
  const int64_t twice_area = std::llabs(signed_area(a, b, c));
  const int64_t edges = std::llabs(int64_t{b.x} - a.x) + std::llabs(int64_t{b.y} - a.y) +
                        std::llabs(int64_t{c.x} - a.x) + std::llabs(int64_t{c.y} - a.y);
  static_assert(DEGENERATE_HEIGHT * (1 << SUBPIXEL_BITS) == 0.25f, "the bound assumes H = 1/4 of a 9.4 unit");
  return 4 * twice_area > 5 * edges + 10;
}

namespace {

// A window coordinate in 9.4 codes, rounded to nearest (half to even, as
// nearbyint), in integers: false unless the code is in [0, 2^13], that is
// the window coordinate in [-1/32, 512 + 1/32] (NaN fails too). Times 16 is
// exact in float, and so is the fraction below: the 9.4 code of a float
// window coordinate is exact. The far edge of a 512-pixel screen, 512.0
// (code 8192, one past 9.4), becomes 511 15/16: the last pixel centres are
// at 511.5, so only the edges through such a vertex move, by at most 1/16
// pixel at the vertex (snapping moves every vertex by up to 1/32). Without
// it a full-width or full-height triangle on a 512-pixel screen would be
// dropped.
bool screen_coordinate(float window, int32_t* code) {
  constexpr float HALF = 0.5f;
  constexpr auto LIMIT = static_cast<float>(MAX_SCREEN_COORDINATE + 1);  // 8192, exact
  const float scaled = window * (1 << SUBPIXEL_BITS);
  if (!(scaled >= -HALF && scaled <= LIMIT + HALF)) return false;
  int32_t rounded = static_cast<int32_t>(scaled);               // towards zero: 0 for [-1/2, 0)
  const float fraction = scaled - static_cast<float>(rounded);  // exact
  if (fraction > HALF || (fraction == HALF && (rounded & 1))) ++rounded;
  *code = std::min(rounded, MAX_SCREEN_COORDINATE);
  return true;
}

// The viewport's depth transform in Mesa's form, z_w = z_c (1 / w_c) (f - n)/2
// + (f + n)/2, in single precision: for z_w in [1/2, 1] a float step is
// 2^-24, one code of the 24-bit depth buffer, so the result is within a
// code or two of the exact depth (Mesa's own float pipeline is no closer).
float window_depth(float z, float inv_w, const Viewport& viewport) {
  const float scale = (viewport.far_depth - viewport.near_depth) * 0.5f;
  const float translate = (viewport.far_depth + viewport.near_depth) * 0.5f;
  return z * inv_w * scale + translate;
}

}  // namespace

float window_depth(const glm::vec4& p, const Viewport& viewport) {
  return window_depth(p.z, 1.0f / p.w, viewport);
}

bool to_screen(const ClipVertex& v, const Viewport& viewport, ScreenVertex* out) {
  const glm::vec4& p = v.position;
  if (!is_valid_clip_position(p)) return false;
  const float inv_w = 1.0f / p.w;
  WindowPoint window;
  if (!window_point(p, inv_w, viewport, &window)) return false;
  int32_t x = 0, y = 0;
  if (!screen_coordinate(window.x, &x) || !screen_coordinate(window.y, &y)) return false;
  out->x = x;
  out->y = y;
  out->z = to_unorm24(window_depth(p.z, inv_w, viewport));
  out->inv_w = inv_w;
  out->r = to_unorm8(v.color.r);
  out->g = to_unorm8(v.color.g);
  out->b = to_unorm8(v.color.b);
  out->a = to_unorm8(v.color.a);
  bool finite = std::isfinite(v.fog);
  for (unsigned u = 0; u < MAX_TEXTURE_UNITS; ++u) {
    out->tex[u] = {v.tex[u].x, v.tex[u].y};
    finite = finite && std::isfinite(v.tex[u].x) && std::isfinite(v.tex[u].y);
  }
  out->fog = v.fog;
  out->x_window = window.x;
  out->y_window = window.y;
  return finite;
}

bool to_screen(const ClipVertex& v, const Viewport& viewport, float depth_offset, ScreenVertex* out) {
  if (!to_screen(v, viewport, out)) return false;
  if (depth_offset == 0) return true;
  const float low = std::min(viewport.near_depth, viewport.far_depth);
  const float high = std::max(viewport.near_depth, viewport.far_depth);
  const float z = std::clamp(window_depth(v.position, viewport) + depth_offset, low, high);
  if (!std::isfinite(z)) return false;
  out->z = to_unorm24(z);
  return true;
}

float depth_slope(const std::vector<WindowDepthPoint>& polygon) {
  // Newell's normal (nx, ny, nz) of the polygon's plane; on the plane
  // nx dx + ny dy + nz dz = 0, so dz/dx = -nx / nz and dz/dy = -ny / nz.
  // Single precision, relative to the first vertex: nz is twice the area
  // from products of coordinate differences (at most the polygon's extent),
  // not of coordinates up to 512, so its rounding error is a few float
  // steps of the extent squared, as in is_degenerate; a polygon thin enough
  // for that to matter (height near 1/64 pixel over 725) has a slope
  // uncertain by about 1 % from its float window coordinates already.
  if (polygon.empty()) return 0;
  const WindowDepthPoint& origin = polygon[0];
  float nx = 0, ny = 0, nz = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const WindowDepthPoint& p = polygon[i];
    const WindowDepthPoint& q = polygon[(i + 1) % polygon.size()];
    const float ax = p.x - origin.x, ay = p.y - origin.y, az = p.z - origin.z;
    const float bx = q.x - origin.x, by = q.y - origin.y, bz = q.z - origin.z;
    nx += (ay - by) * (az + bz);
    ny += (az - bz) * (ax + bx);
    nz += (ax - bx) * (ay + by);
  }
  if (!(std::fabs(nz) > 0)) return 0;
  const float slope = std::max(std::fabs(nx / nz), std::fabs(ny / nz));
  return std::isfinite(slope) ? slope : 0;
}

float minimum_resolvable_depth(unsigned depth_bits) {
  // 2^bits - 1 is exact in float up to 24 bits; 32 bits round it to 2^32.
  const unsigned bits = depth_bits == 0 ? 24 : std::min(depth_bits, 32u);
  return 1.0f / (std::ldexp(1.0f, static_cast<int>(bits)) - 1.0f);
}

float polygon_depth_offset(float slope, float factor, float units, unsigned depth_bits) {
  return slope * factor + minimum_resolvable_depth(depth_bits) * units;
}

int64_t signed_area(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c) {
  return static_cast<int64_t>(b.x - a.x) * (c.y - a.y) - static_cast<int64_t>(c.x - a.x) * (b.y - a.y);
}

glm::vec4 light_vertex(const LightingModel& model, const Material& material, const glm::vec4& eye,
                       const glm::vec3& normal) {
  glm::vec3 color = glm::vec3(material.emission) + glm::vec3(material.ambient) * glm::vec3(model.ambient);
  const glm::vec3 position = glm::vec3(eye) / (eye.w != 0 ? eye.w : 1.0f);
  for (const Light& light : model.lights) {
    if (!light.enabled) continue;
    glm::vec3 to_light;
    float attenuation = 1;
    if (light.position.w != 0) {
      const glm::vec3 light_position = glm::vec3(light.position) / light.position.w;
      to_light = light_position - position;
      const float distance = glm::length(to_light);
      attenuation = 1.0f / (light.constant_attenuation + light.linear_attenuation * distance +
                            light.quadratic_attenuation * distance * distance);
      to_light = distance > 0 ? to_light / distance : glm::vec3(0, 0, 1);
    } else {
      to_light = glm::normalize(glm::vec3(light.position));
    }
    float spot = 1;
    if (light.spot_cutoff != 180) {
      const float cos_angle = glm::dot(-to_light, glm::normalize(light.spot_direction));
      const float cos_cutoff = std::cos(glm::radians(light.spot_cutoff));
      spot = cos_angle < cos_cutoff ? 0.0f : std::pow(std::max(cos_angle, 0.0f), light.spot_exponent);
    }
    const float n_dot_l = glm::dot(normal, to_light);
    glm::vec3 term = glm::vec3(material.ambient) * glm::vec3(light.ambient);
    if (n_dot_l > 0) {
      term += n_dot_l * glm::vec3(material.diffuse) * glm::vec3(light.diffuse);
      // Infinite viewer (ES 1.1 has no local viewer): the eye direction is +z.
      const glm::vec3 half = glm::normalize(to_light + glm::vec3(0, 0, 1));
      const float n_dot_h = glm::dot(normal, half);
      if (n_dot_h > 0) {
        const float power = material.shininess == 0 ? 1.0f : std::pow(n_dot_h, material.shininess);
        term += power * glm::vec3(material.specular) * glm::vec3(light.specular);
      }
    }
    color += attenuation * spot * term;
  }
  color = glm::clamp(color, glm::vec3(0), glm::vec3(1));
  return {color, std::clamp(material.diffuse.a, 0.0f, 1.0f)};
}

}  // namespace tessera::gl
