// Primitive assembly: points, lines and triangles from the transformed
// vertices, clipping, viewport and culling, the batches handed to the back
// end, and the calls that complete drawing (read_pixels, flush, finish).
#include "gl/context.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "common/little_endian.h"
#include "gl/context_internal.h"
#include "gl/frame_phases.h"
#include "gl/runtime.h"

namespace tessera::gl {

void Context::emit_triangle(const Vertex& a, const Vertex& b, const Vertex& c, const glm::vec4* flat_color,
                            Primitive primitive, const glm::vec4* flat_back_color) {
  if (!a.valid || !b.valid || !c.valid) return;  // non-finite vertices: dropped
  const bool polygon_rules = primitive == Primitive::polygon;
  // The polygon and its screen vertices live in scratch vectors of the
  // context, so a triangle that needs no clipping allocates nothing.
  std::vector<ClipVertex>& polygon = m_scratch_polygon;
  polygon.assign({a.clip, b.clip, c.clip});
  if (flat_color)
    for (auto& v : polygon) v.color = *flat_color;
  if (flat_back_color)
    for (auto& v : polygon) v.back_color = *flat_back_color;
  // Points and lines met the user clip planes before they became triangles.
  static const std::vector<glm::vec4> no_planes;
  const std::vector<glm::vec4>& user_planes = polygon_rules ? m_clip.enabled_user_planes : no_planes;
  bool inside = inside_view_volume(a.clip) && inside_view_volume(b.clip) && inside_view_volume(c.clip);
  if (!user_planes.empty()) {
    charge(costs::HostCost::gl_clip_plane_test, 3 * user_planes.size());
    inside = inside && inside_user_planes(a.clip, user_planes) && inside_user_planes(b.clip, user_planes) &&
             inside_user_planes(c.clip, user_planes);
  }
  // A viewport partly off the screen: its picture is cut at the screen.
  const ClipSpacePlanes screen_edges = screen_planes(m_viewport);
  if (screen_edges.count > 0) {
    charge(costs::HostCost::gl_clip_plane_test, 3 * screen_edges.count);
    inside = inside && inside_clip_space_planes(a.clip, screen_edges) &&
             inside_clip_space_planes(b.clip, screen_edges) && inside_clip_space_planes(c.clip, screen_edges);
  }
  if (!inside) {
    polygon = clip_polygon(polygon, user_planes, screen_edges);
    charge(costs::HostCost::gl_clipped_vertex, polygon.size());
    if (polygon.size() < 3) return;
  }
  std::vector<ScreenVertex>& screen = m_scratch_screen;
  screen.assign(polygon.size(), ScreenVertex{});
  for (size_t i = 0; i < polygon.size(); ++i)
    if (!to_screen(polygon[i], m_viewport, &screen[i])) return;
  charge(costs::HostCost::gl_screen_vertex, polygon.size());
  // Orientation from the whole polygon, so that clipping cannot flip a face.
  int64_t area = 0;
  for (size_t i = 1; i + 1 < screen.size(); ++i) area += signed_area(screen[0], screen[i], screen[i + 1]);
  charge(costs::HostCost::gl_primitive);
  // Whether the polygon has any area is decided before snapping, which
  // would turn collinear vertices into a sliver (geometry.h); an integer
  // bound settles it for every triangle but the thin ones.
  if (screen.size() != 3 || !surely_has_area(screen[0], screen[1], screen[2])) {
    std::vector<WindowPoint> window(polygon.size());
    for (size_t i = 0; i < polygon.size(); ++i)
      if (!to_window(polygon[i].position, m_viewport, &window[i])) return;
    charge(costs::HostCost::gl_degeneracy_test);
    if (is_degenerate(window)) return;
  }
  if (area == 0) return;  // a thin polygon whose vertices snapped onto one line
  const bool front = (area > 0) == (m_primitive.front_face == GL_CCW);
  // Culling, two-sided lighting and polygon offset concern polygons only:
  // a point or a line is two triangles here, but neither faces anywhere.
  if (polygon_rules) {
    if (m_enabled.cull && (m_primitive.cull_mode == GL_FRONT_AND_BACK || (m_primitive.cull_mode == GL_BACK) != front))
      return;
    if (!front && two_sided_lighting()) {
      for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::vec4& back = polygon[i].back_color;
        screen[i].r = to_unorm8(back.r), screen[i].g = to_unorm8(back.g), screen[i].b = to_unorm8(back.b);
        screen[i].a = to_unorm8(back.a);
      }
      charge(costs::HostCost::gl_two_sided_vertex, polygon.size());
    }
    if (m_enabled.polygon_offset_fill &&
        (m_rasterization.polygon_offset[0] != 0 || m_rasterization.polygon_offset[1] != 0))
      if (!apply_polygon_offset(polygon, screen)) return;
  }
  for (size_t i = 1; i + 1 < screen.size(); ++i) {
    // The provoking vertex (flat shading) is the last one: keep the
    // triangle's original last vertex last.
    Triangle t{{screen[0], screen[i], screen[i + 1]}};
    if (signed_area(t.v[0], t.v[1], t.v[2]) == 0) continue;
    m_batch.push_back(t);
  }
  if (m_batch.size() >= BATCH_TRIANGLES) flush_triangles();
}

