// A Wavefront OBJ model, given as the only argument, validated by
// load_obj(), centred and scaled to fit the view, lit by one directional
// light and turning slowly. Normals come from the file if every face corner
// has one, otherwise they are computed.
#include <utility>

#include "scenes/gles_compat.h"
#include "scenes/obj_loader.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

Mesh g_model;

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (args.size() != 1) {
    *error = "obj_viewer: takes one argument, the path of an OBJ file";
    return false;
  }
  Mesh model;
  if (!load_obj(args[0], &model, error)) return false;
  fit_to_unit_sphere(&model);
  g_model = std::move(model);
  const float pale_blue[4] = {0.60f, 0.70f, 0.90f, 1.0f};
  set_up_lit_mesh(width, height, pale_blue);
  return true;
}

void draw(int frame) {
  draw_lit_mesh(g_model, frame);
}

}  // namespace

Scene obj_viewer_scene() {
  return {"obj_viewer", "A Wavefront OBJ model (argument: its path), fitted to the view, lit, turning slowly", init,
          draw};
}

}  // namespace tessera::scenes
