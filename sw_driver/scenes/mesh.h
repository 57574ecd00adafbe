// Indexed triangle meshes in the form GL ES 1.1 draws them: float positions
// and normals in client-side arrays, GL_UNSIGNED_SHORT indices. Plain C++,
// no GL, so the geometry is tested without a context.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera::scenes {

// GL ES 1.1 has no 32-bit indices, so a mesh addresses at most 65536 vertices.
constexpr std::size_t MAX_MESH_VERTICES = 65536;

struct Mesh {
  // x, y, z per vertex.
  std::vector<float> positions;
  // Unit x, y, z per vertex, same count as positions.
  std::vector<float> normals;
  // Three per triangle, counter-clockwise when seen from the side the normals point to.
  std::vector<std::uint16_t> indices;

  std::size_t vertex_count() const { return positions.size() / 3; }
  std::size_t triangle_count() const { return indices.size() / 3; }
};

struct Bounds {
  std::array<float, 3> min;
  std::array<float, 3> max;
};

// Axis-aligned box around all vertices; an empty mesh gives a zero box.
Bounds mesh_bounds(const Mesh& mesh);

// Replaces the normals by the average of the normals of the triangles that
// share each vertex, each weighted by the triangle's angle at the vertex, so
// that the result does not depend on how a polygon was cut into triangles.
// A vertex with no non-degenerate triangle gets +z, so every normal is unit
// length.
void compute_smooth_normals(Mesh* mesh);

// Moves the centre of the bounding box to the origin and scales uniformly so
// that the farthest vertex lies on the unit sphere. Normals are unchanged,
// which is correct because the scale is uniform.
void fit_to_unit_sphere(Mesh* mesh);

// The same for a model drawn in several meshes: one centre and one scale
// for all of them, from all their vertices.
void fit_to_unit_sphere(std::vector<Mesh>* meshes);

}  // namespace tessera::scenes
