// glGet*, glGetString and glGetPointerv.
#include "gl/context.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "common/screen_size.h"
#include "gl/context_internal.h"
#include "gl/runtime.h"
#include "gl/texture_formats.h"

namespace tessera::gl {

int Context::query_count(GLenum name) {
  switch (name) {
    case GL_COMPRESSED_TEXTURE_FORMATS: return static_cast<int>(PALETTE_FORMAT_COUNT);
    case GL_COLOR_CLEAR_VALUE:
    case GL_VIEWPORT:
    case GL_SCISSOR_BOX:
    case GL_COLOR_WRITEMASK:
    case GL_CURRENT_COLOR:
    case GL_CURRENT_TEXTURE_COORDS:
    case GL_LIGHT_MODEL_AMBIENT:
    case GL_FOG_COLOR: return 4;
    case GL_CURRENT_NORMAL:
    case GL_POINT_DISTANCE_ATTENUATION: return 3;
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
    case GL_GENERATE_MIPMAP_HINT:
    case GL_POINT_SIZE_MIN:
    case GL_POINT_SIZE_MAX:
    case GL_POINT_FADE_THRESHOLD_SIZE:
    case GL_POINT_SIZE_ARRAY_TYPE_OES:
    case GL_POINT_SIZE_ARRAY_STRIDE_OES:
    case GL_POINT_SIZE_ARRAY_BUFFER_BINDING_OES:
    case GL_POINT_SPRITE_OES:
    case GL_POINT_SIZE_ARRAY_OES: return 1;
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
  const PixelFormatInfo& format = pixel_format_info(m_renderer->color_format());
  switch (name) {
    case GL_COLOR_CLEAR_VALUE: std::copy(m_clear.color, m_clear.color + 4, v); break;
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
      for (int i = 0; i < 4; ++i) v[i] = m_attributes.color[i];
      break;
    case GL_CURRENT_TEXTURE_COORDS:
      for (int i = 0; i < 4; ++i) v[i] = active_unit().texcoord[i];
      break;
    case GL_CURRENT_NORMAL:
      for (int i = 0; i < 3; ++i) v[i] = m_attributes.normal[i];
      break;
    case GL_LIGHT_MODEL_AMBIENT:
      for (int i = 0; i < 4; ++i) v[i] = m_lighting.model.ambient[i];
      break;
    case GL_LIGHT_MODEL_TWO_SIDE: v[0] = m_lighting.two_side; break;
    case GL_FOG_COLOR: std::copy(m_fog.color, m_fog.color + 4, v); break;
    case GL_FOG_MODE: v[0] = static_cast<float>(m_fog.mode); break;
    case GL_FOG_DENSITY: v[0] = m_fog.density; break;
    case GL_FOG_START: v[0] = m_fog.start; break;
    case GL_FOG_END: v[0] = m_fog.end; break;
    case GL_DEPTH_RANGE: v[0] = m_viewport.near_depth, v[1] = m_viewport.far_depth; break;
    case GL_MAX_VIEWPORT_DIMS: v[0] = v[1] = static_cast<GLint>(MAX_SCREEN_SIZE); break;
    case GL_ALIASED_POINT_SIZE_RANGE:
    case GL_SMOOTH_POINT_SIZE_RANGE:
    case GL_ALIASED_LINE_WIDTH_RANGE:
    case GL_SMOOTH_LINE_WIDTH_RANGE: v[0] = MIN_POINT_SIZE, v[1] = MAX_POINT_SIZE; break;
    case GL_MODELVIEW_MATRIX: mat(m_transform.modelview.back()); break;
    case GL_PROJECTION_MATRIX: mat(m_transform.projection.back()); break;
    case GL_TEXTURE_MATRIX: mat(active_unit().matrix.back()); break;
    case GL_DEPTH_CLEAR_VALUE: v[0] = m_clear.depth; break;
    case GL_STENCIL_CLEAR_VALUE: v[0] = static_cast<float>(m_clear.stencil); break;
    case GL_DEPTH_FUNC: v[0] = static_cast<float>(gl_value(m_raster.depth_func)); break;
    case GL_DEPTH_WRITEMASK: v[0] = m_raster.depth_write; break;
    case GL_ALPHA_TEST_FUNC: v[0] = static_cast<float>(gl_value(m_raster.alpha_func)); break;
    case GL_ALPHA_TEST_REF: v[0] = m_references.alpha; break;
    case GL_STENCIL_FUNC: v[0] = static_cast<float>(gl_value(m_raster.stencil_func)); break;
    case GL_STENCIL_REF: v[0] = static_cast<float>(m_references.stencil); break;
    case GL_STENCIL_VALUE_MASK: v[0] = m_raster.stencil_value_mask; break;
    case GL_STENCIL_WRITEMASK: v[0] = m_raster.stencil_write_mask; break;
    case GL_SHADE_MODEL: v[0] = static_cast<float>(m_primitive.shade_model); break;
    case GL_CULL_FACE_MODE: v[0] = static_cast<float>(m_primitive.cull_mode); break;
    case GL_FRONT_FACE: v[0] = static_cast<float>(m_primitive.front_face); break;
    case GL_MATRIX_MODE: v[0] = static_cast<float>(m_transform.matrix_mode); break;
    case GL_MODELVIEW_STACK_DEPTH: v[0] = static_cast<float>(m_transform.modelview.size()); break;
    case GL_PROJECTION_STACK_DEPTH: v[0] = static_cast<float>(m_transform.projection.size()); break;
    case GL_TEXTURE_STACK_DEPTH: v[0] = static_cast<float>(active_unit().matrix.size()); break;
    case GL_MAX_MODELVIEW_STACK_DEPTH: v[0] = MAX_MODELVIEW_DEPTH; break;
    case GL_MAX_PROJECTION_STACK_DEPTH: v[0] = MAX_PROJECTION_DEPTH; break;
    case GL_MAX_TEXTURE_STACK_DEPTH: v[0] = MAX_TEXTURE_DEPTH; break;
    case GL_MAX_LIGHTS: v[0] = MAX_LIGHTS; break;
    case GL_MAX_TEXTURE_SIZE: v[0] = MAX_TEXTURE_SIZE; break;
    case GL_MAX_TEXTURE_UNITS: v[0] = static_cast<float>(m_texture.offered_units); break;
    case GL_MAX_CLIP_PLANES: v[0] = MAX_USER_CLIP_PLANES; break;
    case GL_POINT_SIZE_MIN: v[0] = m_rasterization.point_size_min; break;
    case GL_POINT_SIZE_MAX: v[0] = m_rasterization.point_size_max; break;
    case GL_POINT_FADE_THRESHOLD_SIZE: v[0] = m_rasterization.point_fade_threshold; break;
    case GL_POINT_DISTANCE_ATTENUATION:
      for (int i = 0; i < 3; ++i) v[i] = m_rasterization.point_distance_attenuation[i];
      break;
    case GL_POINT_SIZE_ARRAY_TYPE_OES: v[0] = static_cast<float>(m_attributes.point_size_array.type); break;
    case GL_POINT_SIZE_ARRAY_STRIDE_OES: v[0] = static_cast<float>(m_attributes.point_size_array.stride); break;
    case GL_POINT_SIZE_ARRAY_BUFFER_BINDING_OES: v[0] = static_cast<float>(m_attributes.point_size_array.buffer); break;
    case GL_POINT_SPRITE_OES: v[0] = m_rasterization.point_sprite; break;
    case GL_POINT_SIZE_ARRAY_OES: v[0] = m_attributes.point_size_array.enabled; break;
    case GL_TEXTURE_BINDING_2D: v[0] = static_cast<float>(active_unit().bound); break;
    case GL_ARRAY_BUFFER_BINDING: v[0] = static_cast<float>(m_buffer.array); break;
    case GL_ELEMENT_ARRAY_BUFFER_BINDING: v[0] = static_cast<float>(m_buffer.element); break;
    case GL_RED_BITS: v[0] = static_cast<float>(format.red_bits); break;
    case GL_GREEN_BITS: v[0] = static_cast<float>(format.green_bits); break;
    case GL_BLUE_BITS: v[0] = static_cast<float>(format.blue_bits); break;
    case GL_ALPHA_BITS: v[0] = static_cast<float>(format.alpha_bits); break;
    case GL_DEPTH_BITS: v[0] = static_cast<float>(m_renderer->capabilities().depth_bits); break;
    case GL_STENCIL_BITS: v[0] = static_cast<float>(m_renderer->capabilities().stencil_bits); break;
    case GL_SUBPIXEL_BITS: v[0] = SUBPIXEL_BITS; break;
    case GL_POINT_SIZE: v[0] = m_rasterization.point_size; break;
    case GL_LINE_WIDTH: v[0] = m_rasterization.line_width; break;
    case GL_PACK_ALIGNMENT: v[0] = static_cast<float>(m_pixel_store.pack_alignment); break;
    case GL_UNPACK_ALIGNMENT: v[0] = static_cast<float>(m_pixel_store.unpack_alignment); break;
    case GL_ACTIVE_TEXTURE: v[0] = static_cast<float>(m_attributes.active_texture); break;
    case GL_CLIENT_ACTIVE_TEXTURE: v[0] = static_cast<float>(m_attributes.client_active_texture); break;
    case GL_VERTEX_ARRAY_SIZE: v[0] = static_cast<float>(m_attributes.vertex_array.size); break;
    case GL_VERTEX_ARRAY_TYPE: v[0] = static_cast<float>(m_attributes.vertex_array.type); break;
    case GL_VERTEX_ARRAY_STRIDE: v[0] = static_cast<float>(m_attributes.vertex_array.stride); break;
    case GL_COLOR_ARRAY_SIZE: v[0] = static_cast<float>(m_attributes.color_array.size); break;
    case GL_COLOR_ARRAY_TYPE: v[0] = static_cast<float>(m_attributes.color_array.type); break;
    case GL_COLOR_ARRAY_STRIDE: v[0] = static_cast<float>(m_attributes.color_array.stride); break;
    case GL_NORMAL_ARRAY_TYPE: v[0] = static_cast<float>(m_attributes.normal_array.type); break;
    case GL_NORMAL_ARRAY_STRIDE: v[0] = static_cast<float>(m_attributes.normal_array.stride); break;
    case GL_TEXTURE_COORD_ARRAY_SIZE: v[0] = static_cast<float>(client_unit().texcoord_array.size); break;
    case GL_TEXTURE_COORD_ARRAY_TYPE: v[0] = static_cast<float>(client_unit().texcoord_array.type); break;
    case GL_TEXTURE_COORD_ARRAY_STRIDE: v[0] = static_cast<float>(client_unit().texcoord_array.stride); break;
    case GL_IMPLEMENTATION_COLOR_READ_TYPE_OES: v[0] = GL_UNSIGNED_BYTE; break;
    case GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES: v[0] = GL_RGBA; break;
    case GL_NUM_COMPRESSED_TEXTURE_FORMATS: v[0] = PALETTE_FORMAT_COUNT; break;
    case GL_COMPRESSED_TEXTURE_FORMATS:
      for (unsigned i = 0; i < PALETTE_FORMAT_COUNT; ++i) v[i] = static_cast<float>(PALETTE_FORMATS[i].name);
      break;
    case GL_SAMPLE_BUFFERS: v[0] = 0; break;
    case GL_SAMPLES: v[0] = 0; break;
    case GL_SAMPLE_COVERAGE_VALUE: v[0] = m_coverage.value; break;
    case GL_SAMPLE_COVERAGE_INVERT: v[0] = m_coverage.invert; break;
    case GL_POLYGON_OFFSET_FACTOR: v[0] = m_rasterization.polygon_offset[0]; break;
    case GL_POLYGON_OFFSET_UNITS: v[0] = m_rasterization.polygon_offset[1]; break;
    case GL_BLEND_SRC: v[0] = static_cast<float>(gl_value(m_raster.blend_src)); break;
    case GL_BLEND_DST: v[0] = static_cast<float>(gl_value(m_raster.blend_dst)); break;
    case GL_LOGIC_OP_MODE: v[0] = static_cast<float>(gl_value(m_raster.logic_op_mode)); break;
    case GL_STENCIL_FAIL: v[0] = static_cast<float>(gl_value(m_raster.stencil_fail)); break;
    case GL_STENCIL_PASS_DEPTH_FAIL: v[0] = static_cast<float>(gl_value(m_raster.depth_fail)); break;
    case GL_STENCIL_PASS_DEPTH_PASS: v[0] = static_cast<float>(gl_value(m_raster.depth_pass)); break;
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
    // Those <GLES/glext.h> declares (test_gl_api checks that the two agree).
    case GL_EXTENSIONS:
      return reinterpret_cast<const GLubyte*>(
          "GL_OES_read_format GL_OES_point_size_array GL_OES_point_sprite GL_OES_compressed_paletted_texture "
          "GL_OES_byte_coordinates GL_OES_fixed_point GL_OES_single_precision GL_OES_matrix_get");
    default: error(GL_INVALID_ENUM); return nullptr;
  }
}

void Context::get_pointer(GLenum name, void** value) {
  charge_call();
  switch (name) {
    case GL_VERTEX_ARRAY_POINTER: *value = const_cast<void*>(m_attributes.vertex_array.pointer); break;
    case GL_COLOR_ARRAY_POINTER: *value = const_cast<void*>(m_attributes.color_array.pointer); break;
    case GL_NORMAL_ARRAY_POINTER: *value = const_cast<void*>(m_attributes.normal_array.pointer); break;
    case GL_TEXTURE_COORD_ARRAY_POINTER: *value = const_cast<void*>(client_unit().texcoord_array.pointer); break;
    case GL_POINT_SIZE_ARRAY_POINTER_OES: *value = const_cast<void*>(m_attributes.point_size_array.pointer); break;
    default: error(GL_INVALID_ENUM);
  }
}

}  // namespace tessera::gl
