// Crockett and Orloff's random scene on the SoC: the triangles the cluster
// platform's sort-middle program draws (cluster.scene=random_triangles),
// made by the same GL-free generator (cluster/scene.h) from the same seed
// and seen through the same view (orthographic, one world unit a pixel),
// so that one ARM with the array and p cluster nodes draw the same frame.
// Each vertex comes lit from the generator (its colour), so GL's lighting
// is off; depth test, back-face culling and smooth shading are on, as on
// the nodes. The triangles are made once, at start-up (the nodes too keep
// their share in memory); a frame is one glDrawArrays over them.
// Arguments: --triangles N (default 10000, cluster.triangles'), --size
// PIXELS (default 10, cluster.triangle_pixels'), --seed K (default 1).
#include <cstdint>
#include <string>
#include <vector>

#include "cluster/scene.h"
#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

std::vector<GLfloat> g_positions, g_colours;
GLfloat g_projection[16];

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  cluster::RandomScene scene;
  scene.count = 10000;
  scene.width = static_cast<unsigned>(width);
  scene.height = static_cast<unsigned>(height);
  uint32_t size = 10;
  for (size_t i = 0; i < args.size(); i += 2) {
    bool ok = false;
    if (args[i] == "--triangles")
      ok = whole_number_option("random_triangles", args, i, 1, 1000000, &scene.count, error);
    else if (args[i] == "--size")
      ok = whole_number_option("random_triangles", args, i, 1, 256, &size, error);
    else if (args[i] == "--seed")
      ok = whole_number_option("random_triangles", args, i, 0, 4294967295u, &scene.seed, error);
    else
      *error = "random_triangles: no option '" + args[i] + "' (--triangles N, --size PIXELS, --seed K)";
    if (!ok) return false;
  }
  scene.size = static_cast<float>(size);
  if (const char* problem = cluster::random_scene_error(scene)) {
    *error = std::string("random_triangles: ") + problem;
    return false;
  }
  g_positions.assign(size_t{scene.count} * 9, 0.0f);
  g_colours.assign(size_t{scene.count} * 12, 1.0f);
  for (uint32_t t = 0; t < scene.count; ++t) {
    const cluster::WorldTriangle triangle = cluster::random_triangle(scene, t);
    for (int k = 0; k < 3; ++k) {
      const cluster::WorldVertex& v = triangle.v[k];
      GLfloat* position = &g_positions[(size_t{t} * 3 + k) * 3];
      position[0] = v.x, position[1] = v.y, position[2] = v.z;
      GLfloat* colour = &g_colours[(size_t{t} * 3 + k) * 4];
      colour[0] = v.r, colour[1] = v.g, colour[2] = v.b;
    }
  }
  const cluster::View view = cluster::random_scene_view(scene);
  for (int i = 0; i < 16; ++i) g_projection[i] = view.matrix.m[i];

  glViewport(0, 0, width, height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glDisable(GL_LIGHTING);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glShadeModel(GL_SMOOTH);
  return true;
}

void draw(int /*frame*/) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixf(g_projection);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, g_positions.data());
  glColorPointer(4, GL_FLOAT, 0, g_colours.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(g_positions.size() / 3));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene random_triangles_scene() {
  return {"random_triangles",
          "Crockett and Orloff's random scene, the cluster's (-- --triangles N --size PIXELS --seed K): small lit "
          "triangles in random 3-D orientation, depth tested, back faces culled",
          init, draw};
}

}  // namespace tessera::scenes
