// Vertex fetch and transform: reading the arrays, transforming and lighting
// each vertex (once per index of glDrawElements that misses the vertex
// cache, vertex_cache.h), and what that costs the ARM in soft-float.
#include "gl/context.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "common/little_endian.h"
#include "gl/context_internal.h"
#include "gl/runtime.h"

namespace tessera::gl {

const uint8_t* Context::array_element(const ArrayPointer& array, uint32_t index, size_t element_size) {
  const size_t stride = array.stride ? static_cast<size_t>(array.stride) : element_size;
  const size_t offset = stride * index;
  if (array.buffer) {
    auto it = m_buffer.objects.find(array.buffer);
    const size_t start = reinterpret_cast<size_t>(array.pointer);
    // Compared piece by piece: a huge pointer offset would wrap the sum.
    if (it == m_buffer.objects.end()) return nullptr;
    const size_t size = it->second.data.size();
    if (start > size || offset > size - start || element_size > size - start - offset) return nullptr;
    return it->second.data.data() + start + offset;
  }
  if (!array.pointer) return nullptr;
  return static_cast<const uint8_t*>(array.pointer) + offset;
}

glm::vec4 Context::read_attribute(const ArrayPointer& array, uint32_t index, const glm::vec4& defaults,
                                  bool normalized) {
  const size_t component = type_size(array.type);
  const uint8_t* p = array_element(array, index, component * static_cast<size_t>(array.size));
  glm::vec4 value = defaults;
  if (!p) return glm::vec4(std::numeric_limits<float>::quiet_NaN());
  for (int c = 0; c < array.size; ++c) {
    const uint8_t* q = p + c * component;
    float v = 0;
    switch (array.type) {
      case GL_FLOAT: v = load_float(q); break;
      case GL_FIXED: {
        const auto x = static_cast<int32_t>(load_le32(q));
        v = static_cast<float>(x) / 65536.0f;
        break;
      }
      // Signed normal components map to [-1, 1] as ES 1.1 table 2.7 gives:
      // (2 c + 1) / (2^b - 1); coordinates keep their integer values.
      case GL_SHORT: {
        const auto x = static_cast<int16_t>(load_le16(q));
        v = normalized ? (2.0f * x + 1.0f) / 65535.0f : static_cast<float>(x);
        break;
      }
      case GL_BYTE: {
        const float x = static_cast<int8_t>(*q);
        v = normalized ? (2.0f * x + 1.0f) / 255.0f : x;
        break;
      }
      case GL_UNSIGNED_BYTE: v = *q / 255.0f; break;  // colours: normalised
      default: break;
    }
    value[c] = v;
  }
  return value;
}

void Context::fetch_and_transform(const std::vector<uint32_t>& indices, bool indexed, std::vector<Vertex>& out) {
  out.resize(indices.size());
  const glm::mat4& modelview = m_transform.modelview.back();
  const glm::mat4& projection = m_transform.projection.back();
  // The units that draw: only their coordinates are fetched and transformed.
  unsigned textured_units = 0;
  bool textured[MAX_TEXTURE_UNITS] = {};
  for (unsigned u = 0; u < MAX_TEXTURE_UNITS; ++u) textured_units += textured[u] = unit_textured(u);
  glm::mat3 normal_matrix(1);
  if (m_enabled.lighting) normal_matrix = glm::transpose(glm::inverse(glm::mat3(modelview)));
  unsigned lights = 0;
  for (const Light& l : m_lighting.model.lights) lights += l.enabled;
  Material material = m_lighting.front_material;
  const bool two_sided = two_sided_lighting();
  auto transform = [&](uint32_t index, Vertex& v) {
    glm::vec4 position = read_attribute(m_attributes.vertex_array, index, {0, 0, 0, 1});
    glm::vec4 color = m_attributes.color_array.enabled ? read_attribute(m_attributes.color_array, index, {0, 0, 0, 1})
                                                       : m_attributes.color;
    v.eye = modelview * position;
    v.clip.position = projection * v.eye;
    if (m_enabled.lighting) {
      glm::vec3 n = m_attributes.normal_array.enabled
                        ? glm::vec3(read_attribute(m_attributes.normal_array, index, {0, 0, 1, 0}, true))
                        : m_attributes.normal;
      n = normal_matrix * n;
      if (m_enabled.normalize || m_enabled.rescale_normal) {
        const float length = glm::length(n);
        if (length > 0) n /= length;
      }
      if (m_enabled.color_material) material.ambient = material.diffuse = color;
      v.clip.color = light_vertex(m_lighting.model, material, v.eye, n);
      // Two-sided lighting: the colour a back face shows, lit with the
      // reversed normal (the material is the same for both faces in ES).
      v.clip.back_color = two_sided ? light_vertex(m_lighting.model, material, v.eye, -n) : v.clip.color;
    } else {
      v.clip.color = glm::clamp(color, glm::vec4(0), glm::vec4(1));
      v.clip.back_color = v.clip.color;
    }
    bool tex_finite = true;
    for (unsigned u = 0; u < MAX_TEXTURE_UNITS; ++u) {
      if (!textured[u]) {
        v.clip.tex[u] = {0, 0};
        continue;
      }
      const TextureUnitState& unit = m_texture.units[u];
      glm::vec4 tc =
          unit.texcoord_array.enabled ? read_attribute(unit.texcoord_array, index, {0, 0, 0, 1}) : unit.texcoord;
      tc = unit.matrix.back() * tc;
      v.clip.tex[u] = tc.w != 0 ? glm::vec2(tc) / tc.w : glm::vec2(tc);
      tex_finite = tex_finite && std::isfinite(v.clip.tex[u].x) && std::isfinite(v.clip.tex[u].y);
    }
    v.clip.eye = v.eye;
    // Fog from the eye distance as Mesa takes it: |z_eye|, not divided by w.
    v.clip.fog = m_enabled.fog ? std::fabs(v.eye.z) : 0.0f;
    const glm::vec4& p = v.clip.position;
    v.valid = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w) &&
              std::isfinite(v.clip.color.r) && tex_finite;
  };

  uint64_t transformed = 0;
  if (indexed) {
    // Each index is looked up; only a miss is fetched and transformed.
    m_vertex_cache.invalidate();
    for (size_t i = 0; i < indices.size(); ++i) {
      if (const Vertex* cached = m_vertex_cache.find(indices[i])) {
        out[i] = *cached;
        continue;
      }
      Vertex& slot = m_vertex_cache.insert(indices[i]);
      transform(indices[i], slot);
      out[i] = slot;
      ++transformed;
    }
    const uint64_t hits = indices.size() - transformed;
    charge(costs::HostCost::gl_vertex_cache_lookup, indices.size());
    if (m_counters.cache_hits) *m_counters.cache_hits += hits;
    if (m_counters.cache_misses) *m_counters.cache_misses += transformed;
  } else {
    for (size_t i = 0; i < indices.size(); ++i) transform(indices[i], out[i]);
    transformed = indices.size();
  }
  if (m_counters.vertices_transformed) *m_counters.vertices_transformed += transformed;

  charge(costs::HostCost::gl_vertex, transformed);
  if (m_enabled.lighting) {
    const uint64_t sides = two_sided ? 2 : 1;
    charge(costs::HostCost::gl_vertex_lit, sides * transformed);
    charge(costs::HostCost::gl_vertex_light, sides * lights * transformed);
  }
  charge(costs::HostCost::gl_vertex_texcoord, uint64_t{textured_units} * transformed);
  if (m_enabled.fog) charge(costs::HostCost::gl_vertex_fog, transformed);
}

}  // namespace tessera::gl