bool Context::apply_polygon_offset(const std::vector<ClipVertex>& polygon, std::vector<ScreenVertex>& screen) {
  // The offset is constant over the polygon (GL ES 1.1 section 3.5.5), so
  // adding it to each vertex's window depth before the back end
  // interpolates gives every fragment the same offset depth.
  std::vector<WindowDepthPoint> points(polygon.size());
  for (size_t i = 0; i < polygon.size(); ++i) {
    WindowPoint w;
    if (!to_window(polygon[i].position, m_viewport, &w)) return false;
    points[i] = {w.x, w.y, window_depth(polygon[i].position, m_viewport)};
  }
  const float offset = polygon_depth_offset(depth_slope(points), m_rasterization.polygon_offset[0],
                                            m_rasterization.polygon_offset[1], m_renderer->capabilities().depth_bits);
  for (size_t i = 0; i < polygon.size(); ++i) {
    ScreenVertex shifted;
    if (!to_screen(polygon[i], m_viewport, offset, &shifted)) return false;
    screen[i].z = shifted.z;
  }
  charge(costs::HostCost::gl_polygon_offset_vertex, polygon.size());
  return true;
}

const std::vector<glm::vec4>& Context::enabled_user_planes() {
  m_clip.enabled_user_planes.clear();
  for (size_t i = 0; i < m_clip.planes.size(); ++i)
    if (m_enabled.clip_plane[i]) m_clip.enabled_user_planes.push_back(m_clip.planes[i]);
  return m_clip.enabled_user_planes;
}

float Context::derived_point_size(uint32_t index, const glm::vec4& eye) {
  float size = m_rasterization.point_size;
  if (m_attributes.point_size_array.enabled)
    size = read_attribute(m_attributes.point_size_array, index, {1, 0, 0, 1}).x;
  const glm::vec3& a = m_rasterization.point_distance_attenuation;
  if (a != glm::vec3(1, 0, 0)) {
    // d: the eye-coordinate distance from the eye, (0, 0, 0, 1).
    const float d = glm::length(glm::vec3(eye) / (eye.w != 0 ? eye.w : 1.0f));
    size *= std::sqrt(1.0f / (a.x + a.y * d + a.z * d * d));
    charge(costs::HostCost::gl_point_attenuation);
  }
  // Clamped to GL_POINT_SIZE_MIN/MAX, then to the sizes the driver draws.
  // A size that is not a number stays one, and the point is dropped.
  size = std::min(std::max(size, m_rasterization.point_size_min), m_rasterization.point_size_max);
  return std::min(std::max(size, MIN_POINT_SIZE), MAX_POINT_SIZE);
}

RasterState Context::raster_state() const {
  RasterState s = m_raster;
  s.flat_shading = m_primitive.shade_model == GL_FLAT;
  s.depth_test = m_enabled.depth_test;
  s.alpha_test = m_enabled.alpha_test;
  s.stencil_test = m_enabled.stencil_test;
  s.blend = m_enabled.blend;
  s.logic_op = m_enabled.logic_op;
  s.scissor_test = m_enabled.scissor_test;
  s.polygon_smooth = m_enabled.polygon_smooth;
  for (unsigned u = 0; u < MAX_TEXTURE_UNITS; ++u) {
    TextureUnit& unit = s.unit[u];
    unit.enabled = unit_textured(u);
    if (unit.enabled) unit.tex = drawn_texture(m_texture.objects.at(m_texture.units[u].bound));
    set_unit_environment(m_texture.units[u], &unit);
  }
  s.fog = m_enabled.fog;
  s.fog_mode = from_gl_enum<FogMode>(m_fog.mode).value_or(FogMode::exp);
  s.fog_density = m_fog.density;
  s.fog_start = m_fog.start;
  s.fog_end = m_fog.end;
  for (int i = 0; i < 4; ++i) s.fog_color[i] = to_unorm8(m_fog.color[i]);
  return s;
}

