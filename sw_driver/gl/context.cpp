// The GL context's construction, errors and the host charges every area
// uses; the areas of the state live in their own files (context_internal.h
// lists them).
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

namespace {
Context* g_current = nullptr;
}  // namespace

Context* current_context() {
  return g_current;
}
void set_current_context(Context* context) {
  g_current = context;
}

Context::Context(HostApi& host, Renderer& renderer, ActivityCounters* counters, unsigned texture_units)
    : m_host(host),
      m_renderer(&renderer),
      // The configuration refuses other counts (driver.texture_units); a
      // direct caller's is brought into range.
      m_texture(std::clamp(texture_units, 1u, MAX_TEXTURE_UNITS)) {
  if (counters) {
    m_counters.cache_hits = &counters->counter(
        "vertex_cache.hits", "glDrawElements indices whose vertex was in the post-transform vertex cache");
    m_counters.cache_misses = &counters->counter(
        "vertex_cache.misses", "glDrawElements indices whose vertex had to be fetched and transformed");
    m_counters.vertices_transformed = &counters->counter(
        "vertices_transformed", "vertices fetched, transformed and lit (cache misses and glDrawArrays vertices)");
  }
  m_viewport.width = static_cast<int>(m_renderer->width());
  m_viewport.height = static_cast<int>(m_renderer->height());
  m_raster.scissor_width = m_viewport.width;
  m_raster.scissor_height = m_viewport.height;
  m_lighting.model.lights.resize(MAX_LIGHTS);
  m_lighting.model.lights[0].diffuse = glm::vec4(1);
  m_lighting.model.lights[0].specular = glm::vec4(1);
}

void Context::error(GLenum code) {
  if (m_error == GL_NO_ERROR) m_error = code;
}

GLenum Context::get_error() {
  const GLenum e = m_error;
  m_error = GL_NO_ERROR;
  return e;
}

}  // namespace tessera::gl
