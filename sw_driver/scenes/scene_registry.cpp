#include <algorithm>

#include "scenes/scene_common.h"

namespace tessera::scenes {

Scene aapoly_scene();        // aapoly.cpp
Scene multitexture_scene();  // multitexture.cpp

const std::vector<Scene>& all_scenes() {
  static const std::vector<Scene> scenes = {triangle_scene(),      cubes_scene(),     fullscreen_rect_scene(),
                                            textured_quad_scene(), teapot_scene(),    obj_viewer_scene(),
                                            aapoly_scene(),        tile_grid_scene(), multitexture_scene()};
  return scenes;
}

const Scene* find_scene(const std::string& name) {
  const std::vector<Scene>& scenes = all_scenes();
  const auto found = std::find_if(scenes.begin(), scenes.end(), [&name](const Scene& s) { return name == s.name; });
  return found == scenes.end() ? nullptr : &*found;
}

}  // namespace tessera::scenes
