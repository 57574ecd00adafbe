// The sort-middle renderer's scenes (README.md, step 1): the paper's random
// triangles, generated triangle by triangle from (seed, index) so that a
// node makes only its own share, and an indexed mesh (the teapot) lit the
// same way. Float per vertex only.
#pragma once

#include <cstdint>

#include "cluster/geometry.h"
#include "cluster/records.h"

namespace tessera::cluster {

// One directional light, ambient + diffuse, evaluated at the vertices:
// colour = base * min(1, ambient + diffuse * max(0, n . l)).
struct Light {
  float direction[3] = {0.0f, 0.0f, 1.0f};  // unit, towards the light
  float ambient = 0.2f, diffuse = 0.8f;
};

// The paper's standard scene (fig. 6) is 100000 triangles of size 10 on a
// 512 x 512 screen.
struct RandomScene {
  uint32_t seed = 1;
  uint32_t count = 100000;
  float size = 10.0f;  // the legs of the right isosceles triangle, in pixels
  unsigned width = 512, height = 512;
  Light light;
};

// Null when the scene can be made; else what is wrong, naming the field.
const char* random_scene_error(const RandomScene& scene);

// The view the scene is made for: orthographic, world units are pixels,
// x in [0, width] to the right, y in [0, height] upwards, the eye looking
// down -z, z in [-depth / 2, depth / 2] with depth = max(width, height).
View random_scene_view(const RandomScene& scene);

// Triangle `index` (any index: count is only how many a frame draws) of the
// scene: a right isosceles triangle with legs of scene.size pixels, in a
// uniformly random orientation (its normal uniform on the sphere, turned
// uniformly about it), its centroid uniform in the box that keeps the whole
// triangle inside the view volume, each vertex a random base colour lit
// with the triangle's normal. A function of (seed, index) alone, with the
// same bits on every host.
WorldTriangle random_triangle(const RandomScene& scene, uint32_t index);

// Over the scene's `count` triangles through random_scene_view: how many
// survive culling and their mean projected height, (max y - min y) of the
// snapped vertices, in pixels (the paper's h).
struct SceneStatistics {
  uint32_t survivors = 0;
  uint64_t height_sum = 0;  // 9.4 units
  float mean_height() const {
    return survivors == 0 ? 0.0f : static_cast<float>(height_sum) / (16.0f * static_cast<float>(survivors));
  }
};
SceneStatistics measure_random_scene(const RandomScene& scene);

// An indexed triangle mesh in client arrays (scenes::Mesh's layout): x, y, z
// positions, unit normals, three 16-bit indices per triangle.
struct MeshArrays {
  const float* positions = nullptr;
  const float* normals = nullptr;
  const uint16_t* indices = nullptr;
  uint32_t triangle_count = 0;
};

// Triangle t of the mesh, each vertex lit with its normal (the light's
// direction in the mesh's own coordinates) on a base colour (0 .. 1).
WorldTriangle mesh_triangle(const MeshArrays& mesh, uint32_t t, const float base_color[3], const Light& light);

// The lit colour of one vertex (what both of the above use).
void light_vertex(const float normal[3], const float base_color[3], const Light& light, WorldVertex* out);

}  // namespace tessera::cluster
