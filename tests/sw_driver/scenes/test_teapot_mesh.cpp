// The teapot's tessellation: triangle count, normals, extent and orientation.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "scenes/teapot_mesh.h"

namespace tessera::scenes {
namespace {

using Vec3 = std::array<double, 3>;

Vec3 position(const Mesh& mesh, std::size_t vertex) {
  return {mesh.positions[3 * vertex], mesh.positions[3 * vertex + 1], mesh.positions[3 * vertex + 2]};
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// At n = 1 the spout's two lip patches also vanish: their four corners lie
// on one line. From n = 2 on only the pole triangles go.
TEST(TeapotMesh, TriangleCountIsTwoPerQuadLessThePoleTriangles) {
  EXPECT_EQ(teapot_mesh(1).triangle_count(), std::size_t(32 * 2 - 8 - 2 * 2));
  for (int n : {2, 4, 8}) {
    const Mesh mesh = teapot_mesh(n);
    EXPECT_EQ(mesh.triangle_count(), std::size_t(32 * 2 * n * n - 8 * n)) << "n = " << n;
    EXPECT_EQ(mesh.vertex_count(), std::size_t(32 * (n + 1) * (n + 1))) << "n = " << n;
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
  }
  EXPECT_EQ(teapot_mesh(4).triangle_count(), 992u);
}

// The parts are the one mesh's patches, in order, cut where the next patch
// would pass 65,536 vertices: concatenated (indices offset) they are the mesh.
TEST(TeapotMeshParts, AreTheMeshCutIntoWholePatches) {
  for (int n : {4, 30, TEAPOT_MAX_SUBDIVISIONS}) {
    const Mesh whole = teapot_mesh(n);
    const std::vector<Mesh> parts = teapot_mesh_parts(n);
    const std::size_t patch_vertices = std::size_t(n + 1) * (n + 1);
    const std::size_t per_part = MAX_MESH_VERTICES / patch_vertices;
    ASSERT_EQ(parts.size(), (TEAPOT_PATCHES + per_part - 1) / per_part) << "n = " << n;
    Mesh joined;
    for (const Mesh& part : parts) {
      const std::size_t offset = joined.vertex_count();
      joined.positions.insert(joined.positions.end(), part.positions.begin(), part.positions.end());
      joined.normals.insert(joined.normals.end(), part.normals.begin(), part.normals.end());
      for (std::uint16_t index : part.indices) joined.indices.push_back(static_cast<std::uint16_t>(index + offset));
    }
    EXPECT_EQ(joined.positions, whole.positions) << "n = " << n;
    EXPECT_EQ(joined.normals, whole.normals) << "n = " << n;
    EXPECT_EQ(joined.indices, whole.indices) << "n = " << n;
  }
}

// The stand-ins' tessellations (the smallest n reaching each of the MorphoSys
// paper's counts: 34, 39, 102, 131, 134) and the largest: every part within
// 16-bit indices, and the count 64 n^2 - 8 n, which the scene relies on.
TEST(TeapotMeshParts, FitSixteenBitIndicesAndHaveTheCountedTriangles) {
  for (int n : {34, 39, 102, 131, 134, TEAPOT_MAX_PART_SUBDIVISIONS}) {
    const std::vector<Mesh> parts = teapot_mesh_parts(n);
    std::size_t triangles = 0;
    for (const Mesh& part : parts) {
      EXPECT_LE(part.vertex_count(), MAX_MESH_VERTICES) << "n = " << n;
      triangles += part.triangle_count();
    }
    EXPECT_EQ(triangles, teapot_triangle_count(n)) << "n = " << n;
  }
  EXPECT_LT(teapot_triangle_count(33), 69451u);
  EXPECT_GE(teapot_triangle_count(34), 69451u);
  EXPECT_LT(teapot_triangle_count(133), 1136745u);
  EXPECT_GE(teapot_triangle_count(134), 1136745u);
  EXPECT_THROW(teapot_mesh_parts(0), std::invalid_argument);
  EXPECT_THROW(teapot_mesh_parts(TEAPOT_MAX_PART_SUBDIVISIONS + 1), std::invalid_argument);
}

TEST(TeapotMesh, RejectsSubdivisionsOutsideTheRange) {
  EXPECT_THROW(teapot_mesh(0), std::invalid_argument);
  EXPECT_THROW(teapot_mesh(TEAPOT_MAX_SUBDIVISIONS + 1), std::invalid_argument);
  EXPECT_NO_THROW(teapot_mesh(TEAPOT_MAX_SUBDIVISIONS));
}

TEST(TeapotMesh, NormalsAreFiniteAndUnitLengthIncludingThePoles) {
  const Mesh mesh = teapot_mesh(4);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const float* n = &mesh.normals[3 * v];
    ASSERT_TRUE(std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2])) << "vertex " << v;
    EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-5) << "vertex " << v;
  }
  // The knob's top (0, 0, 3.15) faces up, the bottom's centre (0, 0, 0) down.
  int poles = 0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = position(mesh, v);
    if (p[0] != 0.0 || p[1] != 0.0) continue;
    if (p[2] == 0.0 || std::fabs(p[2] - 3.15) < 1e-6) {
      ++poles;
      EXPECT_NEAR(mesh.normals[3 * v + 2], p[2] == 0.0 ? -1.0 : 1.0, 1e-3) << "vertex " << v;
    }
  }
  // Each of the 8 pole patches has n + 1 vertices at its pole.
  EXPECT_EQ(poles, 8 * 5);
}

