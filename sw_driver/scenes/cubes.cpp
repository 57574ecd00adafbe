// Several cubes turning at different rates, two of them interpenetrating, so
// the depth test decides visibility along their intersection. Half are drawn
// with one flat colour per face from an unindexed array (glDrawArrays), half
// with a colour per corner from eight shared vertices (glDrawElements), with
// colours as floats and as unsigned bytes respectively. The cubes are closed
// and wound counter-clockwise from outside, so back faces are culled.
#include <array>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr float HALF_EDGE = 0.5f;

constexpr std::array<std::array<GLfloat, 4>, 6> FACE_RGBA = {{
    {{0.90f, 0.20f, 0.20f, 1.0f}},
    {{0.20f, 0.80f, 0.30f, 1.0f}},
    {{0.25f, 0.40f, 0.95f, 1.0f}},
    {{0.95f, 0.85f, 0.20f, 1.0f}},
    {{0.20f, 0.85f, 0.90f, 1.0f}},
    {{0.85f, 0.30f, 0.85f, 1.0f}},
}};

struct CubeInstance {
  std::array<float, 3> position;
  float scale;
  std::array<float, 3> axis;
  float degrees_per_frame;
  bool per_vertex_colour;
};

// The large cube at the back and the small one in front of it overlap in
// depth, so their faces cut through each other.
constexpr std::array<CubeInstance, 5> CUBES = {{
    {{-1.6f, 1.0f, -6.0f}, 1.0f, {1.0f, 1.0f, 0.0f}, 2.0f, false},
    {{1.6f, 1.0f, -6.0f}, 1.0f, {0.0f, 1.0f, 1.0f}, -1.5f, true},
    {{0.0f, -0.6f, -7.0f}, 2.0f, {0.0f, 1.0f, 0.0f}, 0.7f, false},
    {{0.5f, -0.2f, -5.6f}, 0.9f, {1.0f, 0.0f, 1.0f}, 3.0f, true},
    {{-1.9f, -1.4f, -5.0f}, 0.6f, {1.0f, 0.3f, 0.2f}, -2.5f, false},
}};

struct Geometry {
  // Per-face colour: 36 vertices, xyz and rgba each.
  std::array<GLfloat, 36 * 3> face_xyz;
  std::array<GLfloat, 36 * 4> face_rgba;
  // Per-corner colour: 8 vertices and 36 indices.
  std::array<GLfloat, 8 * 3> corner_xyz;
  std::array<GLubyte, 8 * 4> corner_rgba;
  std::array<GLushort, 36> corner_indices;
};

Geometry g_geometry;

void corner_position(int corner, GLfloat* xyz) {
  for (int axis = 0; axis < 3; ++axis) xyz[axis] = (corner >> axis) & 1 ? HALF_EDGE : -HALF_EDGE;
}

void build_geometry() {
  // Two triangles per face: (0, 1, 2) and (0, 2, 3) of its corner list.
  const int quad_to_triangles[6] = {0, 1, 2, 0, 2, 3};
  for (int face = 0; face < 6; ++face)
    for (int k = 0; k < 6; ++k) {
      const int vertex = 6 * face + k;
      const GLushort corner = CUBE_FACE_CORNERS[face][quad_to_triangles[k]];
      corner_position(corner, &g_geometry.face_xyz[3 * vertex]);
      for (int c = 0; c < 4; ++c) g_geometry.face_rgba[4 * vertex + c] = FACE_RGBA[face][c];
      g_geometry.corner_indices[vertex] = corner;
    }
  for (int corner = 0; corner < 8; ++corner) {
    corner_position(corner, &g_geometry.corner_xyz[3 * corner]);
    // The corner's colour is its position in the unit RGB cube.
    for (int axis = 0; axis < 3; ++axis) g_geometry.corner_rgba[4 * corner + axis] = (corner >> axis) & 1 ? 255 : 0;
    g_geometry.corner_rgba[4 * corner + 3] = 255;
  }
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  for (size_t i = 0; i < args.size(); ++i)
    if (i > 0 || args[i] != "offscreen") {
      *error =
          "cubes: the only argument is 'offscreen' (the viewport partly off the screen's left and bottom edges), "
          "got '" +
          args[i] + "'";
      return false;
    }
  build_geometry();
  set_perspective(width, height, 45.0f, 1.0f, 20.0f);
  // `offscreen`: the same view through a viewport moved left by a third of
  // the screen and down by a quarter (glViewport accepts a negative origin;
  // the picture is cut at the screen's edges). Its size stays the screen's,
  // within every implementation's GL_MAX_VIEWPORT_DIMS.
  if (!args.empty()) glViewport(-width / 3, -height / 4, width, height);
  glClearColor(0.05f, 0.05f, 0.08f, 1.0f);
  glClearDepthf(1.0f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glShadeModel(GL_SMOOTH);
  glDisable(GL_LIGHTING);
  return true;
}

void draw(int frame) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  for (const CubeInstance& cube : CUBES) {
    glPushMatrix();
    glTranslatef(cube.position[0], cube.position[1], cube.position[2]);
    glRotatef(rotation_degrees(frame, cube.degrees_per_frame), cube.axis[0], cube.axis[1], cube.axis[2]);
    glScalef(cube.scale, cube.scale, cube.scale);
    if (cube.per_vertex_colour) {
      glVertexPointer(3, GL_FLOAT, 0, g_geometry.corner_xyz.data());
      glColorPointer(4, GL_UNSIGNED_BYTE, 0, g_geometry.corner_rgba.data());
      glDrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_SHORT, g_geometry.corner_indices.data());
    } else {
      glVertexPointer(3, GL_FLOAT, 0, g_geometry.face_xyz.data());
      glColorPointer(4, GL_FLOAT, 0, g_geometry.face_rgba.data());
      glDrawArrays(GL_TRIANGLES, 0, 36);
    }
    glPopMatrix();
  }
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene cubes_scene() {
  return {"cubes", "Rotating Gouraud cubes, flat per-face and per-vertex colours, depth test and back-face culling",
          init, draw};
}

}  // namespace tessera::scenes