void Context::flush_triangles() {
  if (m_batch.empty()) return;
  const PhaseScope phase(Phase::rasterization);
  m_renderer->draw(raster_state(), m_batch.data(), m_batch.size());
  m_batch.clear();
}

void Context::emit_quad(const glm::vec2 corners[4], const Vertex& source, const glm::vec2* tex) {
  // Points become two triangles in window space; the corners are turned
  // back into clip coordinates with the source vertex's w so that the
  // normal path (clipping, viewport) applies. `tex`, if given, replaces the
  // texture coordinates corner by corner (point sprites) in each unit whose
  // GL_COORD_REPLACE_OES is on.
  charge(costs::HostCost::gl_quad);
  const glm::vec4& p = source.clip.position;
  Vertex v[4];
  for (int i = 0; i < 4; ++i) {
    v[i] = source;
    const float xn = (corners[i].x - m_viewport.x) * 2.0f / m_viewport.width - 1.0f;
    const float yn = (corners[i].y - m_viewport.y) * 2.0f / m_viewport.height - 1.0f;
    v[i].clip.position = {xn * p.w, yn * p.w, p.z, p.w};
    if (tex)
      for (unsigned u = 0; u < MAX_TEXTURE_UNITS; ++u)
        if (m_texture.units[u].coord_replace) v[i].clip.tex[u] = tex[i];
  }
  emit_triangle(v[0], v[1], v[2], nullptr, Primitive::point_or_line);
  emit_triangle(v[0], v[2], v[3], nullptr, Primitive::point_or_line);
}

