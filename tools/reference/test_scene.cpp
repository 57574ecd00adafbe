#include "test_scene.h"

#include "scenes/gles_compat.h"

namespace tessera::reference {

namespace {

bool init_triangle(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!args.empty()) {
    *error = "takes no arguments";
    return false;
  }
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  const GLfloat aspect = static_cast<GLfloat>(width) / static_cast<GLfloat>(height);
  glOrthof(-aspect, aspect, -1.0f, 1.0f, -1.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glShadeModel(GL_SMOOTH);
  glClearColor(0.1f, 0.1f, 0.25f, 1.0f);
  return true;
}

void draw_triangle(int frame) {
  static const GLfloat positions[] = {-0.8f, -0.7f, 0.8f, -0.7f, 0.0f, 0.85f};
  static const GLubyte colours[] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255};
  glClear(GL_COLOR_BUFFER_BIT);
  glLoadIdentity();
  glRotatef(7.5f * static_cast<GLfloat>(frame), 0.0f, 0.0f, 1.0f);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, positions);
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, colours);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

const scenes::Scene& test_scene() {
  static const scenes::Scene scene{"reference_triangle", "Gouraud-shaded triangle turning 7.5 degrees a frame",
                                   init_triangle, draw_triangle};
  return scene;
}

}  // namespace tessera::reference
