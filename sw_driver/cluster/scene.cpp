#include "cluster/scene.h"

#include <cmath>

namespace tessera::cluster {

namespace {

// Chris Wellons' "lowbias32" integer hash: a bijection of 32-bit words whose
// output bits each depend on every input bit.
uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// Counter-based: draw k of triangle `index` is hash32(key + k * golden),
// key = hash32(seed ^ hash32(index)), so no state is carried between
// triangles and node k can start at any index.
class Random {
 public:
  Random(uint32_t seed, uint32_t index) : m_key(hash32(seed ^ hash32(index ^ 0x5bd1e995u))) {}
  uint32_t next() { return hash32(m_key + 0x9e3779b9u * ++m_counter); }
  // Uniform in [0, 1), 24 bits: exact in single precision.
  float unit() { return static_cast<float>(next() >> 8) * (1.0f / 16777216.0f); }
  float range(float low, float high) { return low + (high - low) * unit(); }

 private:
  uint32_t m_key;
  uint32_t m_counter = 0;
};

struct Vector {
  float x, y, z;
};

float dot(const Vector& a, const Vector& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

Vector cross(const Vector& a, const Vector& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Uniform on the sphere: a point uniform in the cube, kept when inside the
// unit ball (and not too near its centre), projected outwards.
Vector random_direction(Random& random) {
  for (;;) {
    const Vector v{random.range(-1, 1), random.range(-1, 1), random.range(-1, 1)};
    const float length2 = dot(v, v);
    if (length2 > 1e-4f && length2 <= 1.0f) {
      const float scale = 1.0f / std::sqrt(length2);
      return {v.x * scale, v.y * scale, v.z * scale};
    }
  }
}

// A unit vector perpendicular to n, uniform in angle about it.
Vector random_perpendicular(Random& random, const Vector& n) {
  for (;;) {
    const Vector w = random_direction(random);
    const float along = dot(w, n);
    const Vector u{w.x - along * n.x, w.y - along * n.y, w.z - along * n.z};
    const float length2 = dot(u, u);
    if (length2 > 1e-4f) {
      const float scale = 1.0f / std::sqrt(length2);
      return {u.x * scale, u.y * scale, u.z * scale};
    }
  }
}

// The centroid's distance to the farthest vertex of a right isosceles
// triangle with legs L is sqrt(5) / 3 L = 0.7454 L.
constexpr float MARGIN = 0.75f;

}  // namespace

void light_vertex(const float normal[3], const float base_color[3], const Light& light, WorldVertex* out) {
  const float n_dot_l =
      normal[0] * light.direction[0] + normal[1] * light.direction[1] + normal[2] * light.direction[2];
  float intensity = light.ambient + light.diffuse * (n_dot_l > 0 ? n_dot_l : 0.0f);
  if (intensity > 1) intensity = 1;
  out->r = base_color[0] * intensity;
  out->g = base_color[1] * intensity;
  out->b = base_color[2] * intensity;
}

const char* random_scene_error(const RandomScene& scene) {
  if (scene.width < 1 || scene.width > MAX_SCREEN) return "width: must be in 1 .. 512";
  if (scene.height < 1 || scene.height > MAX_SCREEN) return "height: must be in 1 .. 512";
  if (!(scene.size > 0)) return "size: must be positive";
  const float smallest = static_cast<float>(scene.width < scene.height ? scene.width : scene.height);
  if (2 * MARGIN * scene.size > smallest) return "size: the triangle must fit the screen (1.5 size <= width, height)";
  return nullptr;
}

View random_scene_view(const RandomScene& scene) {
  const float depth = static_cast<float>(scene.width > scene.height ? scene.width : scene.height);
  View view;
  view.matrix =
      orthographic(0, static_cast<float>(scene.width), 0, static_cast<float>(scene.height), -depth / 2, depth / 2);
  view.width = scene.width;
  view.height = scene.height;
  return view;
}

WorldTriangle random_triangle(const RandomScene& scene, uint32_t index) {
  Random random(scene.seed, index);
  const Vector n = random_direction(random);
  const Vector u = random_perpendicular(random, n);
  const Vector v = cross(n, u);  // (u, v, n) right-handed: counter-clockwise seen from +n
  const float margin = MARGIN * scene.size;
  const float width = static_cast<float>(scene.width), height = static_cast<float>(scene.height);
  const float depth = width > height ? width : height;
  const Vector centre{random.range(margin, width - margin), random.range(margin, height - margin),
                      random.range(-depth / 2 + margin, depth / 2 - margin)};
  // The right angle at (0, 0), the legs along u and v; the centroid at (L/3, L/3).
  const float leg = scene.size, third = scene.size / 3;
  const float corners[3][2] = {{-third, -third}, {leg - third, -third}, {-third, leg - third}};
  const float normal[3] = {n.x, n.y, n.z};
  WorldTriangle triangle;
  for (int k = 0; k < 3; ++k) {
    WorldVertex& out = triangle.v[k];
    out.x = centre.x + corners[k][0] * u.x + corners[k][1] * v.x;
    out.y = centre.y + corners[k][0] * u.y + corners[k][1] * v.y;
    out.z = centre.z + corners[k][0] * u.z + corners[k][1] * v.z;
    const float base[3] = {random.unit(), random.unit(), random.unit()};
    light_vertex(normal, base, scene.light, &out);
  }
  return triangle;
}

SceneStatistics measure_random_scene(const RandomScene& scene) {
  SceneStatistics statistics;
  const View view = random_scene_view(scene);
  WorkCounters counters;
  for (uint32_t i = 0; i < scene.count; ++i) {
    ScreenTriangle screen;
    if (transform_triangle(random_triangle(scene, i), view, &screen, counters) != GeometryResult::accepted) continue;
    int32_t low = screen.v[0].y, high = screen.v[0].y;
    for (const ScreenVertex& vertex : screen.v) {
      if (vertex.y < low) low = vertex.y;
      if (vertex.y > high) high = vertex.y;
    }
    ++statistics.survivors;
    statistics.height_sum += static_cast<uint64_t>(high - low);
  }
  return statistics;
}

WorldTriangle mesh_triangle(const MeshArrays& mesh, uint32_t t, const float base_color[3], const Light& light) {
  WorldTriangle triangle;
  for (int k = 0; k < 3; ++k) {
    const uint32_t i = mesh.indices[3 * t + k];
    WorldVertex& out = triangle.v[k];
    out.x = mesh.positions[3 * i];
    out.y = mesh.positions[3 * i + 1];
    out.z = mesh.positions[3 * i + 2];
    light_vertex(&mesh.normals[3 * i], base_color, light, &out);
  }
  return triangle;
}

}  // namespace tessera::cluster
