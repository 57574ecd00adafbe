// A built-in scene: drawing code written against OpenGL ES 1.1 only
// (gles_compat.h), so that it compiles unchanged against tessera's driver
// and against Mesa for the reference images. The application wrapper around
// it (EGL set-up and the frame loop) is separate.
#pragma once

#include <string>
#include <vector>

namespace tessera::scenes {

struct Scene {
  const char* name;
  const char* description;
  // Sets up GL state, textures and geometry for a width x height window,
  // with the current context made current. Returns false and fills `error`
  // if an argument (e.g. an OBJ file) is bad.
  bool (*init)(int width, int height, const std::vector<std::string>& args, std::string* error);
  // Draws frame number `frame` (0, 1, ...), clear included.
  void (*draw)(int frame);
};

const std::vector<Scene>& all_scenes();
const Scene* find_scene(const std::string& name);

}  // namespace tessera::scenes
