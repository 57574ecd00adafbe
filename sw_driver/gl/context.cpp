#include "gl/context.h"

#include "gl/runtime.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace tessera::gl {

namespace {

Context* g_current = nullptr;

constexpr size_t MAX_MODELVIEW_DEPTH = 16;
constexpr size_t MAX_PROJECTION_DEPTH = 2;
constexpr size_t MAX_TEXTURE_DEPTH = 2;
constexpr unsigned MAX_LIGHTS = 8;
constexpr GLsizei MAX_TEXTURE_SIZE = 256;
constexpr size_t BATCH_TRIANGLES = 256;

bool compare_func(GLenum func, CompareFunc* out) {
  if (func < GL_NEVER || func > GL_ALWAYS) return false;
  *out = static_cast<CompareFunc>(func - GL_NEVER);
  return true;
}

bool stencil_op_value(GLenum op, StencilOp* out) {
  switch (op) {
    case GL_KEEP: *out = StencilOp::keep; return true;
    case GL_ZERO: *out = StencilOp::zero; return true;
    case GL_REPLACE: *out = StencilOp::replace; return true;
    case GL_INCR: *out = StencilOp::incr; return true;
    case GL_DECR: *out = StencilOp::decr; return true;
    case GL_INVERT: *out = StencilOp::invert; return true;
    default: return false;
  }
}

bool blend_factor(GLenum factor, bool source, BlendFactor* out) {
  switch (factor) {
    case GL_ZERO: *out = BlendFactor::zero; return true;
    case GL_ONE: *out = BlendFactor::one; return true;
    case GL_SRC_COLOR: *out = BlendFactor::src_color; return !source;
    case GL_ONE_MINUS_SRC_COLOR: *out = BlendFactor::one_minus_src_color; return !source;
    case GL_DST_COLOR: *out = BlendFactor::dst_color; return source;
    case GL_ONE_MINUS_DST_COLOR: *out = BlendFactor::one_minus_dst_color; return source;
    case GL_SRC_ALPHA: *out = BlendFactor::src_alpha; return true;
    case GL_ONE_MINUS_SRC_ALPHA: *out = BlendFactor::one_minus_src_alpha; return true;
    case GL_DST_ALPHA: *out = BlendFactor::dst_alpha; return true;
    case GL_ONE_MINUS_DST_ALPHA: *out = BlendFactor::one_minus_dst_alpha; return true;
    case GL_SRC_ALPHA_SATURATE: *out = BlendFactor::src_alpha_saturate; return source;
    default: return false;
  }
}

float clamp01(float v) {
  return std::clamp(v, 0.0f, 1.0f);
}

size_t type_size(GLenum type) {
  switch (type) {
    case GL_BYTE:
    case GL_UNSIGNED_BYTE: return 1;
    case GL_SHORT:
    case GL_UNSIGNED_SHORT: return 2;
    case GL_FLOAT:
    case GL_FIXED: return 4;
    default: return 0;
  }
}

bool is_power_of_two(GLsizei v) {
  return v > 0 && (v & (v - 1)) == 0;
}

}  // namespace

Context* current_context() {
  return g_current;
}
void set_current_context(Context* context) {
  g_current = context;
}

Context::Context(HostApi& host, Renderer& renderer) : m_host(host), m_renderer(&renderer) {
  m_viewport.width = static_cast<int>(m_renderer->width());
  m_viewport.height = static_cast<int>(m_renderer->height());
  m_raster.scissor_width = m_viewport.width;
  m_raster.scissor_height = m_viewport.height;
  m_lighting_model.lights.resize(MAX_LIGHTS);
  m_lighting_model.lights[0].diffuse = glm::vec4(1);
  m_lighting_model.lights[0].specular = glm::vec4(1);
}

void Context::error(GLenum code) {
  if (m_error == GL_NO_ERROR) m_error = code;
}

GLenum Context::get_error() {
  const GLenum e = m_error;
  m_error = GL_NO_ERROR;
  return e;
}

void Context::charge_call(unsigned alu) {
  m_host.compute(Op::call);
  m_host.compute(Op::alu, alu);
}

void Context::charge(const FloatCost& cost, uint64_t times) {
  if (times == 0) return;
  if (cost.add) m_host.compute(Op::fadd, cost.add * times);
  if (cost.mul) m_host.compute(Op::fmul, cost.mul * times);
  if (cost.div) m_host.compute(Op::fdiv, cost.div * times);
  if (cost.sqrt) m_host.compute(Op::fsqrt, cost.sqrt * times);
  if (cost.cmp) m_host.compute(Op::fcmp, cost.cmp * times);
  if (cost.conv) m_host.compute(Op::fconv, cost.conv * times);
  if (cost.calls) m_host.compute(Op::call, cost.calls * times);
}

// ---------------------------------------------------------------- state

void Context::enable(GLenum cap, bool on) {
  charge_call();
  if (cap >= GL_LIGHT0 && cap < GL_LIGHT0 + MAX_LIGHTS) {
    m_lighting_model.lights[cap - GL_LIGHT0].enabled = on;
    return;
  }
  if (cap >= GL_CLIP_PLANE0 && cap < GL_CLIP_PLANE0 + 6) {
    m_clip_plane_enabled[cap - GL_CLIP_PLANE0] = on;
    return;
  }
  switch (cap) {
    case GL_DEPTH_TEST: m_depth_test = on; break;
    case GL_BLEND: m_blend = on; break;
    case GL_ALPHA_TEST: m_alpha_test = on; break;
    case GL_STENCIL_TEST: m_stencil_test = on; break;
    case GL_SCISSOR_TEST: m_scissor_test = on; break;
    case GL_COLOR_LOGIC_OP: m_logic_op = on; break;
    case GL_TEXTURE_2D: m_texture_2d = on; break;
    case GL_DITHER: m_dither = on; break;
    case GL_CULL_FACE: m_cull = on; break;
    case GL_LIGHTING: m_lighting = on; break;
    case GL_NORMALIZE: m_normalize = on; break;
    case GL_RESCALE_NORMAL: m_rescale_normal = on; break;
    case GL_COLOR_MATERIAL: m_color_material = on; break;
    case GL_FOG: m_fog = on; break;
    case GL_MULTISAMPLE: m_multisample = on; break;
    case GL_POLYGON_OFFSET_FILL: m_polygon_offset_fill = on; break;
    case GL_SAMPLE_ALPHA_TO_COVERAGE: m_sample_alpha_to_coverage = on; break;
    case GL_SAMPLE_ALPHA_TO_ONE: m_sample_alpha_to_one = on; break;
    case GL_SAMPLE_COVERAGE: m_sample_coverage = on; break;
    case GL_POINT_SMOOTH: m_point_smooth = on; break;
    case GL_LINE_SMOOTH: m_line_smooth = on; break;
    case 0x0B41: m_polygon_smooth = on; break;  // GL_POLYGON_SMOOTH (desktop GL), for antialiased polygons
    default: error(GL_INVALID_ENUM);
  }
}

