// Current vertex attributes and the client vertex arrays.
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

void Context::color(float r, float g, float b, float a) {
  charge_call();
  m_color = {r, g, b, a};
}

void Context::normal(float x, float y, float z) {
  charge_call();
  m_normal = {x, y, z};
}

void Context::tex_coord(GLenum unit, float s, float t, float r, float q) {
  charge_call();
  if (unit < GL_TEXTURE0 || unit >= GL_TEXTURE0 + m_texture_units) return error(GL_INVALID_ENUM);
  m_units[unit - GL_TEXTURE0].texcoord = {s, t, r, q};
}

void Context::array_pointer(ArrayPointer& array, GLint size, GLenum type, GLsizei stride, const void* pointer,
                            bool size_ok, bool type_ok) {
  charge_call();
  if (!type_ok) return error(GL_INVALID_ENUM);
  if (!size_ok || stride < 0) return error(GL_INVALID_VALUE);
  array.size = size, array.type = type, array.stride = stride, array.pointer = pointer;
  array.buffer = m_array_buffer;
}

void Context::active_texture(GLenum unit, bool client) {
  charge_call();
  if (unit < GL_TEXTURE0 || unit >= GL_TEXTURE0 + m_texture_units) return error(GL_INVALID_ENUM);
  (client ? m_client_active_texture : m_active_texture) = unit;
}

}  // namespace tessera::gl
