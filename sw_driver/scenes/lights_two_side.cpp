// Every one of the eight lights, of every kind, and two-sided lighting. A
// half-cylinder shell turns above a floor, so that its outside (front faces)
// and its inside (back faces, lit with the reversed normal under
// GL_LIGHT_MODEL_TWO_SIDE) both face the viewer in turn. The lights, fixed
// in eye space:
//   0 directional, dim white;
//   1 positional red, linear attenuation;
//   2 positional green, quadratic attenuation;
//   3 spot light, blue, straight down onto the floor (cutoff 30, exponent 10);
//   4 spot light, yellow, slanted (cutoff 45, exponent 2), constant and
//     linear attenuation;
//   5 spot light, cyan (cutoff 20, exponent 0: a hard-edged pool);
//   6 directional, magenta, with a spot cutoff (10) and exponent (5), which
//     Mesa applies with the light's direction as the vertex's direction
//     (inside the cone here, a factor of about 0.98);
//   7 positional white inside the shell, all three attenuations.
// Both surfaces are finely tessellated grids, as lighting is per vertex.
#include <array>
#include <cmath>
#include <vector>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

struct Grid {
  std::vector<GLfloat> xyz, normals;
  std::vector<GLushort> indices;
};

Grid g_shell, g_floor;

// A (columns + 1) x (rows + 1) grid of vertices from `vertex(u, v)` with u,
// v in [0, 1], as triangles wound counter-clockwise when u runs right and v
// up on the side the normals point to.
template <typename Vertex>
Grid make_grid(int columns, int rows, Vertex vertex) {
  Grid grid;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= columns; ++i) {
      float p[3], n[3];
      vertex(float(i) / float(columns), float(j) / float(rows), p, n);
      grid.xyz.insert(grid.xyz.end(), p, p + 3);
      grid.normals.insert(grid.normals.end(), n, n + 3);
    }
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const auto at = [columns](int x, int y) { return GLushort(y * (columns + 1) + x); };
      const GLushort quad[6] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)};
      grid.indices.insert(grid.indices.end(), quad, quad + 6);
    }
  return grid;
}

