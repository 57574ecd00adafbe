// One small triangle in each 8 x 36 cell of the window, the size of an
// ap-tile tile (one per CU): at the array's 192 x 144 every CU gets exactly
// one triangle, so one pass of the array draws the whole frame with every
// CU busy (the study's peak-rate experiment, docs/experiments.md). Each
// triangle lies strictly inside its cell, so no tile gets a second one;
// Gouraud-shaded, sloped in depth and depth-tested, so that every stage of
// a pass has work.
#include <vector>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr int CELL_WIDTH = 8, CELL_HEIGHT = 36;

// Corners in a cell, in pixels from its bottom-left corner, about a pixel in
// from its sides (counter-clockwise), and their depths in the ortho volume.
// On the 1/16-pixel grid and chosen so that no edge passes within 0.03
// pixel of a pixel centre: no pixel is left to the fill rule's tie-break,
// and the picture compares with Mesa's without an allowed mismatch.
const GLfloat CORNER_XYZ[3][3] = {{0.875f, 2.0f, 0.5f}, {7.0f, 0.9375f, 0.0f}, {4.1875f, 34.6875f, -0.5f}};
const GLfloat CORNER_RGBA[3][4] = {{1.0f, 0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f, 1.0f}};

std::vector<GLfloat> g_xyz, g_rgba;

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("tile_grid", args, error)) return false;
  g_xyz.clear();
  g_rgba.clear();
  for (int y0 = 0; y0 + CELL_HEIGHT <= height; y0 += CELL_HEIGHT)
    for (int x0 = 0; x0 + CELL_WIDTH <= width; x0 += CELL_WIDTH)
      for (int corner = 0; corner < 3; ++corner) {
        g_xyz.insert(g_xyz.end(), {static_cast<GLfloat>(x0) + CORNER_XYZ[corner][0],
                                   static_cast<GLfloat>(y0) + CORNER_XYZ[corner][1], CORNER_XYZ[corner][2]});
        g_rgba.insert(g_rgba.end(), CORNER_RGBA[corner], CORNER_RGBA[corner] + 4);
      }
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrthof(0.0f, static_cast<GLfloat>(width), 0.0f, static_cast<GLfloat>(height), -1.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClearDepthf(1.0f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glShadeModel(GL_SMOOTH);
  return true;
}

void draw(int /*frame*/) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, g_xyz.data());
  glColorPointer(4, GL_FLOAT, 0, g_rgba.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(g_xyz.size() / 3));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene tile_grid_scene() {
  return {"tile_grid", "One small triangle in each 8 x 36 cell: at 192 x 144, one per CU of the array", init, draw};
}

}  // namespace tessera::scenes
