// A row of cubes receding into fog over a long floor, three times, one band
// of the window each: linear fog (top), GL_EXP (middle) and GL_EXP2
// (bottom). The cubes stand from 4 to 19 units in front of the eye,
// so each mode's factor sweeps from nearly clear to nearly fog colour; the
// floor is two large triangles whose fog varies across them, which checks
// that the fog coordinate is interpolated per fragment (and perspective-
// correctly) rather than per vertex or per triangle. The clear colour (a
// dark sky) differs from the fog colour, so that a fully fogged pixel is
// never taken for the background when the frame is compared with Mesa's.
// Flat per-face colours without lighting, depth-tested, back faces culled; the cubes turn slowly
// with the frame number.
#include <array>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr int CUBES = 6;
constexpr float NEAREST_CUBE = 4.0f, CUBE_SPACING = 3.0f;  // eye distances 4 .. 19
constexpr float FIRST_CUBE_X = -2.4f, CUBE_STEP_X = 1.0f;  // the row runs diagonally away
constexpr float CUBE_SCALE = 0.8f, CUBE_Y = -0.6f;         // standing on the floor
constexpr float FLOOR_Y = -1.0f, FLOOR_NEAR = -1.0f, FLOOR_FAR = -50.0f, FLOOR_HALF_WIDTH = 15.0f;
constexpr std::array<GLfloat, 4> FOG_COLOUR = {0.62f, 0.66f, 0.72f, 1.0f};
constexpr std::array<GLfloat, 4> SKY_COLOUR = {0.10f, 0.12f, 0.25f, 1.0f};

struct FogPart {
  GLenum mode;
  GLfloat density, start, end;
};
// Linear from 2 to 20; exp and exp2 with densities whose factor at the
// farthest cube (c = 19) is about 0.06 and 0.01.
constexpr std::array<FogPart, 3> PARTS = {{
    {GL_LINEAR, 1.0f, 2.0f, 20.0f},
    {GL_EXP, 0.15f, 0.0f, 1.0f},
    {GL_EXP2, 0.11f, 0.0f, 1.0f},
}};

constexpr std::array<std::array<GLfloat, 4>, 6> FACE_RGBA = {{
    {{0.85f, 0.15f, 0.10f, 1.0f}},
    {{0.15f, 0.70f, 0.20f, 1.0f}},
    {{0.95f, 0.90f, 0.25f, 1.0f}},
    {{0.10f, 0.10f, 0.10f, 1.0f}},
    {{0.20f, 0.30f, 0.90f, 1.0f}},
    {{0.80f, 0.25f, 0.80f, 1.0f}},
}};

std::array<GLfloat, 36 * 3> g_cube_xyz;
std::array<GLfloat, 36 * 4> g_cube_rgba;
// The floor: a dark checker of two colours per corner, so that the fog's
// gradient over it is visible against the vertex colours'.
constexpr std::array<GLfloat, 4 * 3> FLOOR_XYZ = {
    -FLOOR_HALF_WIDTH, FLOOR_Y, FLOOR_NEAR, FLOOR_HALF_WIDTH,  FLOOR_Y, FLOOR_NEAR,
    FLOOR_HALF_WIDTH,  FLOOR_Y, FLOOR_FAR,  -FLOOR_HALF_WIDTH, FLOOR_Y, FLOOR_FAR};
constexpr std::array<GLubyte, 4 * 4> FLOOR_RGBA = {40, 60, 30, 255, 70, 50, 30, 255, 40, 60, 30, 255, 70, 50, 30, 255};
constexpr std::array<GLushort, 6> FLOOR_INDICES = {0, 1, 2, 0, 2, 3};

int g_width = 0, g_height = 0;

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("fog_row", args, error)) return false;
  flat_cube(0.5f, FACE_RGBA, g_cube_xyz, g_cube_rgba);
  g_width = width;
  g_height = height;
  glClearColor(SKY_COLOUR[0], SKY_COLOUR[1], SKY_COLOUR[2], SKY_COLOUR[3]);
  glClearDepthf(1.0f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glShadeModel(GL_SMOOTH);
  glDisable(GL_LIGHTING);
  glEnable(GL_FOG);
  glFogfv(GL_FOG_COLOR, FOG_COLOUR.data());
  glHint(GL_FOG_HINT, GL_NICEST);
  return true;
}

void draw(int frame) {
  glViewport(0, 0, g_width, g_height);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  for (int part = 0; part < 3; ++part) {
    // Top band first: GL's y runs upwards.
    const int y0 = (2 - part) * g_height / 3, y1 = (3 - part) * g_height / 3;
    set_perspective(g_width, y1 - y0, 30.0f, 1.0f, 100.0f);
    glViewport(0, y0, g_width, y1 - y0);
    glRotatef(10.0f, 1.0f, 0.0f, 0.0f);  // looking down onto the floor and the cubes' tops
    const FogPart& p = PARTS[part];
    glFogf(GL_FOG_MODE, static_cast<GLfloat>(p.mode));
    glFogf(GL_FOG_DENSITY, p.density);
    glFogf(GL_FOG_START, p.start);
    glFogf(GL_FOG_END, p.end);

    glVertexPointer(3, GL_FLOAT, 0, FLOOR_XYZ.data());
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, FLOOR_RGBA.data());
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, FLOOR_INDICES.data());

    glVertexPointer(3, GL_FLOAT, 0, g_cube_xyz.data());
    glColorPointer(4, GL_FLOAT, 0, g_cube_rgba.data());
    for (int i = 0; i < CUBES; ++i) {
      glPushMatrix();
      glTranslatef(FIRST_CUBE_X + CUBE_STEP_X * i, CUBE_Y, -(NEAREST_CUBE + CUBE_SPACING * i));
      glRotatef(rotation_degrees(frame, 1.0f) + 25.0f * i, 0.0f, 1.0f, 0.0f);
      glScalef(CUBE_SCALE, CUBE_SCALE, CUBE_SCALE);
      glDrawArrays(GL_TRIANGLES, 0, 36);
      glPopMatrix();
    }
  }
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene fog_row_scene() {
  return {"fog_row", "A row of cubes receding into fog over a floor, in three bands: linear, GL_EXP and GL_EXP2 fog",
          init, draw};
}

}  // namespace tessera::scenes
