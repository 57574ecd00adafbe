#include <algorithm>

#include "scenes/scene_common.h"

namespace tessera::scenes {

Scene aapoly_scene();        // aapoly.cpp
Scene multitexture_scene();  // multitexture.cpp
// The ES 1.1 geometry scenes (clip_offset.cpp, points_lines.cpp, lights_two_side.cpp).
Scene clip_offset_scene();
Scene points_lines_scene();
Scene lights_two_side_scene();
Scene fog_row_scene();           // fog_row.cpp
Scene mipmap_floor_scene();      // mipmap_floor.cpp
Scene texture_formats_scene();   // texture_formats.cpp
Scene fixed_point_scene();       // fixed_point.cpp
Scene random_triangles_scene();  // random_triangles.cpp
Scene dense_teapot_scene();      // dense_teapot.cpp

const std::vector<Scene>& all_scenes() {
  static const std::vector<Scene> scenes = {
      triangle_scene(),         cubes_scene(),           fullscreen_rect_scene(), textured_quad_scene(),
      teapot_scene(),           obj_viewer_scene(),      aapoly_scene(),          tile_grid_scene(),
      clip_offset_scene(),      points_lines_scene(),    lights_two_side_scene(), fog_row_scene(),
      mipmap_floor_scene(),     texture_formats_scene(), multitexture_scene(),    fixed_point_scene(),
      random_triangles_scene(), dense_teapot_scene()};
  return scenes;
}

const Scene* find_scene(const std::string& name) {
  const std::vector<Scene>& scenes = all_scenes();
  const auto found = std::find_if(scenes.begin(), scenes.end(), [&name](const Scene& s) { return name == s.name; });
  return found == scenes.end() ? nullptr : &*found;
}

}  // namespace tessera::scenes
