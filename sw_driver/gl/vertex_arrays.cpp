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
  m_attributes.color = {r, g, b, a};
}

void Context::normal(float x, float y, float z) {
  charge_call();
  m_attributes.normal = {x, y, z};
}

void Context::tex_coord(GLenum unit, float s, float t, float r, float q) {
  charge_call();
  if (unit < GL_TEXTURE0 || unit >= GL_TEXTURE0 + m_texture.offered_units) return error(GL_INVALID_ENUM);
  m_texture.units[unit - GL_TEXTURE0].texcoord = {s, t, r, q};
}

void Context::array_pointer(ArrayPointer& array, GLint size, GLenum type, GLsizei stride, const void* pointer,
                            bool size_ok, bool type_ok) {
  charge_call();
  if (!type_ok) return error(GL_INVALID_ENUM);
  if (!size_ok || stride < 0) return error(GL_INVALID_VALUE);
  array.size = size, array.type = type, array.stride = stride, array.pointer = pointer;
  array.buffer = m_buffer.array;
}

void Context::active_texture(GLenum unit, bool client) {
  charge_call();
  if (unit < GL_TEXTURE0 || unit >= GL_TEXTURE0 + m_texture.offered_units) return error(GL_INVALID_ENUM);
  (client ? m_attributes.client_active_texture : m_attributes.active_texture) = unit;
}

}  // namespace tessera::gl