bool Context::is_enabled(GLenum cap) {
  charge_call();
  if (cap >= GL_LIGHT0 && cap < GL_LIGHT0 + MAX_LIGHTS) return m_lighting_model.lights[cap - GL_LIGHT0].enabled;
  if (cap >= GL_CLIP_PLANE0 && cap < GL_CLIP_PLANE0 + 6) return m_clip_plane_enabled[cap - GL_CLIP_PLANE0];
  switch (cap) {
    case GL_DEPTH_TEST: return m_depth_test;
    case GL_BLEND: return m_blend;
    case GL_ALPHA_TEST: return m_alpha_test;
    case GL_STENCIL_TEST: return m_stencil_test;
    case GL_SCISSOR_TEST: return m_scissor_test;
    case GL_COLOR_LOGIC_OP: return m_logic_op;
    case GL_TEXTURE_2D: return m_texture_2d;
    case GL_DITHER: return m_dither;
    case GL_CULL_FACE: return m_cull;
    case GL_LIGHTING: return m_lighting;
    case GL_NORMALIZE: return m_normalize;
    case GL_RESCALE_NORMAL: return m_rescale_normal;
    case GL_COLOR_MATERIAL: return m_color_material;
    case GL_FOG: return m_fog;
    case GL_MULTISAMPLE: return m_multisample;
    case GL_POLYGON_OFFSET_FILL: return m_polygon_offset_fill;
    case GL_SAMPLE_ALPHA_TO_COVERAGE: return m_sample_alpha_to_coverage;
    case GL_SAMPLE_ALPHA_TO_ONE: return m_sample_alpha_to_one;
    case GL_SAMPLE_COVERAGE: return m_sample_coverage;
    case GL_POINT_SMOOTH: return m_point_smooth;
    case GL_LINE_SMOOTH: return m_line_smooth;
    case 0x0B41: return m_polygon_smooth;
    case GL_VERTEX_ARRAY: return m_vertex_array.enabled;
    case GL_COLOR_ARRAY: return m_color_array.enabled;
    case GL_NORMAL_ARRAY: return m_normal_array.enabled;
    case GL_TEXTURE_COORD_ARRAY: return m_texcoord_array.enabled;
    default: error(GL_INVALID_ENUM); return false;
  }
}

