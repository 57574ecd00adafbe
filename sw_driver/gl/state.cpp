// Fragment and framebuffer state: enables, clears, viewport, depth, stencil,
// blending, masks, culling, hints, point/line sizes, point parameters and
// sprites, polygon offset, fog and clip planes.
#include "gl/context.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "common/screen_size.h"
#include "gl/context_internal.h"
#include "gl/frame_phases.h"
#include "gl/runtime.h"

namespace tessera::gl {

void Context::enable(GLenum cap, bool on) {
  charge_call();
  if (cap >= GL_LIGHT0 && cap < GL_LIGHT0 + MAX_LIGHTS) {
    m_lighting.model.lights[cap - GL_LIGHT0].enabled = on;
    return;
  }
  if (cap >= GL_CLIP_PLANE0 && cap < GL_CLIP_PLANE0 + MAX_USER_CLIP_PLANES) {
    m_enabled.clip_plane[cap - GL_CLIP_PLANE0] = on;
    return;
  }
  switch (cap) {
    case GL_DEPTH_TEST: m_enabled.depth_test = on; break;
    case GL_BLEND: m_enabled.blend = on; break;
    case GL_ALPHA_TEST: m_enabled.alpha_test = on; break;
    case GL_STENCIL_TEST: m_enabled.stencil_test = on; break;
    case GL_SCISSOR_TEST: m_enabled.scissor_test = on; break;
    case GL_COLOR_LOGIC_OP: m_enabled.logic_op = on; break;
    case GL_TEXTURE_2D: active_unit().enabled = on; break;
    case GL_DITHER: m_enabled.dither = on; break;
    case GL_CULL_FACE: m_enabled.cull = on; break;
    case GL_LIGHTING: m_enabled.lighting = on; break;
    case GL_NORMALIZE: m_enabled.normalize = on; break;
    case GL_RESCALE_NORMAL: m_enabled.rescale_normal = on; break;
    case GL_COLOR_MATERIAL: m_enabled.color_material = on; break;
    case GL_FOG: m_enabled.fog = on; break;
    case GL_MULTISAMPLE: m_enabled.multisample = on; break;
    case GL_POLYGON_OFFSET_FILL: m_enabled.polygon_offset_fill = on; break;
    case GL_SAMPLE_ALPHA_TO_COVERAGE: m_enabled.sample_alpha_to_coverage = on; break;
    case GL_SAMPLE_ALPHA_TO_ONE: m_enabled.sample_alpha_to_one = on; break;
    case GL_SAMPLE_COVERAGE: m_enabled.sample_coverage = on; break;
    case GL_POINT_SMOOTH: m_enabled.point_smooth = on; break;
    case GL_LINE_SMOOTH: m_enabled.line_smooth = on; break;
    case GL_POINT_SPRITE_OES: m_rasterization.point_sprite = on; break;
    case 0x0B41: m_enabled.polygon_smooth = on; break;  // GL_POLYGON_SMOOTH (desktop GL), for antialiased polygons
    default: error(GL_INVALID_ENUM);
  }
}

bool Context::is_enabled(GLenum cap) {
  charge_call();
  if (cap >= GL_LIGHT0 && cap < GL_LIGHT0 + MAX_LIGHTS) return m_lighting.model.lights[cap - GL_LIGHT0].enabled;
  if (cap >= GL_CLIP_PLANE0 && cap < GL_CLIP_PLANE0 + MAX_USER_CLIP_PLANES)
    return m_enabled.clip_plane[cap - GL_CLIP_PLANE0];
  switch (cap) {
    case GL_DEPTH_TEST: return m_enabled.depth_test;
    case GL_BLEND: return m_enabled.blend;
    case GL_ALPHA_TEST: return m_enabled.alpha_test;
    case GL_STENCIL_TEST: return m_enabled.stencil_test;
    case GL_SCISSOR_TEST: return m_enabled.scissor_test;
    case GL_COLOR_LOGIC_OP: return m_enabled.logic_op;
    case GL_TEXTURE_2D: return active_unit().enabled;
    case GL_DITHER: return m_enabled.dither;
    case GL_CULL_FACE: return m_enabled.cull;
    case GL_LIGHTING: return m_enabled.lighting;
    case GL_NORMALIZE: return m_enabled.normalize;
    case GL_RESCALE_NORMAL: return m_enabled.rescale_normal;
    case GL_COLOR_MATERIAL: return m_enabled.color_material;
    case GL_FOG: return m_enabled.fog;
    case GL_MULTISAMPLE: return m_enabled.multisample;
    case GL_POLYGON_OFFSET_FILL: return m_enabled.polygon_offset_fill;
    case GL_SAMPLE_ALPHA_TO_COVERAGE: return m_enabled.sample_alpha_to_coverage;
    case GL_SAMPLE_ALPHA_TO_ONE: return m_enabled.sample_alpha_to_one;
    case GL_SAMPLE_COVERAGE: return m_enabled.sample_coverage;
    case GL_POINT_SMOOTH: return m_enabled.point_smooth;
    case GL_LINE_SMOOTH: return m_enabled.line_smooth;
    case GL_POINT_SPRITE_OES: return m_rasterization.point_sprite;
    case GL_POINT_SIZE_ARRAY_OES: return m_attributes.point_size_array.enabled;
    case 0x0B41: return m_enabled.polygon_smooth;
    case GL_VERTEX_ARRAY: return m_attributes.vertex_array.enabled;
    case GL_COLOR_ARRAY: return m_attributes.color_array.enabled;
    case GL_NORMAL_ARRAY: return m_attributes.normal_array.enabled;
    case GL_TEXTURE_COORD_ARRAY: return client_unit().texcoord_array.enabled;
    default: error(GL_INVALID_ENUM); return false;
  }
}

void Context::enable_client_state(GLenum array, bool on) {
  charge_call();
  switch (array) {
    case GL_VERTEX_ARRAY: m_attributes.vertex_array.enabled = on; break;
    case GL_COLOR_ARRAY: m_attributes.color_array.enabled = on; break;
    case GL_NORMAL_ARRAY: m_attributes.normal_array.enabled = on; break;
    case GL_TEXTURE_COORD_ARRAY: client_unit().texcoord_array.enabled = on; break;
    case GL_POINT_SIZE_ARRAY_OES: m_attributes.point_size_array.enabled = on; break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::clear_color(float r, float g, float b, float a) {
  charge_call();
  m_clear.color[0] = clamp01(r), m_clear.color[1] = clamp01(g), m_clear.color[2] = clamp01(b),
  m_clear.color[3] = clamp01(a);
}
void Context::clear_depth(float d) {
  charge_call(), m_clear.depth = clamp01(d);
}
void Context::clear_stencil(GLint s) {
  charge_call(), m_clear.stencil = s;
}

void Context::clear(GLbitfield mask) {
  charge_call();
  if (mask & ~(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT)) return error(GL_INVALID_VALUE);
  flush_triangles();
  ClearRequest request;
  request.color = mask & GL_COLOR_BUFFER_BIT;
  request.depth = mask & GL_DEPTH_BUFFER_BIT;
  request.stencil = mask & GL_STENCIL_BUFFER_BIT;
  for (int i = 0; i < 4; ++i) {
    request.rgba[i] = to_unorm8(m_clear.color[i]);
    request.color_mask[i] = m_raster.color_mask[i];
  }
  request.depth_value = to_unorm24(m_clear.depth);
  request.stencil_value = static_cast<uint8_t>(m_clear.stencil);
  request.depth_write = m_raster.depth_write;
  request.stencil_write_mask = m_raster.stencil_write_mask;
  request.scissor_test = m_enabled.scissor_test;
  request.scissor_x = m_raster.scissor_x;
  request.scissor_y = m_raster.scissor_y;
  request.scissor_width = m_raster.scissor_width;
  request.scissor_height = m_raster.scissor_height;
  const PhaseScope phase(Phase::rasterization);
  const ClearScope timed;
  m_renderer->clear(request);
}

void Context::viewport(GLint x, GLint y, GLsizei w, GLsizei h) {
  charge_call();
  if (w < 0 || h < 0) return error(GL_INVALID_VALUE);
  const auto max = static_cast<GLsizei>(MAX_SCREEN_SIZE);  // the 9.4 screen format
  m_viewport.x = x, m_viewport.y = y, m_viewport.width = std::min(w, max), m_viewport.height = std::min(h, max);
}

void Context::depth_range(float n, float f) {
  charge_call();
  m_viewport.near_depth = clamp01(n), m_viewport.far_depth = clamp01(f);
}

void Context::scissor(GLint x, GLint y, GLsizei w, GLsizei h) {
  charge_call();
  if (w < 0 || h < 0) return error(GL_INVALID_VALUE);
  m_raster.scissor_x = x, m_raster.scissor_y = y, m_raster.scissor_width = w, m_raster.scissor_height = h;
}

void Context::depth_func(GLenum func) {
  charge_call();
  if (!compare_func(func, &m_raster.depth_func)) error(GL_INVALID_ENUM);
}
void Context::depth_mask(bool flag) {
  charge_call(), m_raster.depth_write = flag;
}

void Context::alpha_func(GLenum func, float ref) {
  charge_call();
  if (!compare_func(func, &m_raster.alpha_func)) return error(GL_INVALID_ENUM);
  m_references.alpha = clamp01(ref);
  m_raster.alpha_ref = to_unorm8(m_references.alpha);
}

void Context::stencil_func(GLenum func, GLint ref, GLuint mask) {
  charge_call();
  if (!compare_func(func, &m_raster.stencil_func)) return error(GL_INVALID_ENUM);
  m_references.stencil = ref;
  m_raster.stencil_ref = static_cast<uint8_t>(std::clamp(ref, 0, 255));
  m_raster.stencil_value_mask = static_cast<uint8_t>(mask);
}

void Context::stencil_op(GLenum fail, GLenum zfail, GLenum zpass) {
  charge_call();
  StencilOp a, b, c;
  if (!stencil_op_value(fail, &a) || !stencil_op_value(zfail, &b) || !stencil_op_value(zpass, &c))
    return error(GL_INVALID_ENUM);
  m_raster.stencil_fail = a, m_raster.depth_fail = b, m_raster.depth_pass = c;
}

void Context::stencil_mask(GLuint mask) {
  charge_call(), m_raster.stencil_write_mask = static_cast<uint8_t>(mask);
}

void Context::blend_func(GLenum src, GLenum dst) {
  charge_call();
  BlendFactor s, d;
  if (!blend_factor(src, true, &s) || !blend_factor(dst, false, &d)) return error(GL_INVALID_ENUM);
  m_raster.blend_src = s, m_raster.blend_dst = d;
}

void Context::logic_op(GLenum op) {
  charge_call();
  if (!logic_op_value(op, &m_raster.logic_op_mode)) error(GL_INVALID_ENUM);
}

void Context::color_mask(bool r, bool g, bool b, bool a) {
  charge_call();
  m_raster.color_mask[0] = r, m_raster.color_mask[1] = g, m_raster.color_mask[2] = b, m_raster.color_mask[3] = a;
}

void Context::shade_model(GLenum mode) {
  charge_call();
  if (mode != GL_FLAT && mode != GL_SMOOTH) return error(GL_INVALID_ENUM);
  m_primitive.shade_model = mode;
}

void Context::cull_face(GLenum mode) {
  charge_call();
  if (mode != GL_FRONT && mode != GL_BACK && mode != GL_FRONT_AND_BACK) return error(GL_INVALID_ENUM);
  m_primitive.cull_mode = mode;
}

void Context::front_face(GLenum mode) {
  charge_call();
  if (mode != GL_CW && mode != GL_CCW) return error(GL_INVALID_ENUM);
  m_primitive.front_face = mode;
}

void Context::hint(GLenum target, GLenum mode) {
  charge_call();
  if (mode != GL_FASTEST && mode != GL_NICEST && mode != GL_DONT_CARE) return error(GL_INVALID_ENUM);
  switch (target) {
    case GL_PERSPECTIVE_CORRECTION_HINT:
    case GL_POINT_SMOOTH_HINT:
    case GL_LINE_SMOOTH_HINT:
    case GL_FOG_HINT:
    case GL_GENERATE_MIPMAP_HINT: m_hints[target] = mode; break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::point_size(float size) {
  charge_call();
  if (!(size > 0)) return error(GL_INVALID_VALUE);
  m_rasterization.point_size = size;
}

void Context::line_width(float width) {
  charge_call();
  if (!(width > 0)) return error(GL_INVALID_VALUE);
  m_rasterization.line_width = width;
}

void Context::polygon_offset(float factor, float units) {
  charge_call();
  m_rasterization.polygon_offset[0] = factor, m_rasterization.polygon_offset[1] = units;
}

void Context::point_parameter(GLenum name, const float* v, int count) {
  charge_call();
  switch (name) {
    case GL_POINT_SIZE_MIN:
    case GL_POINT_SIZE_MAX:
    case GL_POINT_FADE_THRESHOLD_SIZE:
      if (!(v[0] >= 0)) return error(GL_INVALID_VALUE);
      (name == GL_POINT_SIZE_MIN   ? m_rasterization.point_size_min
       : name == GL_POINT_SIZE_MAX ? m_rasterization.point_size_max
                                   : m_rasterization.point_fade_threshold) = v[0];
      break;
    case GL_POINT_DISTANCE_ATTENUATION:
      // Only through the vector form (glPointParameterf takes one value).
      if (count < 3) return error(GL_INVALID_ENUM);
      if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) return error(GL_INVALID_VALUE);
      m_rasterization.point_distance_attenuation = {v[0], v[1], v[2]};
      break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::point_sprite_env(GLenum name, const float* v) {
  charge_call();
  if (name != GL_COORD_REPLACE_OES) return error(GL_INVALID_ENUM);
  // GL_TRUE or GL_FALSE only, as Mesa checks it.
  if (v[0] != GL_TRUE && v[0] != GL_FALSE) return error(GL_INVALID_VALUE);
  active_unit().coord_replace = v[0] == GL_TRUE;  // per texture unit
}

void Context::get_point_sprite_env(GLenum name, float* v) {
  charge_call();
  if (name != GL_COORD_REPLACE_OES) return error(GL_INVALID_ENUM);
  v[0] = active_unit().coord_replace ? 1.0f : 0.0f;
}

void Context::pixel_store(GLenum name, GLint value) {
  charge_call();
  if (name != GL_PACK_ALIGNMENT && name != GL_UNPACK_ALIGNMENT) return error(GL_INVALID_ENUM);
  if (value != 1 && value != 2 && value != 4 && value != 8) return error(GL_INVALID_VALUE);
  (name == GL_PACK_ALIGNMENT ? m_pixel_store.pack_alignment : m_pixel_store.unpack_alignment) = value;
}

void Context::sample_coverage(float value, bool invert) {
  charge_call();
  m_coverage.value = clamp01(value), m_coverage.invert = invert;
}

void Context::fog(GLenum name, const float* values, int count) {
  charge_call();
  switch (name) {
    case GL_FOG_MODE: {
      const GLenum mode = enum_from_float(values[0]).value_or(0u);  // 0 is no mode
      if (mode != GL_LINEAR && mode != GL_EXP && mode != GL_EXP2) return error(GL_INVALID_ENUM);
      m_fog.mode = mode;
      break;
    }
    case GL_FOG_DENSITY:
      if (values[0] < 0) return error(GL_INVALID_VALUE);
      m_fog.density = values[0];
      break;
    case GL_FOG_START: m_fog.start = values[0]; break;
    case GL_FOG_END: m_fog.end = values[0]; break;
    case GL_FOG_COLOR:
      if (count < 4) return error(GL_INVALID_ENUM);
      for (int i = 0; i < 4; ++i) m_fog.color[i] = clamp01(values[i]);
      break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::clip_plane(GLenum plane, const float* equation) {
  charge_call();
  if (plane < GL_CLIP_PLANE0 || plane >= GL_CLIP_PLANE0 + MAX_USER_CLIP_PLANES) return error(GL_INVALID_ENUM);
  const glm::vec4 e(equation[0], equation[1], equation[2], equation[3]);
  m_clip.planes[plane - GL_CLIP_PLANE0] = e * glm::inverse(m_transform.modelview.back());
}

void Context::get_clip_plane(GLenum plane, float* equation) {
  charge_call();
  if (plane < GL_CLIP_PLANE0 || plane >= GL_CLIP_PLANE0 + MAX_USER_CLIP_PLANES) return error(GL_INVALID_ENUM);
  const glm::vec4& e = m_clip.planes[plane - GL_CLIP_PLANE0];
  for (int i = 0; i < 4; ++i) equation[i] = e[i];
}

}  // namespace tessera::gl
