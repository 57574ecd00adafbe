#include "scenes/mesh.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tessera::scenes {

namespace {

using Vec3 = std::array<float, 3>;

Vec3 position(const Mesh& mesh, std::size_t vertex) {
  return {mesh.positions[3 * vertex], mesh.positions[3 * vertex + 1], mesh.positions[3 * vertex + 2]};
}

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

float dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

float length(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

float angle_between(const Vec3& a, const Vec3& b) {
  const float lengths = length(a) * length(b);
  if (!(lengths > 0.0f)) return 0.0f;
  return std::acos(std::clamp(dot(a, b) / lengths, -1.0f, 1.0f));
}

}  // namespace

Bounds mesh_bounds(const Mesh& mesh) {
  if (mesh.vertex_count() == 0) return Bounds{{0, 0, 0}, {0, 0, 0}};
  Bounds bounds{position(mesh, 0), position(mesh, 0)};
  for (std::size_t v = 1; v < mesh.vertex_count(); ++v) {
    const Vec3 p = position(mesh, v);
    for (int axis = 0; axis < 3; ++axis) {
      bounds.min[axis] = std::min(bounds.min[axis], p[axis]);
      bounds.max[axis] = std::max(bounds.max[axis], p[axis]);
    }
  }
  return bounds;
}

void compute_smooth_normals(Mesh* mesh) {
  std::vector<float> sums(mesh->positions.size(), 0.0f);
  for (std::size_t t = 0; t < mesh->triangle_count(); ++t) {
    const std::uint16_t* corner = &mesh->indices[3 * t];
    const Vec3 p[3] = {position(*mesh, corner[0]), position(*mesh, corner[1]), position(*mesh, corner[2])};
    const Vec3 face = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    const float face_length = length(face);
    if (!(face_length > 0.0f)) continue;
    for (int k = 0; k < 3; ++k) {
      const float angle = angle_between(sub(p[(k + 1) % 3], p[k]), sub(p[(k + 2) % 3], p[k]));
      for (int axis = 0; axis < 3; ++axis) sums[3 * corner[k] + axis] += angle * face[axis] / face_length;
    }
  }
  mesh->normals.assign(mesh->positions.size(), 0.0f);
  for (std::size_t v = 0; v < mesh->vertex_count(); ++v) {
    const float* sum = &sums[3 * v];
    const float sum_length = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    float* normal = &mesh->normals[3 * v];
    if (sum_length > 0.0f && std::isfinite(sum_length)) {
      for (int axis = 0; axis < 3; ++axis) normal[axis] = sum[axis] / sum_length;
    } else {
      normal[2] = 1.0f;
    }
  }
}

void fit_to_unit_sphere(Mesh* mesh) {
  std::vector<Mesh> one(1);
  one[0] = std::move(*mesh);
  fit_to_unit_sphere(&one);
  *mesh = std::move(one[0]);
}

void fit_to_unit_sphere(std::vector<Mesh>* meshes) {
  bool any = false;
  Bounds bounds{{0, 0, 0}, {0, 0, 0}};
  for (const Mesh& mesh : *meshes) {
    if (mesh.vertex_count() == 0) continue;
    const Bounds part = mesh_bounds(mesh);
    for (int axis = 0; axis < 3; ++axis) {
      bounds.min[axis] = any ? std::min(bounds.min[axis], part.min[axis]) : part.min[axis];
      bounds.max[axis] = any ? std::max(bounds.max[axis], part.max[axis]) : part.max[axis];
    }
    any = true;
  }
  Vec3 centre;
  for (int axis = 0; axis < 3; ++axis) centre[axis] = 0.5f * (bounds.min[axis] + bounds.max[axis]);
  float radius = 0.0f;
  for (const Mesh& mesh : *meshes)
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      radius = std::max(radius, length(sub(position(mesh, v), centre)));
  const float scale = radius > 0.0f ? 1.0f / radius : 1.0f;
  for (Mesh& mesh : *meshes)
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      for (int axis = 0; axis < 3; ++axis) {
        float& coordinate = mesh.positions[3 * v + axis];
        coordinate = (coordinate - centre[axis]) * scale;
      }
}

}  // namespace tessera::scenes
