// The scenes the sort-middle program draws (cluster.scene): the paper's
// random triangles (scene.h) or the teapot (the built-in scene's mesh,
// tessellated by scenes/teapot_mesh.h), each with the view it is seen
// through, triangle by triangle so that a node makes only its own share.
// GL-free: the node program and the Mesa reference draw the same triangles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cluster/geometry.h"
#include "cluster/scene.h"

namespace tessera::cluster {

class ClusterScene {
 public:
  ClusterScene() = default;
  // cluster.scene's `name` ("random_triangles" or "teapot"), with
  // `triangles` of `triangle_pixels` (the random scene's) for a width x
  // height screen. std::invalid_argument for another name.
  ClusterScene(const std::string& name, unsigned triangles, unsigned triangle_pixels, unsigned seed, unsigned width,
               unsigned height);

  uint32_t triangles() const { return m_triangles; }
  const View& view() const { return m_view; }
  WorldTriangle triangle(uint32_t index) const;

 private:
  bool m_teapot = false;
  uint32_t m_triangles = 0;
  RandomScene m_random;
  View m_view;
  std::vector<float> m_positions, m_normals;
  std::vector<uint16_t> m_indices;
  MeshArrays m_mesh;
  Light m_light;
};

}  // namespace tessera::cluster
