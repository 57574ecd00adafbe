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

#include "gl/context_internal.h"
#include "gl/runtime.h"

namespace tessera::gl {

void Context::emit_triangle(const Vertex& a, const Vertex& b, const Vertex& c, const glm::vec4* flat_color) {
  if (!a.valid || !b.valid || !c.valid) return;  // non-finite vertices: dropped
  std::vector<ClipVertex> polygon = {a.clip, b.clip, c.clip};
  if (flat_color)
    for (auto& v : polygon) v.color = *flat_color;
  const bool inside = inside_view_volume(a.clip) && inside_view_volume(b.clip) && inside_view_volume(c.clip);
  if (!inside) {
    polygon = clip_polygon(polygon);
    charge({12, 12, 1, 0, 7, 0, 0}, polygon.size());
    if (polygon.size() < 3) return;
  }
  std::vector<ScreenVertex> screen(polygon.size());
  for (size_t i = 0; i < polygon.size(); ++i)
    if (!to_screen(polygon[i], m_viewport, &screen[i])) return;
  charge(screen_cost(), polygon.size());
  // Orientation from the whole polygon, so that clipping cannot flip a face.
  int64_t area = 0;
  for (size_t i = 1; i + 1 < screen.size(); ++i) area += signed_area(screen[0], screen[i], screen[i + 1]);
  m_host.compute(Op::alu, 12 + SURELY_HAS_AREA_ALU);
  // Whether the polygon has any area is decided before snapping, which
  // would turn collinear vertices into a sliver (geometry.h); an integer
  // bound settles it for every triangle but the thin ones.
  if (screen.size() != 3 || !surely_has_area(screen[0], screen[1], screen[2])) {
    std::vector<WindowPoint> window(polygon.size());
    for (size_t i = 0; i < polygon.size(); ++i)
      if (!to_window(polygon[i].position, m_viewport, &window[i])) return;
    charge(degeneracy_cost(window.size()), 1);
    if (is_degenerate(window)) return;
  }
  if (area == 0) return;  // a thin polygon whose vertices snapped onto one line
  const bool front = (area > 0) == (m_front_face == GL_CCW);
  if (m_cull && (m_cull_mode == GL_FRONT_AND_BACK || (m_cull_mode == GL_BACK) != front)) return;
  for (size_t i = 1; i + 1 < screen.size(); ++i) {
    // The provoking vertex (flat shading) is the last one: keep the
    // triangle's original last vertex last.
    Triangle t{{screen[0], screen[i], screen[i + 1]}};
    if (signed_area(t.v[0], t.v[1], t.v[2]) == 0) continue;
    m_batch.push_back(t);
  }
  if (m_batch.size() >= BATCH_TRIANGLES) flush_triangles();
}

RasterState Context::raster_state() const {
  RasterState s = m_raster;
  s.flat_shading = m_shade_model == GL_FLAT;
  s.depth_test = m_depth_test;
  s.alpha_test = m_alpha_test;
  s.stencil_test = m_stencil_test;
  s.blend = m_blend;
  s.logic_op = m_logic_op;
  s.scissor_test = m_scissor_test;
  s.polygon_smooth = m_polygon_smooth;
  for (unsigned u = 0; u < MAX_TEXTURE_UNITS; ++u) {
    TextureUnit& unit = s.unit[u];
    unit.enabled = unit_textured(u);
    if (unit.enabled) unit.tex = m_textures.at(m_units[u].bound).texture;
    set_unit_environment(m_units[u], &unit);
  }
  return s;
}

void Context::flush_triangles() {
  if (m_batch.empty()) return;
  m_renderer->draw(raster_state(), m_batch.data(), m_batch.size());
  m_batch.clear();
}

void Context::emit_quad(const glm::vec2 corners[4], const Vertex& source, float, float) {
  // Points and lines become two triangles in window space; the corners are
  // turned back into clip coordinates with the source vertex's w so that the
  // normal path (clipping, viewport) applies.
  const glm::vec4& p = source.clip.position;
  Vertex v[4];
  for (int i = 0; i < 4; ++i) {
    v[i] = source;
    const float xn = (corners[i].x - m_viewport.x) * 2.0f / m_viewport.width - 1.0f;
    const float yn = (corners[i].y - m_viewport.y) * 2.0f / m_viewport.height - 1.0f;
    v[i].clip.position = {xn * p.w, yn * p.w, p.z, p.w};
  }
  emit_triangle(v[0], v[1], v[2], nullptr);
  emit_triangle(v[0], v[2], v[3], nullptr);
}

void Context::draw(GLenum mode, const std::vector<uint32_t>& indices, bool indexed) {
  if (!m_vertex_array.enabled) return;  // nothing to draw without positions
  fetch_and_transform(indices, indexed, m_vertices);
  const std::vector<Vertex>& v = m_vertices;
  const size_t n = v.size();
  const bool flat = m_shade_model == GL_FLAT;
  auto triangle = [&](size_t a, size_t b, size_t c, size_t provoking) {
    const glm::vec4 color = v[provoking].clip.color;
    emit_triangle(v[a], v[b], v[c], flat ? &color : nullptr);
  };
  auto window = [&](const Vertex& x) {
    const glm::vec4& p = x.clip.position;
    return glm::vec2((p.x / p.w + 1) * m_viewport.width * 0.5f + m_viewport.x,
                     (p.y / p.w + 1) * m_viewport.height * 0.5f + m_viewport.y);
  };
  auto line = [&](size_t a, size_t b) {
    if (!v[a].valid || !v[b].valid || !(v[a].clip.position.w > 0) || !(v[b].clip.position.w > 0)) return;
    const glm::vec2 pa = window(v[a]), pb = window(v[b]);
    glm::vec2 d = pb - pa;
    const float length = glm::length(d);
    if (!(length > 0)) return;
    const glm::vec2 side = glm::vec2(-d.y, d.x) / length * (m_line_width * 0.5f);
    Vertex va = v[a], vb = v[b];
    if (flat) va.clip.color = vb.clip.color;
    // A quad along the segment: two triangles, each end keeps its attributes.
    Vertex q[4] = {va, vb, vb, va};
    const glm::vec2 corners[4] = {pa - side, pb - side, pb + side, pa + side};
    for (int i = 0; i < 4; ++i) {
      const glm::vec4& p = q[i].clip.position;
      q[i].clip.position = {((corners[i].x - m_viewport.x) * 2.0f / m_viewport.width - 1.0f) * p.w,
                            ((corners[i].y - m_viewport.y) * 2.0f / m_viewport.height - 1.0f) * p.w, p.z, p.w};
    }
    emit_triangle(q[0], q[1], q[2], nullptr);
    emit_triangle(q[0], q[2], q[3], nullptr);
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
    case GL_POINTS:
      for (size_t i = 0; i < n; ++i) {
        if (!v[i].valid || !(v[i].clip.position.w > 0)) continue;
        const glm::vec2 c = window(v[i]);
        const float h = m_point_size * 0.5f;
        const glm::vec2 corners[4] = {{c.x - h, c.y - h}, {c.x + h, c.y - h}, {c.x + h, c.y + h}, {c.x - h, c.y + h}};
        emit_quad(corners, v[i], 0, 0);
      }
      break;
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
  if (m_element_buffer) {
    const BufferObject& b = m_buffers[m_element_buffer];
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
    else {
      uint16_t x;
      std::memcpy(&x, base + 2 * i, 2);
      indices[i] = x;
    }
  }
  m_host.compute(Op::alu, 2ull * static_cast<uint64_t>(count));
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
  const size_t stride = (row + m_pack_alignment - 1) / m_pack_alignment * m_pack_alignment;
  // A rectangle reaching past INT_MAX (x = INT_MAX) lies outside any window,
  // where GL leaves the values undefined: they are 0, as the renderers give
  // for pixels outside, without handing the renderer an x + w that overflows.
  if (!fits(std::max(x, 0), w, INT_MAX) || !fits(std::max(y, 0), h, INT_MAX)) {
    for (GLsizei j = 0; j < h; ++j) std::memset(static_cast<uint8_t*>(pixels) + j * stride, 0, row);
    return;
  }
  std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4, 0);
  m_renderer->read_pixels(x, y, w, h, rgba.data());
  for (GLsizei j = 0; j < h; ++j) std::memcpy(static_cast<uint8_t*>(pixels) + j * stride, rgba.data() + j * row, row);
}

void Context::flush() {
  charge_call();
  flush_triangles();
}

void Context::finish() {
  charge_call();
  flush_triangles();
  m_renderer->finish();
}

}  // namespace tessera::gl
