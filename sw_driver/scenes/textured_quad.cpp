// A quad tilted away from the viewer and turning in its own plane, textured
// with a procedurally generated 64x64 RGBA checkerboard (white squares
// alternating with coloured ones), repeated twice across the quad and
// modulated by a different colour at each corner. Under perspective, a
// texture interpolated linearly in screen space bends the checkerboard's
// straight lines, so the scene shows whether texturing is perspective
// correct. Argument: "linear" (default) or "nearest", the filter for both
// magnification and minification (there are no mipmaps).
#include <array>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr int TEXTURE_SIZE = 64;
constexpr int SQUARE_SIZE = 8;
constexpr float TILT_DEGREES = -60.0f;
constexpr float QUAD_DISTANCE = 3.0f;
constexpr float DEGREES_PER_FRAME = 0.5f;

// Quad in the xy plane, counter-clockwise from the lower left.
const GLfloat QUAD_XYZ[] = {-1.0f, -1.0f, 0.0f, 1.0f, -1.0f, 0.0f, 1.0f, 1.0f, 0.0f, -1.0f, 1.0f, 0.0f};
// 0..2: the texture repeats twice in each direction (GL_REPEAT).
const GLfloat QUAD_ST[] = {0.0f, 0.0f, 2.0f, 0.0f, 2.0f, 2.0f, 0.0f, 2.0f};
const GLubyte QUAD_RGBA[] = {255, 255, 255, 255, 255, 230, 120, 255, 140, 230, 255, 255, 255, 160, 220, 255};
const GLushort QUAD_TRIANGLES[] = {0, 1, 2, 0, 2, 3};

const std::vector<std::array<GLubyte, 3>> SQUARE_COLOURS = {{
    {{220, 40, 40}},
    {{40, 180, 60}},
    {{50, 80, 230}},
    {{235, 200, 30}},
    {{30, 200, 210}},
    {{200, 60, 200}},
}};

GLuint g_texture = 0;

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  GLint filter = GL_LINEAR;
  if (args.size() > 1) {
    *error = "textured_quad: takes at most one argument, the filter";
    return false;
  }
  if (!args.empty()) {
    if (args[0] == "nearest") {
      filter = GL_NEAREST;
    } else if (args[0] != "linear") {
      *error = "textured_quad: the filter must be 'linear' or 'nearest', not '" + args[0] + "'";
      return false;
    }
  }

  set_perspective(width, height, 45.0f, 0.5f, 10.0f);
  glClearColor(0.15f, 0.15f, 0.15f, 1.0f);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_LIGHTING);
  glShadeModel(GL_SMOOTH);
  glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);

  const auto texels = checkerboard_rgba8(TEXTURE_SIZE, SQUARE_SIZE, 255, SQUARE_COLOURS, 3);
  glGenTextures(1, &g_texture);
  glBindTexture(GL_TEXTURE_2D, g_texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, TEXTURE_SIZE, TEXTURE_SIZE, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  // The default minification filter uses mipmaps, which this texture lacks.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glEnable(GL_TEXTURE_2D);
  return true;
}

void draw(int frame) {
  glClear(GL_COLOR_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glTranslatef(0.0f, 0.0f, -QUAD_DISTANCE);
  glRotatef(TILT_DEGREES, 1.0f, 0.0f, 0.0f);
  glRotatef(rotation_degrees(frame, DEGREES_PER_FRAME), 0.0f, 0.0f, 1.0f);

  glBindTexture(GL_TEXTURE_2D, g_texture);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, QUAD_XYZ);
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, QUAD_RGBA);
  glTexCoordPointer(2, GL_FLOAT, 0, QUAD_ST);
  glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, QUAD_TRIANGLES);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene textured_quad_scene() {
  return {"textured_quad",
          "A tilted quad with a 64x64 RGBA checkerboard texture, GL_MODULATE with vertex colours, in perspective "
          "(argument: linear or nearest)",
          init, draw};
}

}  // namespace tessera::scenes
