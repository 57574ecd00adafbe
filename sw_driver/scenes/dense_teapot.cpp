// The Newell teapot tessellated to a chosen number of triangles: the
// stand-ins for the meshes Davila et al. rendered on MorphoSys (their
// Table 2: Stanford's bunny 69,451 triangles, a horse 96,966, a hand
// 654,666, a Buddha 1,087,716, a thorax and hip 1,136,745), which are not
// reachable from here. Same lighting, material, view and turn as `teapot`.
//
// Each Bezier patch is cut into n x n quads, n the smallest (from 2) whose
// 64 n^2 - 8 n triangles reach the count asked for; the triangles beyond it
// are dropped from the end of the last patches (the bottom's, which the
// view never shows). The patches go in meshes of at most 65,536 vertices,
// one glDrawElements each, since GL ES 1.1 indices are 16-bit.
//
// Arguments: --triangles N (1 to 4,000,000, default 10,000) or --stand-in
// bunny|horse|hand|buddha|thorax (the paper's count).
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"
#include "scenes/teapot_mesh.h"

namespace tessera::scenes {

namespace {

struct StandIn {
  const char* name;
  uint32_t triangles;
};

// Davila et al., Table 2.
constexpr StandIn STAND_INS[] = {
    {"bunny", 69451}, {"horse", 96966}, {"hand", 654666}, {"buddha", 1087716}, {"thorax", 1136745},
};

constexpr uint32_t DEFAULT_TRIANGLES = 10000;
constexpr uint32_t MOST_TRIANGLES = 4000000;

std::vector<Mesh> g_parts;

void make_y_up(std::vector<float>* xyz) {
  for (std::size_t i = 0; i < xyz->size(); i += 3) {
    const float y = (*xyz)[i + 1];
    (*xyz)[i + 1] = (*xyz)[i + 2];
    (*xyz)[i + 2] = -y;
  }
}

bool stand_in(const std::vector<std::string>& args, std::size_t i, uint32_t* triangles, std::string* error) {
  std::string names;
  for (const StandIn& s : STAND_INS) {
    if (i + 1 < args.size() && args[i + 1] == s.name) {
      *triangles = s.triangles;
      return true;
    }
    names += names.empty() ? s.name : std::string("|") + s.name;
  }
  *error = "dense_teapot: --stand-in takes " + names + (i + 1 < args.size() ? ", not '" + args[i + 1] + "'" : "");
  return false;
}

// Drops triangles from the end of the last parts until `count` are left,
// and the parts left empty.
void keep_first_triangles(std::size_t count, std::vector<Mesh>* parts) {
  std::size_t total = 0;
  for (const Mesh& part : *parts) total += part.triangle_count();
  for (auto part = parts->rbegin(); part != parts->rend() && total > count; ++part) {
    const std::size_t drop = std::min(total - count, part->triangle_count());
    part->indices.resize(part->indices.size() - 3 * drop);
    total -= drop;
  }
  parts->erase(std::remove_if(parts->begin(), parts->end(), [](const Mesh& m) { return m.indices.empty(); }),
               parts->end());
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  uint32_t triangles = DEFAULT_TRIANGLES;
  for (std::size_t i = 0; i < args.size(); i += 2) {
    bool ok = false;
    if (args[i] == "--triangles")
      ok = whole_number_option("dense_teapot", args, i, 1, MOST_TRIANGLES, &triangles, error);
    else if (args[i] == "--stand-in")
      ok = stand_in(args, i, &triangles, error);
    else
      *error = "dense_teapot: no option '" + args[i] + "' (--triangles N, --stand-in NAME)";
    if (!ok) return false;
  }
  int n = 2;
  while (teapot_triangle_count(n) < triangles) ++n;
  g_parts = teapot_mesh_parts(n);
  keep_first_triangles(triangles, &g_parts);
  for (Mesh& part : g_parts) {
    make_y_up(&part.positions);
    make_y_up(&part.normals);
  }
  fit_to_unit_sphere(&g_parts);
  const float porcelain[4] = {0.85f, 0.55f, 0.30f, 1.0f};
  set_up_lit_mesh(width, height, porcelain);
  return true;
}

void draw(int frame) {
  draw_lit_meshes(g_parts.data(), g_parts.size(), frame);
}

}  // namespace

Scene dense_teapot_scene() {
  return {"dense_teapot",
          "The teapot tessellated to --triangles N (default 10,000) or --stand-in bunny|horse|hand|buddha|thorax "
          "(the MorphoSys paper's meshes' counts), drawn in meshes of 16-bit indices",
          init, draw};
}

}  // namespace tessera::scenes
