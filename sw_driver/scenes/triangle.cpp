// One Gouraud-shaded triangle with a red, a green and a blue corner: the
// smallest scene that exercises vertex and colour arrays, colour
// interpolation and the viewport transform.
#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

const GLfloat TRIANGLE_XY[] = {-0.8f, -0.7f, 0.8f, -0.7f, 0.0f, 0.8f};
const GLfloat TRIANGLE_RGBA[] = {1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f};

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("triangle", args, error)) return false;
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrthof(-1.0f, 1.0f, -1.0f, 1.0f, -1.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glDisable(GL_DEPTH_TEST);
  glShadeModel(GL_SMOOTH);
  return true;
}

void draw(int /*frame*/) {
  glClear(GL_COLOR_BUFFER_BIT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, TRIANGLE_XY);
  glColorPointer(4, GL_FLOAT, 0, TRIANGLE_RGBA);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene triangle_scene() {
  return {"triangle", "A Gouraud-shaded triangle with red, green and blue corners", init, draw};
}

}  // namespace tessera::scenes
