// Buffer objects (vertex and index data).
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

void Context::gen_buffers(GLsizei n, GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    while (m_buffer.objects.count(m_buffer.next_name)) ++m_buffer.next_name;
    names[i] = m_buffer.next_name;
    m_buffer.objects[m_buffer.next_name++] = BufferObject{};
  }
}

void Context::delete_buffers(GLsizei n, const GLuint* names) {
  charge_call();
  if (n < 0) return error(GL_INVALID_VALUE);
  for (GLsizei i = 0; i < n; ++i) {
    m_buffer.objects.erase(names[i]);
    if (m_buffer.array == names[i]) m_buffer.array = 0;
    if (m_buffer.element == names[i]) m_buffer.element = 0;
  }
}

void Context::bind_buffer(GLenum target, GLuint name) {
  charge_call();
  if (target != GL_ARRAY_BUFFER && target != GL_ELEMENT_ARRAY_BUFFER) return error(GL_INVALID_ENUM);
  if (name != 0 && !m_buffer.objects.count(name)) m_buffer.objects[name] = BufferObject{};
  (target == GL_ARRAY_BUFFER ? m_buffer.array : m_buffer.element) = name;
}

bool Context::is_buffer(GLuint name) {
  charge_call();
  return name != 0 && m_buffer.objects.count(name) != 0;
}

void Context::buffer_data(GLenum target, GLsizeiptr size, const void* data, GLenum usage) {
  charge_call();
  if (target != GL_ARRAY_BUFFER && target != GL_ELEMENT_ARRAY_BUFFER) return error(GL_INVALID_ENUM);
  if (usage != GL_STATIC_DRAW && usage != GL_DYNAMIC_DRAW) return error(GL_INVALID_ENUM);
  if (size < 0) return error(GL_INVALID_VALUE);
  const GLuint name = target == GL_ARRAY_BUFFER ? m_buffer.array : m_buffer.element;
  if (name == 0) return error(GL_INVALID_OPERATION);
  BufferObject& b = m_buffer.objects[name];
  b.usage = usage;
  b.data.assign(static_cast<size_t>(size), 0);
  if (data) std::memcpy(b.data.data(), data, static_cast<size_t>(size));
  charge(costs::HostCost::gl_buffer_word, static_cast<uint64_t>(size) / 4);
}

void Context::buffer_sub_data(GLenum target, GLintptr offset, GLsizeiptr size, const void* data) {
  charge_call();
  if (target != GL_ARRAY_BUFFER && target != GL_ELEMENT_ARRAY_BUFFER) return error(GL_INVALID_ENUM);
  const GLuint name = target == GL_ARRAY_BUFFER ? m_buffer.array : m_buffer.element;
  if (name == 0) return error(GL_INVALID_OPERATION);
  BufferObject& b = m_buffer.objects[name];
  if (offset < 0 || size < 0 || static_cast<size_t>(offset) > b.data.size() ||
      static_cast<size_t>(size) > b.data.size() - static_cast<size_t>(offset))
    return error(GL_INVALID_VALUE);
  if (data) std::memcpy(b.data.data() + offset, data, static_cast<size_t>(size));
}

void Context::get_buffer_parameter(GLenum target, GLenum name, GLint* value) {
  charge_call();
  if (target != GL_ARRAY_BUFFER && target != GL_ELEMENT_ARRAY_BUFFER) return error(GL_INVALID_ENUM);
  const GLuint buffer = target == GL_ARRAY_BUFFER ? m_buffer.array : m_buffer.element;
  if (buffer == 0) return error(GL_INVALID_OPERATION);
  const BufferObject& b = m_buffer.objects[buffer];
  switch (name) {
    case GL_BUFFER_SIZE: *value = static_cast<GLint>(b.data.size()); break;
    case GL_BUFFER_USAGE: *value = static_cast<GLint>(b.usage); break;
    default: error(GL_INVALID_ENUM);
  }
}

}  // namespace tessera::gl
