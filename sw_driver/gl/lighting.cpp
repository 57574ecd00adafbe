// Lights, the light model and materials.
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

void Context::light(GLenum which, GLenum name, const float* v, int count) {
  charge_call();
  if (which < GL_LIGHT0 || which >= GL_LIGHT0 + MAX_LIGHTS) return error(GL_INVALID_ENUM);
  Light& l = m_lighting.model.lights[which - GL_LIGHT0];
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
      if (need(4)) l.position = m_transform.modelview.back() * glm::vec4(v[0], v[1], v[2], v[3]);
      break;
    case GL_SPOT_DIRECTION:
      if (need(3)) l.spot_direction = glm::mat3(m_transform.modelview.back()) * glm::vec3(v[0], v[1], v[2]);
      break;
    // The range checks are written to fail for NaN, which no range holds
    // (a NaN compares false both ways, and passed "< 0 || > 128").
    case GL_SPOT_EXPONENT:
      if (!(v[0] >= 0 && v[0] <= 128)) return error(GL_INVALID_VALUE);
      l.spot_exponent = v[0];
      break;
    case GL_SPOT_CUTOFF:
      if (!(v[0] >= 0 && v[0] <= 90) && v[0] != 180) return error(GL_INVALID_VALUE);
      l.spot_cutoff = v[0];
      break;
    case GL_CONSTANT_ATTENUATION:
    case GL_LINEAR_ATTENUATION:
    case GL_QUADRATIC_ATTENUATION:
      if (!(v[0] >= 0)) return error(GL_INVALID_VALUE);
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
  const Light& l = m_lighting.model.lights[which - GL_LIGHT0];
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
      m_lighting.model.ambient = {v[0], v[1], v[2], v[3]};
      break;
    case GL_LIGHT_MODEL_TWO_SIDE: m_lighting.two_side = v[0] != 0; break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::material(GLenum face, GLenum name, const float* v, int count) {
  charge_call();
  // ES 1.1 accepts only GL_FRONT_AND_BACK.
  if (face != GL_FRONT_AND_BACK) return error(GL_INVALID_ENUM);
  Material& m = m_lighting.front_material;
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
      if (!(v[0] >= 0 && v[0] <= 128)) return error(GL_INVALID_VALUE);  // NaN too
      m.shininess = v[0];
      break;
    default: error(GL_INVALID_ENUM);
  }
}

void Context::get_material(GLenum face, GLenum name, float* v) {
  charge_call();
  if (face != GL_FRONT && face != GL_BACK) return error(GL_INVALID_ENUM);
  const Material& m = m_lighting.front_material;
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

}  // namespace tessera::gl
