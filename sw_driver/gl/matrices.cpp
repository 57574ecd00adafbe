// The matrix stacks: modelview, projection and texture.
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

void Context::matrix_mode(GLenum mode) {
  charge_call();
  if (mode != GL_MODELVIEW && mode != GL_PROJECTION && mode != GL_TEXTURE) return error(GL_INVALID_ENUM);
  m_transform.matrix_mode = mode;
}

glm::mat4& Context::current_matrix() {
  switch (m_transform.matrix_mode) {
    case GL_PROJECTION: return m_transform.projection.back();
    case GL_TEXTURE: return active_unit().matrix.back();
    default: return m_transform.modelview.back();
  }
}

void Context::load_matrix(const glm::mat4& m) {
  charge_call();
  current_matrix() = m;
}

void Context::mult_matrix(const glm::mat4& m) {
  charge_call();
  charge(costs::HostCost::gl_matrix_multiply);
  current_matrix() = current_matrix() * m;
}

void Context::push_matrix() {
  charge_call();
  auto& stack = m_transform.matrix_mode == GL_PROJECTION ? m_transform.projection
                : m_transform.matrix_mode == GL_TEXTURE  ? active_unit().matrix
                                                         : m_transform.modelview;
  const size_t limit = m_transform.matrix_mode == GL_PROJECTION ? MAX_PROJECTION_DEPTH
                       : m_transform.matrix_mode == GL_TEXTURE  ? MAX_TEXTURE_DEPTH
                                                                : MAX_MODELVIEW_DEPTH;
  if (stack.size() >= limit) return error(GL_STACK_OVERFLOW);
  stack.push_back(stack.back());
}

void Context::pop_matrix() {
  charge_call();
  auto& stack = m_transform.matrix_mode == GL_PROJECTION ? m_transform.projection
                : m_transform.matrix_mode == GL_TEXTURE  ? active_unit().matrix
                                                         : m_transform.modelview;
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

}  // namespace tessera::gl
