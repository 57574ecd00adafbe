// The Newell teapot, about a thousand triangles tessellated from its Bezier
// patches, lit by one directional light with a specular highlight and
// turning slowly. Exercises normal arrays, fixed-function lighting and
// materials, and the depth test on a curved, self-occluding model.
#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"
#include "scenes/teapot_mesh.h"

namespace tessera::scenes {

namespace {

// 992 triangles: see teapot_mesh().
constexpr int TEAPOT_SUBDIVISIONS = 4;

Mesh g_teapot;

// The data is z-up; GL's eye space is y-up. Turning -90 degrees about x
// maps (x, y, z) to (x, z, -y), a rotation, so winding and normals stay right.
void make_y_up(std::vector<float>* xyz) {
  for (std::size_t i = 0; i < xyz->size(); i += 3) {
    const float y = (*xyz)[i + 1];
    (*xyz)[i + 1] = (*xyz)[i + 2];
    (*xyz)[i + 2] = -y;
  }
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("teapot", args, error)) return false;
  g_teapot = teapot_mesh(TEAPOT_SUBDIVISIONS);
  make_y_up(&g_teapot.positions);
  make_y_up(&g_teapot.normals);
  fit_to_unit_sphere(&g_teapot);
  const float porcelain[4] = {0.85f, 0.55f, 0.30f, 1.0f};
  set_up_lit_mesh(width, height, porcelain);
  return true;
}

void draw(int frame) {
  draw_lit_mesh(g_teapot, frame);
}

}  // namespace

Scene teapot_scene() {
  return {"teapot", "The Newell teapot from its Bezier patches, lit with one light, turning slowly", init, draw};
}

}  // namespace tessera::scenes