void Context::enable_client_state(GLenum array, bool on) {
  charge_call();
  switch (array) {
    case GL_VERTEX_ARRAY: m_vertex_array.enabled = on; break;
    case GL_COLOR_ARRAY: m_color_array.enabled = on; break;
    case GL_NORMAL_ARRAY: m_normal_array.enabled = on; break;
    case GL_TEXTURE_COORD_ARRAY:
      if (m_client_active_texture == GL_TEXTURE0) m_texcoord_array.enabled = on;
      break;
    case GL_POINT_SIZE_ARRAY_OES: break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::clear_color(float r, float g, float b, float a) {
  charge_call();
  m_clear_color[0] = clamp01(r), m_clear_color[1] = clamp01(g), m_clear_color[2] = clamp01(b),
  m_clear_color[3] = clamp01(a);
}
void Context::clear_depth(float d) {
  charge_call(), m_clear_depth = clamp01(d);
}
void Context::clear_stencil(GLint s) {
  charge_call(), m_clear_stencil = s;
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
    request.rgba[i] = to_unorm8(m_clear_color[i]);
    request.color_mask[i] = m_raster.color_mask[i];
  }
  request.depth_value = to_unorm24(m_clear_depth);
  request.stencil_value = static_cast<uint8_t>(m_clear_stencil);
  request.depth_write = m_raster.depth_write;
  request.stencil_write_mask = m_raster.stencil_write_mask;
  request.scissor_test = m_scissor_test;
  request.scissor_x = m_raster.scissor_x;
  request.scissor_y = m_raster.scissor_y;
  request.scissor_width = m_raster.scissor_width;
  request.scissor_height = m_raster.scissor_height;
  m_renderer->clear(request);
}

void Context::viewport(GLint x, GLint y, GLsizei w, GLsizei h) {
  charge_call();
  if (w < 0 || h < 0) return error(GL_INVALID_VALUE);
  const GLsizei max = 1 << 9;  // the 9.4 screen format
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
  m_alpha_ref = clamp01(ref);
  m_raster.alpha_ref = to_unorm8(m_alpha_ref);
}

void Context::stencil_func(GLenum func, GLint ref, GLuint mask) {
  charge_call();
  if (!compare_func(func, &m_raster.stencil_func)) return error(GL_INVALID_ENUM);
  m_stencil_ref = ref;
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
  if (op < GL_CLEAR || op > GL_SET) return error(GL_INVALID_ENUM);
  m_raster.logic_op_code = static_cast<uint8_t>(op - GL_CLEAR);
}

void Context::color_mask(bool r, bool g, bool b, bool a) {
  charge_call();
  m_raster.color_mask[0] = r, m_raster.color_mask[1] = g, m_raster.color_mask[2] = b, m_raster.color_mask[3] = a;
}

void Context::shade_model(GLenum mode) {
  charge_call();
  if (mode != GL_FLAT && mode != GL_SMOOTH) return error(GL_INVALID_ENUM);
  m_shade_model = mode;
}

void Context::cull_face(GLenum mode) {
  charge_call();
  if (mode != GL_FRONT && mode != GL_BACK && mode != GL_FRONT_AND_BACK) return error(GL_INVALID_ENUM);
  m_cull_mode = mode;
}

void Context::front_face(GLenum mode) {
  charge_call();
  if (mode != GL_CW && mode != GL_CCW) return error(GL_INVALID_ENUM);
  m_front_face = mode;
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
  m_point_size = size;
}

void Context::line_width(float width) {
  charge_call();
  if (!(width > 0)) return error(GL_INVALID_VALUE);
  m_line_width = width;
}

void Context::polygon_offset(float factor, float units) {
  charge_call();
  m_polygon_offset[0] = factor, m_polygon_offset[1] = units;
}

void Context::pixel_store(GLenum name, GLint value) {
  charge_call();
  if (name != GL_PACK_ALIGNMENT && name != GL_UNPACK_ALIGNMENT) return error(GL_INVALID_ENUM);
  if (value != 1 && value != 2 && value != 4 && value != 8) return error(GL_INVALID_VALUE);
  (name == GL_PACK_ALIGNMENT ? m_pack_alignment : m_unpack_alignment) = value;
}

void Context::sample_coverage(float value, bool invert) {
  charge_call();
  m_sample_coverage_value = clamp01(value), m_sample_coverage_invert = invert;
}

void Context::fog(GLenum name, const float* values, int count) {
  charge_call();
  switch (name) {
    case GL_FOG_MODE: {
      const GLenum mode = static_cast<GLenum>(values[0]);
      if (mode != GL_LINEAR && mode != GL_EXP && mode != GL_EXP2) return error(GL_INVALID_ENUM);
      m_fog_mode = mode;
      break;
    }
    case GL_FOG_DENSITY:
      if (values[0] < 0) return error(GL_INVALID_VALUE);
      m_fog_density = values[0];
      break;
    case GL_FOG_START: m_fog_start = values[0]; break;
    case GL_FOG_END: m_fog_end = values[0]; break;
    case GL_FOG_COLOR:
      if (count < 4) return error(GL_INVALID_ENUM);
      for (int i = 0; i < 4; ++i) m_fog_color[i] = clamp01(values[i]);
      break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::clip_plane(GLenum plane, const float* equation) {
  charge_call();
  if (plane < GL_CLIP_PLANE0 || plane >= GL_CLIP_PLANE0 + 6) return error(GL_INVALID_ENUM);
  const glm::vec4 e(equation[0], equation[1], equation[2], equation[3]);
  m_clip_planes[plane - GL_CLIP_PLANE0] = e * glm::inverse(m_modelview.back());
}

void Context::get_clip_plane(GLenum plane, float* equation) {
  charge_call();
  if (plane < GL_CLIP_PLANE0 || plane >= GL_CLIP_PLANE0 + 6) return error(GL_INVALID_ENUM);
  const glm::vec4& e = m_clip_planes[plane - GL_CLIP_PLANE0];
  for (int i = 0; i < 4; ++i) equation[i] = e[i];
}

// ---------------------------------------------------------------- matrices

void Context::matrix_mode(GLenum mode) {
  charge_call();
  if (mode != GL_MODELVIEW && mode != GL_PROJECTION && mode != GL_TEXTURE) return error(GL_INVALID_ENUM);
  m_matrix_mode = mode;
}

glm::mat4& Context::current_matrix() {
  switch (m_matrix_mode) {
    case GL_PROJECTION: return m_projection.back();
    case GL_TEXTURE: return m_texture_matrix.back();
    default: return m_modelview.back();
  }
}

void Context::load_matrix(const glm::mat4& m) {
  charge_call(16);
  current_matrix() = m;
}

void Context::mult_matrix(const glm::mat4& m) {
  charge_call();
  charge({48, 64, 0, 0, 0, 0, 0}, 1);
  current_matrix() = current_matrix() * m;
}

void Context::push_matrix() {
  charge_call(16);
  auto& stack = m_matrix_mode == GL_PROJECTION ? m_projection
                : m_matrix_mode == GL_TEXTURE  ? m_texture_matrix
                                               : m_modelview;
  const size_t limit = m_matrix_mode == GL_PROJECTION ? MAX_PROJECTION_DEPTH
                       : m_matrix_mode == GL_TEXTURE  ? MAX_TEXTURE_DEPTH
                                                      : MAX_MODELVIEW_DEPTH;
  if (stack.size() >= limit) return error(GL_STACK_OVERFLOW);
  stack.push_back(stack.back());
}

void Context::pop_matrix() {
  charge_call();
  auto& stack = m_matrix_mode == GL_PROJECTION ? m_projection
                : m_matrix_mode == GL_TEXTURE  ? m_texture_matrix
                                               : m_modelview;
  if (stack.size() <= 1) return error(GL_STACK_UNDERFLOW);
  stack.pop_back();
}

void Context::frustum(float l, float r, float b, float t, float n, float f) {
  if (!(n > 0) || !(f > 0) || l == r || b == t || n == f) return charge_call(), error(GL_INVALID_VALUE);
  mult_matrix(glm::frustum(l, r, b, t, n, f));
}

void Context::ortho(float l, float r, float b, float t, float n, float f) {
  if (l == r || b == t || n == f) return charge_call(), error(GL_INVALID_VALUE);
  mult_matrix(glm::ortho(l, r, b, t, n, f));
}

// ---------------------------------------------------------------- attributes

void Context::color(float r, float g, float b, float a) {
  charge_call(4);
  m_color = {r, g, b, a};
}

void Context::normal(float x, float y, float z) {
  charge_call(3);
  m_normal = {x, y, z};
}

void Context::tex_coord(GLenum unit, float s, float t, float r, float q) {
  charge_call(4);
  if (unit < GL_TEXTURE0 || unit > GL_TEXTURE1) return error(GL_INVALID_ENUM);
  if (unit == GL_TEXTURE0) m_texcoord = {s, t, r, q};
}

void Context::array_pointer(ArrayPointer& array, GLint size, GLenum type, GLsizei stride, const void* pointer,
                            bool size_ok, bool type_ok) {
  charge_call(6);
  if (!type_ok) return error(GL_INVALID_ENUM);
  if (!size_ok || stride < 0) return error(GL_INVALID_VALUE);
  if (&array == &m_texcoord_array && m_client_active_texture != GL_TEXTURE0) return;
  array.size = size, array.type = type, array.stride = stride, array.pointer = pointer;
  array.buffer = m_array_buffer;
}

void Context::active_texture(GLenum unit, bool client) {
  charge_call();
  if (unit < GL_TEXTURE0 || unit > GL_TEXTURE1) return error(GL_INVALID_ENUM);
  (client ? m_client_active_texture : m_active_texture) = unit;
}

// ---------------------------------------------------------------- lighting

void Context::light(GLenum which, GLenum name, const float* v, int count) {
  charge_call(8);
  if (which < GL_LIGHT0 || which >= GL_LIGHT0 + MAX_LIGHTS) return error(GL_INVALID_ENUM);
  Light& l = m_lighting_model.lights[which - GL_LIGHT0];
  auto need = [&](int n) {
    if (count < n) error(GL_INVALID_ENUM);
    return count >= n;
  };
  switch (name) {
    case GL_AMBIENT:
      if (need(4)) l.ambient = {v[0], v[1], v[2], v[3]};
      break;
    case GL_DIFFUSE:
      if (need(4)) l.diffuse = {v[0], v[1], v[2], v[3]};
      break;
    case GL_SPECULAR:
      if (need(4)) l.specular = {v[0], v[1], v[2], v[3]};
      break;
    case GL_POSITION:
      if (need(4)) l.position = m_modelview.back() * glm::vec4(v[0], v[1], v[2], v[3]);
      break;
    case GL_SPOT_DIRECTION:
      if (need(3)) l.spot_direction = glm::mat3(m_modelview.back()) * glm::vec3(v[0], v[1], v[2]);
      break;
    case GL_SPOT_EXPONENT:
      if (v[0] < 0 || v[0] > 128) return error(GL_INVALID_VALUE);
      l.spot_exponent = v[0];
      break;
    case GL_SPOT_CUTOFF:
      if ((v[0] < 0 || v[0] > 90) && v[0] != 180) return error(GL_INVALID_VALUE);
      l.spot_cutoff = v[0];
      break;
    case GL_CONSTANT_ATTENUATION:
    case GL_LINEAR_ATTENUATION:
    case GL_QUADRATIC_ATTENUATION:
      if (v[0] < 0) return error(GL_INVALID_VALUE);
      (name == GL_CONSTANT_ATTENUATION ? l.constant_attenuation
       : name == GL_LINEAR_ATTENUATION ? l.linear_attenuation
                                       : l.quadratic_attenuation) = v[0];
      break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::get_light(GLenum which, GLenum name, float* v) {
  charge_call();
  if (which < GL_LIGHT0 || which >= GL_LIGHT0 + MAX_LIGHTS) return error(GL_INVALID_ENUM);
  const Light& l = m_lighting_model.lights[which - GL_LIGHT0];
  auto put = [&](const glm::vec4& x, int n) {
    for (int i = 0; i < n; ++i) v[i] = x[i];
  };
  switch (name) {
    case GL_AMBIENT: put(l.ambient, 4); break;
    case GL_DIFFUSE: put(l.diffuse, 4); break;
    case GL_SPECULAR: put(l.specular, 4); break;
    case GL_POSITION: put(l.position, 4); break;
    case GL_SPOT_DIRECTION: put(glm::vec4(l.spot_direction, 0), 3); break;
    case GL_SPOT_EXPONENT: v[0] = l.spot_exponent; break;
    case GL_SPOT_CUTOFF: v[0] = l.spot_cutoff; break;
    case GL_CONSTANT_ATTENUATION: v[0] = l.constant_attenuation; break;
    case GL_LINEAR_ATTENUATION: v[0] = l.linear_attenuation; break;
    case GL_QUADRATIC_ATTENUATION: v[0] = l.quadratic_attenuation; break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::light_model(GLenum name, const float* v, int count) {
  charge_call();
  switch (name) {
    case GL_LIGHT_MODEL_AMBIENT:
      if (count < 4) return error(GL_INVALID_ENUM);
      m_lighting_model.ambient = {v[0], v[1], v[2], v[3]};
      break;
    case GL_LIGHT_MODEL_TWO_SIDE: m_two_side = v[0] != 0; break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::material(GLenum face, GLenum name, const float* v, int count) {
  charge_call(8);
  // ES 1.1 accepts only GL_FRONT_AND_BACK.
  if (face != GL_FRONT_AND_BACK) return error(GL_INVALID_ENUM);
  Material& m = m_front_material;
  auto rgba = [&](glm::vec4& target) {
    if (count < 4) return error(GL_INVALID_ENUM);
    target = {v[0], v[1], v[2], v[3]};
  };
  switch (name) {
    case GL_AMBIENT: rgba(m.ambient); break;
    case GL_DIFFUSE: rgba(m.diffuse); break;
    case GL_AMBIENT_AND_DIFFUSE: rgba(m.ambient), rgba(m.diffuse); break;
    case GL_SPECULAR: rgba(m.specular); break;
    case GL_EMISSION: rgba(m.emission); break;
    case GL_SHININESS:
      if (v[0] < 0 || v[0] > 128) return error(GL_INVALID_VALUE);
      m.shininess = v[0];
      break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::get_material(GLenum face, GLenum name, float* v) {
  charge_call();
  if (face != GL_FRONT && face != GL_BACK) return error(GL_INVALID_ENUM);
  const Material& m = m_front_material;
  auto put = [&](const glm::vec4& x) {
    for (int i = 0; i < 4; ++i) v[i] = x[i];
  };
  switch (name) {
    case GL_AMBIENT: put(m.ambient); break;
    case GL_DIFFUSE: put(m.diffuse); break;
    case GL_SPECULAR: put(m.specular); break;
    case GL_EMISSION: put(m.emission); break;
    case GL_SHININESS: v[0] = m.shininess; break;
    default: error(GL_INVALID_ENUM);
  }
}

// ---------------------------------------------------------------- textures

void Context::gen_textures(GLsizei n, GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    while (m_textures.count(m_next_texture)) ++m_next_texture;
    names[i] = m_next_texture;
    m_textures[m_next_texture++] = TextureObject{};
  }
}

void Context::delete_textures(GLsizei n, const GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    if (names[i] == 0) continue;
    m_textures.erase(names[i]);  // system memory of the texels is not reused (bump allocator)
    if (m_bound_texture == names[i]) m_bound_texture = 0;
  }
}

void Context::bind_texture(GLenum target, GLuint name) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  if (name != 0 && !m_textures.count(name)) m_textures[name] = TextureObject{};
  m_bound_texture = name;
}

bool Context::is_texture(GLuint name) {
  charge_call();
  return name != 0 && m_textures.count(name) != 0;
}

TextureObject* Context::bound_texture() {
  // Texture object 0 is the default texture, which exists like any other.
  return &m_textures[m_bound_texture];
}

namespace {

// Bytes per pixel of an external format, 0 for a bad combination.
int pixel_bytes(GLenum format, GLenum type, bool* format_ok, bool* type_ok) {
  *format_ok = format == GL_RGBA || format == GL_RGB || format == GL_LUMINANCE || format == GL_ALPHA ||
               format == GL_LUMINANCE_ALPHA;
  *type_ok = type == GL_UNSIGNED_BYTE;
  if (!*format_ok || !*type_ok) return 0;
  switch (format) {
    case GL_RGBA: return 4;
    case GL_RGB: return 3;
    case GL_LUMINANCE_ALPHA: return 2;
    default: return 1;
  }
}

void expand_texel(GLenum format, const uint8_t* in, uint8_t* out) {
  switch (format) {
    case GL_RGBA: std::memcpy(out, in, 4); break;
    case GL_RGB: out[0] = in[0], out[1] = in[1], out[2] = in[2], out[3] = 255; break;
    case GL_LUMINANCE: out[0] = out[1] = out[2] = in[0], out[3] = 255; break;
    case GL_LUMINANCE_ALPHA: out[0] = out[1] = out[2] = in[0], out[3] = in[1]; break;
    case GL_ALPHA: out[0] = out[1] = out[2] = 0, out[3] = in[0]; break;
  }
}

}  // namespace

void Context::tex_image(GLenum target, GLint level, GLint internal_format, GLsizei width, GLsizei height, GLint border,
                        GLenum format, GLenum type, const void* pixels) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  bool format_ok, type_ok;
  pixel_bytes(format, type, &format_ok, &type_ok);
  if (!format_ok || !type_ok) return error(GL_INVALID_ENUM);
  if (level < 0 || border != 0 || width < 0 || height < 0 || width > MAX_TEXTURE_SIZE || height > MAX_TEXTURE_SIZE ||
      (width && !is_power_of_two(width)) || (height && !is_power_of_two(height)))
    return error(GL_INVALID_VALUE);
  if (static_cast<GLenum>(internal_format) != format) return error(GL_INVALID_OPERATION);
  if (level > 0) return;  // mipmap levels are accepted and not used: no mipmapping (documented)
  TextureObject* object = bound_texture();
  const uint32_t texel_bytes = static_cast<uint32_t>(width) * height * 4;
  if (texel_bytes == 0) {
    object->defined = false;
    return;
  }
  // Stored as RGBA8 in system memory, where every back end fetches it.
  if (object->texture.width != static_cast<unsigned>(width) ||
      object->texture.height != static_cast<unsigned>(height) || object->texture.address == 0)
    object->texture.address = allocate(texel_bytes);
  object->texture.width = static_cast<unsigned>(width);
  object->texture.height = static_cast<unsigned>(height);
  object->defined = true;
  if (pixels) tex_sub_image(target, 0, 0, 0, width, height, format, type, pixels);
}

void Context::tex_sub_image(GLenum target, GLint level, GLint x, GLint y, GLsizei width, GLsizei height, GLenum format,
                            GLenum type, const void* pixels) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  bool format_ok, type_ok;
  const int bytes = pixel_bytes(format, type, &format_ok, &type_ok);
  if (!format_ok || !type_ok) return error(GL_INVALID_ENUM);
  TextureObject* object = bound_texture();
  if (!object->defined) return error(GL_INVALID_OPERATION);
  if (level < 0 || x < 0 || y < 0 || width < 0 || height < 0 ||
      static_cast<unsigned>(x + width) > object->texture.width ||
      static_cast<unsigned>(y + height) > object->texture.height)
    return error(GL_INVALID_VALUE);
  if (level > 0 || !pixels) return;
  const auto* in = static_cast<const uint8_t*>(pixels);
  const size_t row_bytes = static_cast<size_t>(width) * bytes;
  const size_t stride = (row_bytes + m_unpack_alignment - 1) / m_unpack_alignment * m_unpack_alignment;
  std::vector<uint32_t> row(static_cast<size_t>(width));
  for (GLsizei j = 0; j < height; ++j) {
    for (GLsizei i = 0; i < width; ++i)
      expand_texel(format, in + j * stride + static_cast<size_t>(i) * bytes, reinterpret_cast<uint8_t*>(&row[i]));
    // The driver's conversion loop: a load, a few shifts and a store per texel.
    m_host.compute(Op::alu, 4ull * width);
    const uint32_t address = object->texture.address + ((y + j) * object->texture.width + x) * 4;
    for (GLsizei i = 0; i < width; i += 8)
      m_host.write_words(address + 4 * i, &row[i], static_cast<unsigned>(std::min<GLsizei>(8, width - i)));
  }
}

void Context::tex_parameter(GLenum target, GLenum name, float value) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  Texture& t = bound_texture()->texture;
  const GLenum v = static_cast<GLenum>(value);
  switch (name) {
    case GL_TEXTURE_MIN_FILTER:
      if (v == GL_NEAREST || v == GL_NEAREST_MIPMAP_NEAREST || v == GL_NEAREST_MIPMAP_LINEAR)
        t.min_filter = TexFilter::nearest;
      else if (v == GL_LINEAR || v == GL_LINEAR_MIPMAP_NEAREST || v == GL_LINEAR_MIPMAP_LINEAR)
        t.min_filter = TexFilter::linear;
      else
        error(GL_INVALID_ENUM);
      break;
    case GL_TEXTURE_MAG_FILTER:
      if (v == GL_NEAREST)
        t.mag_filter = TexFilter::nearest;
      else if (v == GL_LINEAR)
        t.mag_filter = TexFilter::linear;
      else
        error(GL_INVALID_ENUM);
      break;
    case GL_TEXTURE_WRAP_S:
    case GL_TEXTURE_WRAP_T: {
      TexWrap wrap;
      if (v == GL_REPEAT)
        wrap = TexWrap::repeat;
      else if (v == GL_CLAMP_TO_EDGE)
        wrap = TexWrap::clamp_to_edge;
      else
        return error(GL_INVALID_ENUM);
      (name == GL_TEXTURE_WRAP_S ? t.wrap_s : t.wrap_t) = wrap;
      break;
    }
    case GL_GENERATE_MIPMAP: break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::get_tex_parameter(GLenum target, GLenum name, float* value) {
  charge_call();
  if (target != GL_TEXTURE_2D) return error(GL_INVALID_ENUM);
  const Texture& t = bound_texture()->texture;
  switch (name) {
    case GL_TEXTURE_MIN_FILTER: *value = t.min_filter == TexFilter::nearest ? GL_NEAREST : GL_LINEAR; break;
    case GL_TEXTURE_MAG_FILTER: *value = t.mag_filter == TexFilter::nearest ? GL_NEAREST : GL_LINEAR; break;
    case GL_TEXTURE_WRAP_S: *value = t.wrap_s == TexWrap::repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE; break;
    case GL_TEXTURE_WRAP_T: *value = t.wrap_t == TexWrap::repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE; break;
    case GL_GENERATE_MIPMAP: *value = GL_FALSE; break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::tex_env(GLenum target, GLenum name, const float* values, int count) {
  charge_call();
  if (target != GL_TEXTURE_ENV) return error(GL_INVALID_ENUM);
  if (name == GL_TEXTURE_ENV_MODE) {
    const GLenum mode = static_cast<GLenum>(values[0]);
    if (mode != GL_MODULATE && mode != GL_REPLACE && mode != GL_DECAL && mode != GL_BLEND && mode != GL_ADD &&
        mode != GL_COMBINE)
      return error(GL_INVALID_ENUM);
    // BLEND, ADD and COMBINE are valid GL ES 1.1 and stored; the back ends
    // render them as MODULATE (documented limitation).
    m_tex_env_mode = mode;
  } else if (name == GL_TEXTURE_ENV_COLOR) {
    if (count < 4) return error(GL_INVALID_ENUM);
    for (int i = 0; i < 4; ++i) m_tex_env_color[i] = clamp01(values[i]);
  } else {
    error(GL_INVALID_ENUM);
  }
}

void Context::get_tex_env(GLenum target, GLenum name, float* values) {
  charge_call();
  if (target != GL_TEXTURE_ENV) return error(GL_INVALID_ENUM);
  if (name == GL_TEXTURE_ENV_MODE)
    values[0] = static_cast<float>(m_tex_env_mode);
  else if (name == GL_TEXTURE_ENV_COLOR)
    std::copy(m_tex_env_color, m_tex_env_color + 4, values);
  else
    error(GL_INVALID_ENUM);
}

// ---------------------------------------------------------------- buffers

void Context::gen_buffers(GLsizei n, GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    while (m_buffers.count(m_next_buffer)) ++m_next_buffer;
    names[i] = m_next_buffer;
    m_buffers[m_next_buffer++] = BufferObject{};
  }
}

void Context::delete_buffers(GLsizei n, const GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    m_buffers.erase(names[i]);
    if (m_array_buffer == names[i]) m_array_buffer = 0;
    if (m_element_buffer == names[i]) m_element_buffer = 0;
  }
}

void Context::bind_buffer(GLenum target, GLuint name) {
  charge_call();
  if (target != GL_ARRAY_BUFFER && target != GL_ELEMENT_ARRAY_BUFFER) return error(GL_INVALID_ENUM);
  if (name != 0 && !m_buffers.count(name)) m_buffers[name] = BufferObject{};
  (target == GL_ARRAY_BUFFER ? m_array_buffer : m_element_buffer) = name;
}

bool Context::is_buffer(GLuint name) {
  charge_call();
  return name != 0 && m_buffers.count(name) != 0;
}

void Context::buffer_data(GLenum target, GLsizeiptr size, const void* data, GLenum usage) {
  charge_call();
  if (target != GL_ARRAY_BUFFER && target != GL_ELEMENT_ARRAY_BUFFER) return error(GL_INVALID_ENUM);
  if (usage != GL_STATIC_DRAW && usage != GL_DYNAMIC_DRAW) return error(GL_INVALID_ENUM);
  if (size < 0) return error(GL_INVALID_VALUE);
  const GLuint name = target == GL_ARRAY_BUFFER ? m_array_buffer : m_element_buffer;
  if (name == 0) return error(GL_INVALID_OPERATION);
  BufferObject& b = m_buffers[name];
  b.usage = usage;
  b.data.assign(static_cast<size_t>(size), 0);
  if (data) std::memcpy(b.data.data(), data, static_cast<size_t>(size));
  m_host.compute(Op::alu, static_cast<uint64_t>(size) / 4);
}

void Context::buffer_sub_data(GLenum target, GLintptr offset, GLsizeiptr size, const void* data) {
  charge_call();
  if (target != GL_ARRAY_BUFFER && target != GL_ELEMENT_ARRAY_BUFFER) return error(GL_INVALID_ENUM);
  const GLuint name = target == GL_ARRAY_BUFFER ? m_array_buffer : m_element_buffer;
  if (name == 0) return error(GL_INVALID_OPERATION);
  BufferObject& b = m_buffers[name];
  if (offset < 0 || size < 0 || static_cast<size_t>(offset + size) > b.data.size()) return error(GL_INVALID_VALUE);
  if (data) std::memcpy(b.data.data() + offset, data, static_cast<size_t>(size));
}

void Context::get_buffer_parameter(GLenum target, GLenum name, GLint* value) {
  charge_call();
  if (target != GL_ARRAY_BUFFER && target != GL_ELEMENT_ARRAY_BUFFER) return error(GL_INVALID_ENUM);
  const GLuint buffer = target == GL_ARRAY_BUFFER ? m_array_buffer : m_element_buffer;
  if (buffer == 0) return error(GL_INVALID_OPERATION);
  const BufferObject& b = m_buffers[buffer];
  switch (name) {
    case GL_BUFFER_SIZE: *value = static_cast<GLint>(b.data.size()); break;
    case GL_BUFFER_USAGE: *value = static_cast<GLint>(b.usage); break;
    default: error(GL_INVALID_ENUM);
  }
}

// ---------------------------------------------------------------- drawing

const uint8_t* Context::array_element(const ArrayPointer& array, uint32_t index, size_t element_size) {
  const size_t stride = array.stride ? static_cast<size_t>(array.stride) : element_size;
  const size_t offset = stride * index;
  if (array.buffer) {
    auto it = m_buffers.find(array.buffer);
    const size_t start = reinterpret_cast<size_t>(array.pointer);
    if (it == m_buffers.end() || start + offset + element_size > it->second.data.size()) return nullptr;
    return it->second.data.data() + start + offset;
  }
  if (!array.pointer) return nullptr;
  return static_cast<const uint8_t*>(array.pointer) + offset;
}

glm::vec4 Context::read_attribute(const ArrayPointer& array, uint32_t index, const glm::vec4& defaults) {
  const size_t component = type_size(array.type);
  const uint8_t* p = array_element(array, index, component * static_cast<size_t>(array.size));
  glm::vec4 value = defaults;
  if (!p) return glm::vec4(std::numeric_limits<float>::quiet_NaN());
  for (int c = 0; c < array.size; ++c) {
    const uint8_t* q = p + c * component;
    float v = 0;
    switch (array.type) {
      case GL_FLOAT: std::memcpy(&v, q, 4); break;
      case GL_FIXED: {
        int32_t x;
        std::memcpy(&x, q, 4);
        v = static_cast<float>(x) / 65536.0f;
        break;
      }
      case GL_SHORT: {
        int16_t x;
        std::memcpy(&x, q, 2);
        v = x;
        break;
      }
      case GL_BYTE: v = static_cast<int8_t>(*q); break;
      case GL_UNSIGNED_BYTE: v = *q / 255.0f; break;  // colours: normalised
      default: break;
    }
    value[c] = v;
  }
  return value;
}

bool Context::fetch_and_transform(const std::vector<uint32_t>& indices, std::vector<Vertex>& out) {
  out.resize(indices.size());
  const glm::mat4& modelview = m_modelview.back();
  const glm::mat4& projection = m_projection.back();
  const glm::mat4& texture = m_texture_matrix.back();
  const bool texturing = m_texture_2d && m_textures.count(m_bound_texture) && m_textures[m_bound_texture].defined;
  glm::mat3 normal_matrix(1);
  if (m_lighting) normal_matrix = glm::transpose(glm::inverse(glm::mat3(modelview)));
  unsigned lights = 0;
  for (const Light& l : m_lighting_model.lights) lights += l.enabled;
  Material material = m_front_material;
  for (size_t i = 0; i < indices.size(); ++i) {
    const uint32_t index = indices[i];
    Vertex& v = out[i];
    glm::vec4 position = read_attribute(m_vertex_array, index, {0, 0, 0, 1});
    glm::vec4 color = m_color_array.enabled ? read_attribute(m_color_array, index, {0, 0, 0, 1}) : m_color;
    v.eye = modelview * position;
    v.clip.position = projection * v.eye;
    if (m_lighting) {
      glm::vec3 n = m_normal_array.enabled ? glm::vec3(read_attribute(m_normal_array, index, {0, 0, 1, 0})) : m_normal;
      n = normal_matrix * n;
      if (m_normalize || m_rescale_normal) {
        const float length = glm::length(n);
        if (length > 0) n /= length;
      }
      if (m_color_material) material.ambient = material.diffuse = color;
      v.clip.color = light_vertex(m_lighting_model, material, v.eye, n);
    } else {
      v.clip.color = glm::clamp(color, glm::vec4(0), glm::vec4(1));
    }
    if (texturing) {
      glm::vec4 tc = m_texcoord_array.enabled ? read_attribute(m_texcoord_array, index, {0, 0, 0, 1}) : m_texcoord;
      tc = texture * tc;
      v.clip.tex = tc.w != 0 ? glm::vec2(tc) / tc.w : glm::vec2(tc);
    } else {
      v.clip.tex = {0, 0};
    }
    const glm::vec4& p = v.clip.position;
    v.valid = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w) &&
              std::isfinite(v.clip.color.r) && std::isfinite(v.clip.tex.x) && std::isfinite(v.clip.tex.y);
  }
  // The geometry's soft-float work on the ARM, per vertex.
  FloatCost per_vertex = transform_cost();
  per_vertex += transform_cost();
  if (m_lighting) per_vertex += lighting_cost(lights) += FloatCost{6, 9, 0, 0, 0, 0, 0};
  if (texturing) per_vertex += transform_cost();
  per_vertex += clip_test_cost();
  charge(per_vertex, indices.size());
  m_host.compute(Op::alu, 20 * indices.size());  // fetch, conversions, loop overhead
  return true;
}

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
  m_host.compute(Op::alu, 12);
  if (area == 0) return;  // degenerate after snapping to 9.4
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
  auto it = m_textures.find(m_bound_texture);
  s.texture = m_texture_2d && it != m_textures.end() && it->second.defined;
  if (s.texture) s.tex = it->second.texture;
  s.tex_env = m_tex_env_mode == GL_REPLACE ? TexEnv::replace
              : m_tex_env_mode == GL_DECAL ? TexEnv::decal
                                           : TexEnv::modulate;
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

void Context::draw(GLenum mode, const std::vector<uint32_t>& indices) {
  if (!m_vertex_array.enabled) return;  // nothing to draw without positions
  fetch_and_transform(indices, m_vertices);
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
  for (GLsizei i = 0; i < count; ++i) indices[i] = static_cast<uint32_t>(first + i);
  draw(mode, indices);
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
    if (offset + size * static_cast<size_t>(count) > b.data.size()) return error(GL_INVALID_OPERATION);
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
  draw(mode, indices);
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
  std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4, 0);
  m_renderer->read_pixels(x, y, w, h, rgba.data());
  const size_t row = static_cast<size_t>(w) * 4;
  const size_t stride = (row + m_pack_alignment - 1) / m_pack_alignment * m_pack_alignment;
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

// ---------------------------------------------------------------- queries

int Context::query_count(GLenum name) {
  switch (name) {
    case GL_COLOR_CLEAR_VALUE:
    case GL_VIEWPORT:
    case GL_SCISSOR_BOX:
    case GL_COLOR_WRITEMASK:
    case GL_CURRENT_COLOR:
    case GL_CURRENT_TEXTURE_COORDS:
    case GL_LIGHT_MODEL_AMBIENT:
    case GL_FOG_COLOR: return 4;
    case GL_CURRENT_NORMAL: return 3;
    case GL_DEPTH_RANGE:
    case GL_MAX_VIEWPORT_DIMS:
    case GL_ALIASED_POINT_SIZE_RANGE:
    case GL_ALIASED_LINE_WIDTH_RANGE:
    case GL_SMOOTH_POINT_SIZE_RANGE:
    case GL_SMOOTH_LINE_WIDTH_RANGE:
    case GL_POLYGON_OFFSET_FACTOR: return name == GL_POLYGON_OFFSET_FACTOR ? 1 : 2;
    case GL_MODELVIEW_MATRIX:
    case GL_PROJECTION_MATRIX:
    case GL_TEXTURE_MATRIX: return 16;
    case GL_DEPTH_CLEAR_VALUE:
    case GL_STENCIL_CLEAR_VALUE:
    case GL_DEPTH_FUNC:
    case GL_DEPTH_WRITEMASK:
    case GL_ALPHA_TEST_FUNC:
    case GL_ALPHA_TEST_REF:
    case GL_STENCIL_FUNC:
    case GL_STENCIL_REF:
    case GL_STENCIL_VALUE_MASK:
    case GL_STENCIL_WRITEMASK:
    case GL_STENCIL_FAIL:
    case GL_STENCIL_PASS_DEPTH_FAIL:
    case GL_STENCIL_PASS_DEPTH_PASS:
    case GL_BLEND_SRC:
    case GL_BLEND_DST:
    case GL_LOGIC_OP_MODE:
    case GL_SHADE_MODEL:
    case GL_CULL_FACE_MODE:
    case GL_FRONT_FACE:
    case GL_MATRIX_MODE:
    case GL_MODELVIEW_STACK_DEPTH:
    case GL_PROJECTION_STACK_DEPTH:
    case GL_TEXTURE_STACK_DEPTH:
    case GL_MAX_MODELVIEW_STACK_DEPTH:
    case GL_MAX_PROJECTION_STACK_DEPTH:
    case GL_MAX_TEXTURE_STACK_DEPTH:
    case GL_MAX_LIGHTS:
    case GL_MAX_TEXTURE_SIZE:
    case GL_MAX_TEXTURE_UNITS:
    case GL_MAX_CLIP_PLANES:
    case GL_TEXTURE_BINDING_2D:
    case GL_ARRAY_BUFFER_BINDING:
    case GL_ELEMENT_ARRAY_BUFFER_BINDING:
    case GL_RED_BITS:
    case GL_GREEN_BITS:
    case GL_BLUE_BITS:
    case GL_ALPHA_BITS:
    case GL_DEPTH_BITS:
    case GL_STENCIL_BITS:
    case GL_SUBPIXEL_BITS:
    case GL_POINT_SIZE:
    case GL_LINE_WIDTH:
    case GL_PACK_ALIGNMENT:
    case GL_UNPACK_ALIGNMENT:
    case GL_ACTIVE_TEXTURE:
    case GL_CLIENT_ACTIVE_TEXTURE:
    case GL_VERTEX_ARRAY_SIZE:
    case GL_VERTEX_ARRAY_TYPE:
    case GL_VERTEX_ARRAY_STRIDE:
    case GL_COLOR_ARRAY_SIZE:
    case GL_COLOR_ARRAY_TYPE:
    case GL_COLOR_ARRAY_STRIDE:
    case GL_NORMAL_ARRAY_TYPE:
    case GL_NORMAL_ARRAY_STRIDE:
    case GL_TEXTURE_COORD_ARRAY_SIZE:
    case GL_TEXTURE_COORD_ARRAY_TYPE:
    case GL_TEXTURE_COORD_ARRAY_STRIDE:
    case GL_IMPLEMENTATION_COLOR_READ_TYPE_OES:
    case GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES:
    case GL_NUM_COMPRESSED_TEXTURE_FORMATS:
    case GL_FOG_MODE:
    case GL_FOG_DENSITY:
    case GL_FOG_START:
    case GL_FOG_END:
    case GL_SAMPLE_BUFFERS:
    case GL_SAMPLES:
    case GL_SAMPLE_COVERAGE_VALUE:
    case GL_SAMPLE_COVERAGE_INVERT:
    case GL_POLYGON_OFFSET_UNITS:
    case GL_LIGHT_MODEL_TWO_SIDE:
    case GL_PERSPECTIVE_CORRECTION_HINT:
    case GL_POINT_SMOOTH_HINT:
    case GL_LINE_SMOOTH_HINT:
    case GL_FOG_HINT:
    case GL_GENERATE_MIPMAP_HINT: return 1;
    default: return 0;
  }
}

void Context::get_floats(GLenum name, float* v) {
  charge_call();
  auto mat = [&](const glm::mat4& m) { std::memcpy(v, glm::value_ptr(m), 16 * sizeof(float)); };
  auto hint_value = [&](GLenum target) {
    auto it = m_hints.find(target);
    return static_cast<float>(it == m_hints.end() ? GL_DONT_CARE : it->second);
  };
  const bool rgb565 = true;
  switch (name) {
    case GL_COLOR_CLEAR_VALUE: std::copy(m_clear_color, m_clear_color + 4, v); break;
    case GL_VIEWPORT:
      v[0] = m_viewport.x, v[1] = m_viewport.y, v[2] = m_viewport.width, v[3] = m_viewport.height;
      break;
    case GL_SCISSOR_BOX:
      v[0] = m_raster.scissor_x, v[1] = m_raster.scissor_y, v[2] = m_raster.scissor_width,
      v[3] = m_raster.scissor_height;
      break;
    case GL_COLOR_WRITEMASK:
      for (int i = 0; i < 4; ++i) v[i] = m_raster.color_mask[i];
      break;
    case GL_CURRENT_COLOR:
      for (int i = 0; i < 4; ++i) v[i] = m_color[i];
      break;
    case GL_CURRENT_TEXTURE_COORDS:
      for (int i = 0; i < 4; ++i) v[i] = m_texcoord[i];
      break;
    case GL_CURRENT_NORMAL:
      for (int i = 0; i < 3; ++i) v[i] = m_normal[i];
      break;
    case GL_LIGHT_MODEL_AMBIENT:
      for (int i = 0; i < 4; ++i) v[i] = m_lighting_model.ambient[i];
      break;
    case GL_LIGHT_MODEL_TWO_SIDE: v[0] = m_two_side; break;
    case GL_FOG_COLOR: std::copy(m_fog_color, m_fog_color + 4, v); break;
    case GL_FOG_MODE: v[0] = static_cast<float>(m_fog_mode); break;
    case GL_FOG_DENSITY: v[0] = m_fog_density; break;
    case GL_FOG_START: v[0] = m_fog_start; break;
    case GL_FOG_END: v[0] = m_fog_end; break;
    case GL_DEPTH_RANGE: v[0] = m_viewport.near_depth, v[1] = m_viewport.far_depth; break;
    case GL_MAX_VIEWPORT_DIMS: v[0] = v[1] = 512; break;
    case GL_ALIASED_POINT_SIZE_RANGE:
    case GL_SMOOTH_POINT_SIZE_RANGE:
    case GL_ALIASED_LINE_WIDTH_RANGE:
    case GL_SMOOTH_LINE_WIDTH_RANGE: v[0] = 1, v[1] = 64; break;
    case GL_MODELVIEW_MATRIX: mat(m_modelview.back()); break;
    case GL_PROJECTION_MATRIX: mat(m_projection.back()); break;
    case GL_TEXTURE_MATRIX: mat(m_texture_matrix.back()); break;
    case GL_DEPTH_CLEAR_VALUE: v[0] = m_clear_depth; break;
    case GL_STENCIL_CLEAR_VALUE: v[0] = static_cast<float>(m_clear_stencil); break;
    case GL_DEPTH_FUNC: v[0] = static_cast<float>(GL_NEVER + static_cast<int>(m_raster.depth_func)); break;
    case GL_DEPTH_WRITEMASK: v[0] = m_raster.depth_write; break;
    case GL_ALPHA_TEST_FUNC: v[0] = static_cast<float>(GL_NEVER + static_cast<int>(m_raster.alpha_func)); break;
    case GL_ALPHA_TEST_REF: v[0] = m_alpha_ref; break;
    case GL_STENCIL_FUNC: v[0] = static_cast<float>(GL_NEVER + static_cast<int>(m_raster.stencil_func)); break;
    case GL_STENCIL_REF: v[0] = static_cast<float>(m_stencil_ref); break;
    case GL_STENCIL_VALUE_MASK: v[0] = m_raster.stencil_value_mask; break;
    case GL_STENCIL_WRITEMASK: v[0] = m_raster.stencil_write_mask; break;
    case GL_SHADE_MODEL: v[0] = static_cast<float>(m_shade_model); break;
    case GL_CULL_FACE_MODE: v[0] = static_cast<float>(m_cull_mode); break;
    case GL_FRONT_FACE: v[0] = static_cast<float>(m_front_face); break;
    case GL_MATRIX_MODE: v[0] = static_cast<float>(m_matrix_mode); break;
    case GL_MODELVIEW_STACK_DEPTH: v[0] = static_cast<float>(m_modelview.size()); break;
    case GL_PROJECTION_STACK_DEPTH: v[0] = static_cast<float>(m_projection.size()); break;
    case GL_TEXTURE_STACK_DEPTH: v[0] = static_cast<float>(m_texture_matrix.size()); break;
    case GL_MAX_MODELVIEW_STACK_DEPTH: v[0] = MAX_MODELVIEW_DEPTH; break;
    case GL_MAX_PROJECTION_STACK_DEPTH: v[0] = MAX_PROJECTION_DEPTH; break;
    case GL_MAX_TEXTURE_STACK_DEPTH: v[0] = MAX_TEXTURE_DEPTH; break;
    case GL_MAX_LIGHTS: v[0] = MAX_LIGHTS; break;
    case GL_MAX_TEXTURE_SIZE: v[0] = MAX_TEXTURE_SIZE; break;
    case GL_MAX_TEXTURE_UNITS: v[0] = 2; break;
    case GL_MAX_CLIP_PLANES: v[0] = 6; break;
    case GL_TEXTURE_BINDING_2D: v[0] = static_cast<float>(m_bound_texture); break;
    case GL_ARRAY_BUFFER_BINDING: v[0] = static_cast<float>(m_array_buffer); break;
    case GL_ELEMENT_ARRAY_BUFFER_BINDING: v[0] = static_cast<float>(m_element_buffer); break;
    case GL_RED_BITS:
    case GL_BLUE_BITS: v[0] = rgb565 ? 5 : 8; break;
    case GL_GREEN_BITS: v[0] = rgb565 ? 6 : 8; break;
    case GL_ALPHA_BITS: v[0] = 0; break;
    case GL_DEPTH_BITS: v[0] = 16; break;
    case GL_STENCIL_BITS: v[0] = 8; break;
    case GL_SUBPIXEL_BITS: v[0] = SUBPIXEL_BITS; break;
    case GL_POINT_SIZE: v[0] = m_point_size; break;
    case GL_LINE_WIDTH: v[0] = m_line_width; break;
    case GL_PACK_ALIGNMENT: v[0] = static_cast<float>(m_pack_alignment); break;
    case GL_UNPACK_ALIGNMENT: v[0] = static_cast<float>(m_unpack_alignment); break;
    case GL_ACTIVE_TEXTURE: v[0] = static_cast<float>(m_active_texture); break;
    case GL_CLIENT_ACTIVE_TEXTURE: v[0] = static_cast<float>(m_client_active_texture); break;
    case GL_VERTEX_ARRAY_SIZE: v[0] = static_cast<float>(m_vertex_array.size); break;
    case GL_VERTEX_ARRAY_TYPE: v[0] = static_cast<float>(m_vertex_array.type); break;
    case GL_VERTEX_ARRAY_STRIDE: v[0] = static_cast<float>(m_vertex_array.stride); break;
    case GL_COLOR_ARRAY_SIZE: v[0] = static_cast<float>(m_color_array.size); break;
    case GL_COLOR_ARRAY_TYPE: v[0] = static_cast<float>(m_color_array.type); break;
    case GL_COLOR_ARRAY_STRIDE: v[0] = static_cast<float>(m_color_array.stride); break;
    case GL_NORMAL_ARRAY_TYPE: v[0] = static_cast<float>(m_normal_array.type); break;
    case GL_NORMAL_ARRAY_STRIDE: v[0] = static_cast<float>(m_normal_array.stride); break;
    case GL_TEXTURE_COORD_ARRAY_SIZE: v[0] = static_cast<float>(m_texcoord_array.size); break;
    case GL_TEXTURE_COORD_ARRAY_TYPE: v[0] = static_cast<float>(m_texcoord_array.type); break;
    case GL_TEXTURE_COORD_ARRAY_STRIDE: v[0] = static_cast<float>(m_texcoord_array.stride); break;
    case GL_IMPLEMENTATION_COLOR_READ_TYPE_OES: v[0] = GL_UNSIGNED_BYTE; break;
    case GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES: v[0] = GL_RGBA; break;
    case GL_NUM_COMPRESSED_TEXTURE_FORMATS: v[0] = 0; break;
    case GL_SAMPLE_BUFFERS: v[0] = 0; break;
    case GL_SAMPLES: v[0] = 0; break;
    case GL_SAMPLE_COVERAGE_VALUE: v[0] = m_sample_coverage_value; break;
    case GL_SAMPLE_COVERAGE_INVERT: v[0] = m_sample_coverage_invert; break;
    case GL_POLYGON_OFFSET_FACTOR: v[0] = m_polygon_offset[0]; break;
    case GL_POLYGON_OFFSET_UNITS: v[0] = m_polygon_offset[1]; break;
    case GL_BLEND_SRC:
    case GL_BLEND_DST: {
      static const GLenum factors[] = {GL_ZERO,
                                       GL_ONE,
                                       GL_SRC_COLOR,
                                       GL_ONE_MINUS_SRC_COLOR,
                                       GL_DST_COLOR,
                                       GL_ONE_MINUS_DST_COLOR,
                                       GL_SRC_ALPHA,
                                       GL_ONE_MINUS_SRC_ALPHA,
                                       GL_DST_ALPHA,
                                       GL_ONE_MINUS_DST_ALPHA,
                                       GL_SRC_ALPHA_SATURATE};
      v[0] =
          static_cast<float>(factors[static_cast<int>(name == GL_BLEND_SRC ? m_raster.blend_src : m_raster.blend_dst)]);
      break;
    }
    case GL_LOGIC_OP_MODE: v[0] = static_cast<float>(GL_CLEAR + m_raster.logic_op_code); break;
    case GL_STENCIL_FAIL:
    case GL_STENCIL_PASS_DEPTH_FAIL:
    case GL_STENCIL_PASS_DEPTH_PASS: {
      static const GLenum ops[] = {GL_KEEP, GL_ZERO, GL_REPLACE, GL_INCR, GL_DECR, GL_INVERT};
      const StencilOp op = name == GL_STENCIL_FAIL              ? m_raster.stencil_fail
                           : name == GL_STENCIL_PASS_DEPTH_FAIL ? m_raster.depth_fail
                                                                : m_raster.depth_pass;
      v[0] = static_cast<float>(ops[static_cast<int>(op)]);
      break;
    }
    case GL_PERSPECTIVE_CORRECTION_HINT:
    case GL_POINT_SMOOTH_HINT:
    case GL_LINE_SMOOTH_HINT:
    case GL_FOG_HINT:
    case GL_GENERATE_MIPMAP_HINT: v[0] = hint_value(name); break;
    default: error(GL_INVALID_ENUM);
  }
}

const GLubyte* Context::get_string(GLenum name) {
  charge_call();
  switch (name) {
    case GL_VENDOR: return reinterpret_cast<const GLubyte*>("tessera");
    case GL_RENDERER: return reinterpret_cast<const GLubyte*>(m_renderer->name());
    case GL_VERSION: return reinterpret_cast<const GLubyte*>("OpenGL ES-CM 1.1");
    case GL_EXTENSIONS: return reinterpret_cast<const GLubyte*>("");
    default: error(GL_INVALID_ENUM); return nullptr;
  }
}

void Context::get_pointer(GLenum name, void** value) {
  charge_call();
  switch (name) {
    case GL_VERTEX_ARRAY_POINTER: *value = const_cast<void*>(m_vertex_array.pointer); break;
    case GL_COLOR_ARRAY_POINTER: *value = const_cast<void*>(m_color_array.pointer); break;
    case GL_NORMAL_ARRAY_POINTER: *value = const_cast<void*>(m_normal_array.pointer); break;
    case GL_TEXTURE_COORD_ARRAY_POINTER: *value = const_cast<void*>(m_texcoord_array.pointer); break;
    default: error(GL_INVALID_ENUM);
  }
}

}  // namespace tessera::gl