void set_light(GLenum light, const GLfloat position[4], const GLfloat diffuse[4]) {
  const GLfloat ambient[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  glLightfv(light, GL_AMBIENT, ambient);
  glLightfv(light, GL_DIFFUSE, diffuse);
  glLightfv(light, GL_SPECULAR, diffuse);
  glLightfv(light, GL_POSITION, position);
  glEnable(light);
}

void set_spot(GLenum light, GLfloat x, GLfloat y, GLfloat z, GLfloat cutoff, GLfloat exponent) {
  const GLfloat direction[3] = {x, y, z};
  glLightfv(light, GL_SPOT_DIRECTION, direction);
  glLightf(light, GL_SPOT_CUTOFF, cutoff);
  glLightf(light, GL_SPOT_EXPONENT, exponent);
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("lights_two_side", args, error)) return false;
  const float pi = float(std::acos(-1.0));
  // The shell: half a cylinder of radius 1 around y, from y = -0.9 to 0.9,
  // normals pointing out.
  g_shell = make_grid(24, 10, [pi](float u, float v, float* p, float* n) {
    const float angle = pi * u;
    n[0] = std::cos(angle), n[1] = 0.0f, n[2] = -std::sin(angle);
    p[0] = n[0], p[1] = -0.9f + 1.8f * v, p[2] = n[2];
  });
  // The floor: y = -1.3 from x = -4 to 4, z = -2 to -11, normal up.
  g_floor = make_grid(16, 16, [](float u, float v, float* p, float* n) {
    p[0] = -4.0f + 8.0f * u, p[1] = -1.3f, p[2] = -2.0f - 9.0f * v;
    n[0] = 0.0f, n[1] = 1.0f, n[2] = 0.0f;
  });

  set_perspective(width, height, 50.0f, 1.0f, 20.0f);
  glClearColor(0.05f, 0.05f, 0.08f, 1.0f);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_LIGHTING);
  glEnable(GL_NORMALIZE);
  glLightModelf(GL_LIGHT_MODEL_TWO_SIDE, 1.0f);
  const GLfloat model_ambient[4] = {0.08f, 0.08f, 0.08f, 1.0f};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, model_ambient);
  const GLfloat specular[4] = {0.6f, 0.6f, 0.6f, 1.0f};
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, specular);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 24.0f);

  // The lights, in eye coordinates (identity modelview).
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  const GLfloat dim_white[4] = {0.25f, 0.25f, 0.25f, 1.0f};
  const GLfloat p0[4] = {-0.5f, 1.0f, 1.0f, 0.0f};
  set_light(GL_LIGHT0, p0, dim_white);
  const GLfloat red[4] = {0.9f, 0.15f, 0.1f, 1.0f};
  const GLfloat p1[4] = {2.5f, 0.5f, -3.5f, 1.0f};
  set_light(GL_LIGHT1, p1, red);
  glLightf(GL_LIGHT1, GL_LINEAR_ATTENUATION, 0.35f);
  const GLfloat green[4] = {0.1f, 0.9f, 0.2f, 1.0f};
  const GLfloat p2[4] = {-2.5f, 0.2f, -4.0f, 1.0f};
  set_light(GL_LIGHT2, p2, green);
  glLightf(GL_LIGHT2, GL_QUADRATIC_ATTENUATION, 0.12f);
  const GLfloat blue[4] = {0.2f, 0.35f, 1.0f, 1.0f};
  const GLfloat p3[4] = {0.0f, 2.5f, -6.5f, 1.0f};
  set_light(GL_LIGHT3, p3, blue);
  set_spot(GL_LIGHT3, 0.0f, -1.0f, 0.0f, 30.0f, 10.0f);
  const GLfloat yellow[4] = {1.0f, 0.85f, 0.2f, 1.0f};
  const GLfloat p4[4] = {-2.0f, 2.0f, -3.0f, 1.0f};
  set_light(GL_LIGHT4, p4, yellow);
  set_spot(GL_LIGHT4, 0.6f, -1.0f, -0.8f, 45.0f, 2.0f);
  glLightf(GL_LIGHT4, GL_CONSTANT_ATTENUATION, 0.5f);
  glLightf(GL_LIGHT4, GL_LINEAR_ATTENUATION, 0.15f);
  const GLfloat cyan[4] = {0.1f, 0.8f, 0.8f, 1.0f};
  const GLfloat p5[4] = {2.0f, 2.5f, -7.5f, 1.0f};
  set_light(GL_LIGHT5, p5, cyan);
  set_spot(GL_LIGHT5, -0.2f, -1.0f, 0.1f, 20.0f, 0.0f);
  const GLfloat magenta[4] = {0.3f, 0.05f, 0.3f, 1.0f};
  const GLfloat p6[4] = {0.3f, 0.2f, 1.0f, 0.0f};
  set_light(GL_LIGHT6, p6, magenta);
  set_spot(GL_LIGHT6, -0.2f, -0.2f, -1.0f, 10.0f, 5.0f);
  const GLfloat white[4] = {0.7f, 0.7f, 0.6f, 1.0f};
  const GLfloat p7[4] = {0.0f, 0.0f, -5.0f, 1.0f};
  set_light(GL_LIGHT7, p7, white);
  glLightf(GL_LIGHT7, GL_CONSTANT_ATTENUATION, 0.4f);
  glLightf(GL_LIGHT7, GL_LINEAR_ATTENUATION, 0.3f);
  glLightf(GL_LIGHT7, GL_QUADRATIC_ATTENUATION, 0.5f);
  return true;
}

void draw_grid(const Grid& grid, const GLfloat diffuse[4]) {
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, diffuse);
  glVertexPointer(3, GL_FLOAT, 0, grid.xyz.data());
  glNormalPointer(GL_FLOAT, 0, grid.normals.data());
  glDrawElements(GL_TRIANGLES, GLsizei(grid.indices.size()), GL_UNSIGNED_SHORT, grid.indices.data());
}

void draw(int frame) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  const GLfloat grey[4] = {0.7f, 0.7f, 0.7f, 1.0f};
  draw_grid(g_floor, grey);
  glPushMatrix();
  glTranslatef(0.0f, 0.0f, -5.0f);
  glRotatef(20.0f, 1.0f, 0.0f, 0.0f);
  glRotatef(rotation_degrees(frame, 6.0f) + 120.0f, 0.0f, 1.0f, 0.0f);
  const GLfloat ivory[4] = {0.9f, 0.85f, 0.75f, 1.0f};
  draw_grid(g_shell, ivory);
  glPopMatrix();
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene lights_two_side_scene() {
  return {"lights_two_side",
          "A turning half-cylinder shell lit on both sides (two-sided lighting) above a floor, by eight lights: "
          "directional, attenuated and spot",
          init, draw};
}

}  // namespace tessera::scenes
