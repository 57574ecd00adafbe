// A user clip plane and polygon offset. A cube with a colour per face turns
// above a receding floor; a user clip plane, given in the cube's own
// coordinates while its rotation is on the modelview stack (so the driver
// must take it through the inverse modelview into eye space), cuts off a
// corner, and through the cut the inside of the far faces shows (no
// culling). On the floor lies a decal in the floor's own plane, drawn after
// it with the same depth test and glPolygonOffset(-1, -2): without the
// offset the two coplanar polygons would fight pixel by pixel; with it the
// decal wins everywhere. The floor recedes steeply, so the depth slope term
// (factor) is what separates them, as the specification means it to.
#include <array>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr float HALF_EDGE = 0.6f;

constexpr std::array<std::array<GLfloat, 4>, 6> FACE_RGBA = {{
    {{0.90f, 0.20f, 0.20f, 1.0f}},
    {{0.20f, 0.80f, 0.30f, 1.0f}},
    {{0.25f, 0.40f, 0.95f, 1.0f}},
    {{0.95f, 0.85f, 0.20f, 1.0f}},
    {{0.20f, 0.85f, 0.90f, 1.0f}},
    {{0.85f, 0.30f, 0.85f, 1.0f}},
}};

// Keeps x + 0.6 y + 0.8 z <= 0.45 in the cube's coordinates: cuts off the
// corner at (+, +, +) down to a little beyond the middle of its three faces.
constexpr GLfloat CUBE_CLIP_PLANE[4] = {-1.0f, -0.6f, -0.8f, 0.45f};

std::array<GLfloat, 36 * 3> g_cube_xyz;
std::array<GLfloat, 36 * 4> g_cube_rgba;

// The floor (y = -1.2, from z = -2.5 to -12) and the decal on it.
constexpr GLfloat FLOOR_XYZ[4 * 3] = {-4.0f, -1.2f, -2.5f,  4.0f,  -1.2f, -2.5f,
                                      4.0f,  -1.2f, -12.0f, -4.0f, -1.2f, -12.0f};
constexpr GLfloat DECAL_XYZ[4 * 3] = {-1.8f, -1.2f, -3.5f, 1.4f, -1.2f, -3.0f, 2.2f, -1.2f, -9.0f, -2.5f, -1.2f, -8.0f};

void draw_quad(const GLfloat* xyz, GLfloat r, GLfloat g, GLfloat b) {
  static constexpr GLubyte FAN_INDICES[6] = {0, 1, 2, 0, 2, 3};
  glColor4f(r, g, b, 1.0f);
  glVertexPointer(3, GL_FLOAT, 0, xyz);
  glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_BYTE, FAN_INDICES);
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("clip_offset", args, error)) return false;
  flat_cube(HALF_EDGE, FACE_RGBA, g_cube_xyz, g_cube_rgba);
  set_perspective(width, height, 50.0f, 1.0f, 20.0f);
  glClearColor(0.1f, 0.1f, 0.2f, 1.0f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_LIGHTING);
  glShadeModel(GL_SMOOTH);
  return true;
}

void draw(int frame) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();

  // The floor, then the coplanar decal pulled towards the viewer.
  draw_quad(FLOOR_XYZ, 0.55f, 0.55f, 0.5f);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1.0f, -2.0f);
  draw_quad(DECAL_XYZ, 0.9f, 0.45f, 0.1f);
  glDisable(GL_POLYGON_OFFSET_FILL);

  // The cube, cut by a plane that turns with it.
  glPushMatrix();
  glTranslatef(0.0f, 0.1f, -5.0f);
  glRotatef(rotation_degrees(frame, 3.0f), 0.3f, 1.0f, 0.2f);
  glClipPlanef(GL_CLIP_PLANE0, CUBE_CLIP_PLANE);
  glEnable(GL_CLIP_PLANE0);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, g_cube_xyz.data());
  glColorPointer(4, GL_FLOAT, 0, g_cube_rgba.data());
  glDrawArrays(GL_TRIANGLES, 0, 36);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisable(GL_CLIP_PLANE0);
  glPopMatrix();
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene clip_offset_scene() {
  return {"clip_offset",
          "A turning cube cut by a user clip plane above a floor with a coplanar decal drawn with polygon offset", init,
          draw};
}

}  // namespace tessera::scenes