void Context::draw(GLenum mode, const std::vector<uint32_t>& indices, bool indexed) {
  if (!m_attributes.vertex_array.enabled) return;  // nothing to draw without positions
  const PhaseScope phase(Phase::geometry);
  // A frame's first draw costs the ISS more than the later ones
  // (docs/calibration.md, "A frame's first draw"); on the ISS both are nothing.
  if (costs::units_since_taken(costs::HostCost::gl_draw) == 0) charge(costs::HostCost::gl_draw_first);
  charge(costs::HostCost::gl_draw);
  fetch_and_transform(indices, indexed, m_vertices);
  enabled_user_planes();
  const std::vector<glm::vec4>& user_planes = m_clip.enabled_user_planes;
  const std::vector<Vertex>& v = m_vertices;
  const size_t n = v.size();
  const bool flat = m_primitive.shade_model == GL_FLAT;
  auto triangle = [&](size_t a, size_t b, size_t c, size_t provoking) {
    const glm::vec4 color = v[provoking].clip.color, back_color = v[provoking].clip.back_color;
    emit_triangle(v[a], v[b], v[c], flat ? &color : nullptr, Primitive::polygon, flat ? &back_color : nullptr);
  };
  auto window = [&](const Vertex& x) {
    const glm::vec4& p = x.clip.position;
    return glm::vec2((p.x / p.w + 1) * m_viewport.width * 0.5f + m_viewport.x,
                     (p.y / p.w + 1) * m_viewport.height * 0.5f + m_viewport.y);
  };
  auto line = [&](size_t a, size_t b) {
    if (!v[a].valid || !v[b].valid) return;
    Vertex va = v[a], vb = v[b];
    if (flat) va.clip.color = vb.clip.color;
    if (!user_planes.empty()) {
      // The segment is clipped by the user planes before it is widened.
      float t0 = 0, t1 = 1;
      charge(costs::HostCost::gl_clip_plane_test, 2 * user_planes.size());
      if (!clip_segment(va.clip.eye, vb.clip.eye, user_planes, &t0, &t1)) return;
      const ClipVertex ca = va.clip, cb = vb.clip;
      if (t0 > 0) va.clip = interpolate(ca, cb, t0);
      if (t1 < 1) vb.clip = interpolate(ca, cb, t1);
      va.eye = va.clip.eye, vb.eye = vb.clip.eye;
    }
    if (!(va.clip.position.w > 0) || !(vb.clip.position.w > 0)) return;
    glm::vec2 pa = window(va), pb = window(vb);
    const glm::vec2 d = pb - pa;
    const float length = glm::length(d);
    if (!(length > 0)) return;
    // An aliased wide line (ES 1.1 section 3.4.2): each column of an
    // x-major line (each row of a y-major one) gets a span of the width,
    // centred on the line: a parallelogram whose short sides are vertical
    // (horizontal), not a rectangle. Placed as Mesa places it (its draw
    // module's wide lines, which softpipe draws): the whole line moved by
    // half a pixel back along its major axis, against the direction it is
    // drawn in, and by 1/8 pixel across it (up in x-major lines, right in
    // y-major ones), so that its pixels are those of GL's diamond-exit
    // rule at the ends.
    const float half_width = m_rasterization.line_width * 0.5f;
    const bool x_major = std::fabs(d.x) >= std::fabs(d.y);
    const glm::vec2 side = x_major ? glm::vec2(0, half_width) : glm::vec2(half_width, 0);
    constexpr float ACROSS = 0.125f, ALONG = 0.5f;
    const glm::vec2 shift =
        x_major ? glm::vec2(d.x > 0 ? -ALONG : ALONG, ACROSS) : glm::vec2(ACROSS, d.y > 0 ? -ALONG : ALONG);
    pa += shift, pb += shift;
    // A quad along the segment: two triangles, each end keeps its attributes.
    Vertex q[4] = {va, vb, vb, va};
    const glm::vec2 corners[4] = {pa - side, pb - side, pb + side, pa + side};
    for (int i = 0; i < 4; ++i) {
      const glm::vec4& p = q[i].clip.position;
      q[i].clip.position = {((corners[i].x - m_viewport.x) * 2.0f / m_viewport.width - 1.0f) * p.w,
                            ((corners[i].y - m_viewport.y) * 2.0f / m_viewport.height - 1.0f) * p.w, p.z, p.w};
    }
    emit_triangle(q[0], q[1], q[2], nullptr, Primitive::point_or_line);
    emit_triangle(q[0], q[2], q[3], nullptr, Primitive::point_or_line);
  };
  switch (mode) {
    case GL_TRIANGLES:
      for (size_t i = 0; i + 2 < n; i += 3) triangle(i, i + 1, i + 2, i + 2);
      break;
    case GL_TRIANGLE_STRIP:
      for (size_t i = 0; i + 2 < n; ++i) {
        if (i % 2 == 0)
          triangle(i, i + 1, i + 2, i + 2);
        else
          triangle(i + 1, i, i + 2, i + 2);
      }
      break;
    case GL_TRIANGLE_FAN:
      for (size_t i = 1; i + 1 < n; ++i) triangle(0, i, i + 1, i + 1);
      break;
    case GL_POINTS: {
      // Point sprites (OES_point_sprite) with GL_COORD_REPLACE_OES: s runs
      // 0 to 1 from the point's left to its right, t 0 to 1 from its top to
      // its bottom (y is up here), as the extension's formulas and Mesa give.
      static constexpr glm::vec2 SPRITE_TEX[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
      const glm::vec2* sprite_tex = m_rasterization.point_sprite ? SPRITE_TEX : nullptr;
      for (size_t i = 0; i < n; ++i) {
        if (!v[i].valid || !(v[i].clip.position.w > 0)) continue;
        // A point outside a user clip plane is discarded whole.
        if (!user_planes.empty()) {
          charge(costs::HostCost::gl_clip_plane_test, user_planes.size());
          if (!inside_user_planes(v[i].clip, user_planes)) continue;
        }
        float size = derived_point_size(indices[i], v[i].eye);
        if (!(size > 0)) continue;
        const glm::vec2 c = window(v[i]);
        float left = c.x - size * 0.5f, bottom = c.y - size * 0.5f;
        if (!m_rasterization.point_sprite) {
          // An aliased point (ES 1.1 section 3.3.1) is a square of whole
          // pixels on the pixel grid. Placed as Mesa's softpipe places it,
          // which is GL's rule (the square centred on the pixel centre or
          // corner nearest the point's) with a quarter-pixel bias: its
          // size truncated to whole pixels, its left column
          // floor(x + 3/4 - size / 2) and its top row, counted down from
          // the top, floor(y_down + 1/4 - size / 2).
          const float whole = std::max(1.0f, std::floor(size));
          left = std::floor(c.x + 0.75f - size * 0.5f);
          bottom = std::ceil(c.y + size * 0.5f - 0.25f) - whole;
          size = whole;
        }
        const float right = left + size, top = bottom + size;
        const glm::vec2 corners[4] = {{left, bottom}, {right, bottom}, {right, top}, {left, top}};
        emit_quad(corners, v[i], sprite_tex);
      }
      break;
    }
    case GL_LINES:
      for (size_t i = 0; i + 1 < n; i += 2) line(i, i + 1);
      break;
    case GL_LINE_STRIP:
      for (size_t i = 0; i + 1 < n; ++i) line(i, i + 1);
      break;
    case GL_LINE_LOOP:
      for (size_t i = 0; i + 1 < n; ++i) line(i, i + 1);
      if (n > 1) line(n - 1, 0);
      break;
  }
  flush_triangles();
}

void Context::draw_arrays(GLenum mode, GLint first, GLsizei count) {
  charge_call();
  if (mode > GL_TRIANGLE_FAN) return error(GL_INVALID_ENUM);
  if (count < 0 || first < 0) return error(GL_INVALID_VALUE);
  std::vector<uint32_t> indices(static_cast<size_t>(count));
  // In 32 unsigned bits: first + i overflows a GLint when first is near INT_MAX.
  for (GLsizei i = 0; i < count; ++i) indices[i] = static_cast<uint32_t>(first) + static_cast<uint32_t>(i);
  draw(mode, indices, false);
}

void Context::draw_elements(GLenum mode, GLsizei count, GLenum type, const void* pointer) {
  charge_call();
  if (mode > GL_TRIANGLE_FAN) return error(GL_INVALID_ENUM);
  if (type != GL_UNSIGNED_BYTE && type != GL_UNSIGNED_SHORT) return error(GL_INVALID_ENUM);
  if (count < 0) return error(GL_INVALID_VALUE);
  const uint8_t* base = static_cast<const uint8_t*>(pointer);
  const size_t size = type == GL_UNSIGNED_BYTE ? 1 : 2;
  if (m_buffer.element) {
    const BufferObject& b = m_buffer.objects[m_buffer.element];
    const size_t offset = reinterpret_cast<size_t>(pointer);
    if (offset > b.data.size() || size * static_cast<size_t>(count) > b.data.size() - offset)
      return error(GL_INVALID_OPERATION);
    base = b.data.data() + offset;
  } else if (!pointer && count > 0) {
    return error(GL_INVALID_VALUE);
  }
  std::vector<uint32_t> indices(static_cast<size_t>(count));
  for (GLsizei i = 0; i < count; ++i) {
    if (size == 1)
      indices[i] = base[i];
    else
      indices[i] = load_le16(base + 2 * i);
  }
  charge(costs::HostCost::gl_index, static_cast<uint64_t>(count));
  draw(mode, indices, true);
}

void Context::read_pixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum format, GLenum type, void* pixels) {
  charge_call();
  if (w < 0 || h < 0) return error(GL_INVALID_VALUE);
  if (format != GL_RGBA || type != GL_UNSIGNED_BYTE) {
    if ((format != GL_RGBA && format != GL_RGB && format != GL_ALPHA && format != GL_LUMINANCE &&
         format != GL_LUMINANCE_ALPHA) ||
        (type != GL_UNSIGNED_BYTE && type != GL_UNSIGNED_SHORT_5_6_5 && type != GL_UNSIGNED_SHORT_4_4_4_4 &&
         type != GL_UNSIGNED_SHORT_5_5_5_1))
      return error(GL_INVALID_ENUM);
    return error(GL_INVALID_OPERATION);  // only the required RGBA / UNSIGNED_BYTE pair is implemented
  }
  if (w == 0 || h == 0) return;
  flush_triangles();
  const size_t row = static_cast<size_t>(w) * 4;
  const size_t stride =
      (row + m_pixel_store.pack_alignment - 1) / m_pixel_store.pack_alignment * m_pixel_store.pack_alignment;
  // A rectangle reaching past INT_MAX (x = INT_MAX) lies outside any window,
  // where GL leaves the values undefined: they are 0, as the renderers give
  // for pixels outside, without handing the renderer an x + w that overflows.
  if (!fits(std::max(x, 0), w, INT_MAX) || !fits(std::max(y, 0), h, INT_MAX)) {
    for (GLsizei j = 0; j < h; ++j) std::memset(static_cast<uint8_t*>(pixels) + j * stride, 0, row);
    return;
  }
  std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4, 0);
  {
    const PhaseScope phase(Phase::rasterization);
    m_renderer->read_pixels(x, y, w, h, rgba.data());
  }
  for (GLsizei j = 0; j < h; ++j) std::memcpy(static_cast<uint8_t*>(pixels) + j * stride, rgba.data() + j * row, row);
}

void Context::flush() {
  charge_call();
  flush_triangles();
}

void Context::finish() {
  charge_call();
  flush_triangles();
  const PhaseScope phase(Phase::rasterization);
  m_renderer->finish();
}

}  // namespace tessera::gl
