#include "cluster/cluster_scene.h"

#include <stdexcept>

#include "scenes/teapot_mesh.h"

namespace tessera::cluster {

namespace {

// The teapot: the mesh at 8 subdivisions (4,032 triangles), turned to a
// three-quarter view and seen in perspective, lit from the upper left.
constexpr int TEAPOT_SUBDIVISIONS = 8;
constexpr float TEAPOT_COLOUR[3] = {0.9f, 0.6f, 0.3f};

View teapot_view(unsigned width, unsigned height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  Matrix4 m = frustum(-0.5f * aspect, 0.5f * aspect, -0.5f, 0.5f, 1.0f, 20.0f);
  m = multiply(m, translation(0.0f, 0.0f, -8.0f));
  m = multiply(m, rotation(0, 0.9063078f, 0.4226183f));   // 25 degrees about x: seen from above
  m = multiply(m, rotation(1, 0.8191520f, -0.5735764f));  // -35 degrees about the vertical
  m = multiply(m, rotation(0, 0.0f, -1.0f));              // the data's z up to y up
  m = multiply(m, translation(0.0f, 0.0f, -1.5f));        // the body's middle to the origin
  return {m, width, height};
}

}  // namespace

ClusterScene::ClusterScene(const std::string& name, unsigned triangles, unsigned triangle_pixels, unsigned seed,
                           unsigned width, unsigned height) {
  if (name == "teapot") {
    m_teapot = true;
    scenes::Mesh mesh = scenes::teapot_mesh(TEAPOT_SUBDIVISIONS);
    m_positions = std::move(mesh.positions);
    m_normals = std::move(mesh.normals);
    m_indices = std::move(mesh.indices);
    m_mesh = {m_positions.data(), m_normals.data(), m_indices.data(), static_cast<uint32_t>(m_indices.size() / 3)};
    m_triangles = m_mesh.triangle_count;
    m_view = teapot_view(width, height);
    m_light.direction[0] = -0.3980148f;  // (-0.4, -0.6, 0.7), unit, in the mesh's coordinates: from above,
    m_light.direction[1] = -0.5970223f;  // on the viewer's side
    m_light.direction[2] = 0.6965260f;
    return;
  }
  if (name != "random_triangles") throw std::invalid_argument("cluster.scene: no scene '" + name + "'");
  m_random.seed = seed;
  m_random.count = triangles;
  m_random.size = static_cast<float>(triangle_pixels);
  m_random.width = width;
  m_random.height = height;
  m_triangles = triangles;
  m_view = random_scene_view(m_random);
}

WorldTriangle ClusterScene::triangle(uint32_t index) const {
  if (!m_teapot) return random_triangle(m_random, index);
  return mesh_triangle(m_mesh, index, TEAPOT_COLOUR, m_light);
}

}  // namespace tessera::cluster