TEST(TeapotMesh, NoDegenerateTriangles) {
  const Mesh mesh = teapot_mesh(4);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint16_t* c = &mesh.indices[3 * t];
    const Vec3 a = position(mesh, c[0]);
    const double area2 = std::sqrt(dot(cross(sub(position(mesh, c[1]), a), sub(position(mesh, c[2]), a)),
                                       cross(sub(position(mesh, c[1]), a), sub(position(mesh, c[2]), a))));
    EXPECT_GT(area2, 1e-6) << "triangle " << t;
  }
}

// The extremes of the surface are corners of patches, which the surface
// interpolates: the handle's outer edge at x = -3, the body's widest ring at
// |y| = 2, the base at z = 0 and the knob at z = 3.15. The spout's lip
// bulges past its corner at x = 3.3 towards the control point at x = 3.525,
// which bounds it, since a Bezier patch lies in its control points' hull.
TEST(TeapotMesh, BoundingBoxMatchesTheControlPoints) {
  const Bounds bounds = mesh_bounds(teapot_mesh(4));
  EXPECT_NEAR(bounds.min[0], -3.0, 1e-5);
  EXPECT_GE(bounds.max[0], 3.3 - 1e-5);
  EXPECT_LE(bounds.max[0], 3.525);
  EXPECT_NEAR(bounds.min[1], -2.0, 1e-5);
  EXPECT_NEAR(bounds.max[1], 2.0, 1e-5);
  EXPECT_NEAR(bounds.min[2], 0.0, 1e-5);
  EXPECT_NEAR(bounds.max[2], 3.15, 1e-5);
}

// Welds vertices that coincide and checks that every edge shared by two
// triangles is walked once in each direction: the whole surface is wound
// consistently, across patch borders too.
TEST(TeapotMesh, WindingIsConsistentAcrossPatches) {
  const Mesh mesh = teapot_mesh(4);
  std::map<std::tuple<long, long, long>, int> weld;
  std::vector<int> welded(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = position(mesh, v);
    const auto key = std::make_tuple(std::lround(p[0] * 1e4), std::lround(p[1] * 1e4), std::lround(p[2] * 1e4));
    welded[v] = weld.emplace(key, static_cast<int>(weld.size())).first->second;
  }
  std::map<std::pair<int, int>, int> directed_edges;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k)
      ++directed_edges[{welded[mesh.indices[3 * t + k]], welded[mesh.indices[3 * t + (k + 1) % 3]]}];
  int shared = 0;
  for (const auto& [edge, count] : directed_edges) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << " -> " << edge.second;
    if (directed_edges.count({edge.second, edge.first})) ++shared;
  }
  // Almost all edges are shared: the teapot is closed but for the rims of
  // the body and the lid, the spout's opening and the handle's ends.
  EXPECT_GT(shared, int(directed_edges.size() * 9 / 10));
}

// With outward normals and consistent winding the divergence theorem gives a
// positive volume; it is bounded by the box around the teapot.
TEST(TeapotMesh, NormalsPointOutwardsAndAgreeWithTheWinding) {
  const Mesh mesh = teapot_mesh(8);
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint16_t* c = &mesh.indices[3 * t];
    const Vec3 a = position(mesh, c[0]), b = position(mesh, c[1]), d = position(mesh, c[2]);
    volume += dot(a, cross(b, d)) / 6.0;
    const Vec3 face = cross(sub(b, a), sub(d, a));
    Vec3 mean_normal{};
    for (int k = 0; k < 3; ++k)
      for (int axis = 0; axis < 3; ++axis) mean_normal[axis] += mesh.normals[3 * c[k] + axis];
    EXPECT_GT(dot(face, mean_normal), 0.0) << "triangle " << t;
  }
  EXPECT_GT(volume, 10.0);
  EXPECT_LT(volume, 6.525 * 4.0 * 3.15);
}

}  // namespace
}  // namespace tessera::scenes
