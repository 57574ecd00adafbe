// A rectangle of two triangles whose corners are exactly the corners of the
// viewport, so every pixel is covered once and the shared diagonal must leave
// neither a gap nor a doubled pixel. The colour is a linear function of the
// position (red grows to the right, green upwards, blue to the left), so
// Gouraud shading reproduces it exactly and any seam along the diagonal
// shows an interpolation error. With the argument `depth` the depth buffer
// is cleared and every pixel depth-tested too (the study's full-screen
// experiment, docs/experiments.md); the picture is the same.
#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

const GLfloat CORNER_XY[] = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f};
const GLfloat CORNER_RGBA[] = {0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 1.0f,
                               0.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 0.0f, 1.0f};
const GLushort TWO_TRIANGLES[] = {0, 1, 3, 0, 3, 2};

bool g_depth = false;

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  for (size_t i = 0; i < args.size(); ++i)
    if (i > 0 || args[i] != "depth") {
      *error = "fullscreen_rect: the only argument is 'depth' (depth-test every pixel), got '" + args[i] + "'";
      return false;
    }
  g_depth = !args.empty();
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrthof(0.0f, 1.0f, 0.0f, 1.0f, -1.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  // Magenta never appears in the gradient, so an uncovered pixel stands out.
  glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
  if (g_depth) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepthf(1.0f);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  glDisable(GL_CULL_FACE);
  glShadeModel(GL_SMOOTH);
  return true;
}

void draw(int /*frame*/) {
  glClear(g_depth ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, CORNER_XY);
  glColorPointer(4, GL_FLOAT, 0, CORNER_RGBA);
  glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, TWO_TRIANGLES);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene fullscreen_rect_scene() {
  return {"fullscreen_rect",
          "Two triangles covering the viewport exactly, with a linear colour gradient (argument: depth, to "
          "depth-test every pixel)",
          init, draw};
}

}  // namespace tessera::scenes
