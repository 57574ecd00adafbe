// Limits and small helpers shared by the GL context's source files (one per
// area of the state: state.cpp, matrices.cpp, vertex_arrays.cpp,
// lighting.cpp, textures.cpp, buffers.cpp, vertex_fetch.cpp,
// primitives.cpp, queries.cpp). Not part of the driver's interface.
#pragma once

#include <GLES/gl.h>

#include <algorithm>
#include <cstddef>

#include "gl/renderer.h"

namespace tessera::gl {

inline constexpr size_t MAX_MODELVIEW_DEPTH = 16;
inline constexpr size_t MAX_PROJECTION_DEPTH = 2;
inline constexpr size_t MAX_TEXTURE_DEPTH = 2;
inline constexpr unsigned MAX_LIGHTS = 8;
inline constexpr GLsizei MAX_TEXTURE_SIZE = 256;
inline constexpr size_t BATCH_TRIANGLES = 256;

inline bool compare_func(GLenum func, CompareFunc* out) {
  if (func < GL_NEVER || func > GL_ALWAYS) return false;
  *out = static_cast<CompareFunc>(func - GL_NEVER);
  return true;
}

inline bool stencil_op_value(GLenum op, StencilOp* out) {
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

inline bool blend_factor(GLenum factor, bool source, BlendFactor* out) {
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

inline float clamp01(float v) {
  return std::clamp(v, 0.0f, 1.0f);
}

inline size_t type_size(GLenum type) {
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

inline bool is_power_of_two(GLsizei v) {
  return v > 0 && (v & (v - 1)) == 0;
}

}  // namespace tessera::gl
