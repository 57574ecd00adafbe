// Limits and small helpers shared by the GL context's source files (one per
// area of the state: state.cpp, matrices.cpp, vertex_arrays.cpp,
// lighting.cpp, textures.cpp, buffers.cpp, vertex_fetch.cpp,
// primitives.cpp, queries.cpp). Not part of the driver's interface.
#pragma once

#include <GLES/gl.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "common/fixed_function.h"
#include "gl/renderer.h"

namespace tessera::gl {

inline constexpr size_t MAX_MODELVIEW_DEPTH = 16;
inline constexpr size_t MAX_PROJECTION_DEPTH = 2;
inline constexpr size_t MAX_TEXTURE_DEPTH = 2;
inline constexpr unsigned MAX_LIGHTS = 8;
inline constexpr GLsizei MAX_TEXTURE_SIZE = 256;
inline constexpr size_t BATCH_TRIANGLES = 256;

// A float parameter that names an enum (glTexParameterf(..., GL_LINEAR)
// passes 9729.0f): only a whole number in GLenum's range names one.
// Anything else (1e30, NaN, 9729.5) names no enum, and the caller raises
// GL_INVALID_ENUM; converting it with a cast would be undefined behaviour.
inline std::optional<GLenum> enum_from_float(float value) {
  if (!(value >= 0.0f && value < 4294967296.0f) || value != std::floor(value)) return std::nullopt;
  return static_cast<GLenum>(value);
}

// A float answered through an integer query (glGetIntegerv and the like):
// rounded to the nearest integer (GL ES 1.1 section 6.1.2) and, where GLint
// cannot hold it, clamped (NaN as 0) instead of converted out of range.
// Every float from 2^23 up is an integer, so the largest below 2^31,
// 2^31 - 128, fits GLint; 2^31 and beyond clamp (-2^31 is INT_MIN itself).
inline GLint int_from_float(float value) {
  constexpr float LIMIT = 2147483648.0f;  // 2^31
  if (std::isnan(value)) return 0;
  if (value >= LIMIT) return INT_MAX;
  if (value <= -LIMIT) return INT_MIN;
  return static_cast<GLint>(std::lround(value));
}

// A colour or depth answered through an integer query: [-1, 1] mapped
// linearly to [-(2^31 - 1), 2^31 - 1] (GL ES 1.1 section 6.1.2 with table
// 2.7), that is value * (2^31 - 1) rounded to nearest, half away from zero,
// and clamped to GLint (NaN as 0). Exact in integers: value = m 2^(e - 24)
// with a 24-bit integer m and e <= 0 inside (-1, 1), so the product is
// m (2^31 - 1), below 2^55, shifted right by 24 - e.
inline GLint int_from_unit_float(float value) {
  if (std::isnan(value)) return 0;
  if (value >= 1.0f) return INT_MAX;
  if (value == -1.0f) return -INT_MAX;
  if (value < -1.0f) return INT_MIN;
  int exponent = 0;
  const float fraction = std::frexp(std::fabs(value), &exponent);      // [0.5, 1), or 0
  const auto mantissa = static_cast<int64_t>(fraction * 16777216.0f);  // exact: a power of two
  const int shift = 24 - exponent;
  if (shift >= 63) return 0;  // below 2^-39: rounds to 0
  const int64_t magnitude = (mantissa * INT_MAX + (int64_t{1} << (shift - 1))) >> shift;
  return static_cast<GLint>(value < 0 ? -magnitude : magnitude);
}

// x + width <= limit for a rectangle that starts at x >= 0 and has
// width >= 0, without the signed overflow of x + width (x = INT_MAX).
inline bool fits(GLint x, GLsizei width, uint32_t limit) {
  return static_cast<int64_t>(x) + width <= static_cast<int64_t>(limit);
}

// GL enums to the hardware codes of common/fixed_function.def, with GL's
// rules on which values each call accepts; false for an enum GL rejects
// there (the caller raises GL_INVALID_ENUM and keeps its state).
template <typename E>
inline bool fixed_function_value(GLenum value, E* out) {
  const std::optional<E> code = from_gl_enum<E>(value);
  if (code) *out = *code;
  return code.has_value();
}

inline bool compare_func(GLenum func, CompareFunc* out) {
  return fixed_function_value(func, out);
}

inline bool stencil_op_value(GLenum op, StencilOp* out) {
  return fixed_function_value(op, out);
}

inline bool logic_op_value(GLenum op, LogicOp* out) {
  return fixed_function_value(op, out);
}

// glBlendFunc: the source and destination factors are different sets.
inline bool blend_factor(GLenum factor, bool source, BlendFactor* out) {
  const std::optional<BlendFactor> code =
      blend_factor_from_gl_enum(factor, source ? BlendSide::source : BlendSide::destination);
  if (code) *out = *code;
  return code.has_value();
}

inline bool tex_filter_value(GLenum filter, TexFilter* out) {
  return fixed_function_value(filter, out);
}

// A minification filter: the filter within a level and how levels are chosen.
inline bool tex_min_filter_value(GLenum filter, TexFilter* within, MipmapFilter* mipmap) {
  switch (filter) {
    case GL_NEAREST_MIPMAP_NEAREST: *within = TexFilter::nearest, *mipmap = MipmapFilter::nearest; return true;
    case GL_LINEAR_MIPMAP_NEAREST: *within = TexFilter::linear, *mipmap = MipmapFilter::nearest; return true;
    case GL_NEAREST_MIPMAP_LINEAR: *within = TexFilter::nearest, *mipmap = MipmapFilter::linear; return true;
    case GL_LINEAR_MIPMAP_LINEAR: *within = TexFilter::linear, *mipmap = MipmapFilter::linear; return true;
    default:
      if (!fixed_function_value(filter, within)) return false;
      *mipmap = MipmapFilter::none;
      return true;
  }
}

inline GLenum tex_min_filter_enum(TexFilter within, MipmapFilter mipmap) {
  const bool linear = within == TexFilter::linear;
  switch (mipmap) {
    case MipmapFilter::nearest: return linear ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
    case MipmapFilter::linear: return linear ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
    case MipmapFilter::none: break;
  }
  return linear ? GL_LINEAR : GL_NEAREST;
}

inline bool tex_wrap_value(GLenum wrap, TexWrap* out) {
  return fixed_function_value(wrap, out);
}

// A texture unit's environment as the back ends take it (textures.cpp);
// the texture and `enabled` are the caller's.
void set_unit_environment(const TextureUnitState& in, TextureUnit* out);

// The GL enum of a code the state holds, for glGet.
template <typename E>
inline GLenum gl_value(E code) {
  return static_cast<GLenum>(gl_enum_of(code).value_or(0));
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
