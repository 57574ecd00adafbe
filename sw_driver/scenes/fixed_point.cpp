// A program written only with the fixed-point (S15.16) half of ES 1.1, as
// one for a CPU without floating point would be: three textured, lit cubes
// turning above a textured, lit floor, a positional light with a specular
// highlight, and the light's position marked by unlit points. Every value
// handed to GL is a GLfixed (glClearColorx, glClearDepthx, glFrustumx,
// glTranslatex, glRotatex, glScalex, glLightxv, glLightModelxv,
// glMaterialxv, glMaterialx, glTexParameterx, glTexEnvx, glColor4x,
// glNormal3x, glPointSizex; GL_FIXED vertex, normal and texture coordinate
// arrays) and the program's own arithmetic is integer arithmetic too.
//
// The floor and the cubes' faces are grids with one checkerboard square per
// cell, not a few large triangles: lighting is per vertex, and the array
// back ends interpolate texture coordinates affinely, which agrees with the
// perspective-correct reference at the vertices, so on the squares' edges.
// Its features are those every back end draws itself (one texture unit,
// GL_MODULATE, level 0 with the same minification and magnification filter,
// no blending, no fog), so the picture is compared with Mesa on all of them.
#include <array>
#include <cstdint>
#include <vector>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr GLfixed ONE = 1 << 16;

// value / 100 in S15.16, rounded: the scene's constants in hundredths.
constexpr GLfixed hundredths(int value) {
  return static_cast<GLfixed>((static_cast<int64_t>(value) * ONE + (value < 0 ? -50 : 50)) / 100);
}

constexpr int FLOOR_CELLS = 12;
constexpr int FACE_CELLS = 4;  // ONE / 4 is exact, so the faces' shared edges have the same vertices
constexpr int FACE_VERTICES = (FACE_CELLS + 1) * (FACE_CELLS + 1);
constexpr int TEXTURE_SIZE = 64;
constexpr int SQUARE_SIZE = 16;   // 4 x 4 squares: one per face cell
constexpr int FLOOR_REPEATS = 3;  // across and along: 12 squares, one per floor cell

struct CubeInstance {
  std::array<GLfixed, 3> position;
  GLfixed scale;
  std::array<GLfixed, 3> axis;
  GLfixed start_degrees;  // no face seen edge-on at frame 0
  GLfixed degrees_per_frame;
};

// Each cube's lowest point, at its half diagonal (0.87 x scale) below its
// centre, stays above the floor (y = -1) however it turns.
const std::array<CubeInstance, 3> CUBES = {{
    {{hundredths(-170), 0, hundredths(-550)}, ONE, {ONE, ONE, 0}, 30 * ONE, 2 * ONE},
    {{hundredths(40), hundredths(15), hundredths(-750)},
     hundredths(130),
     {0, ONE, hundredths(30)},
     -20 * ONE,
     -3 * ONE / 2},
    {{hundredths(190), hundredths(-10), hundredths(-480)}, hundredths(80), {ONE, 0, ONE}, 50 * ONE, 3 * ONE},
}};

// The camera looks down at the floor by this much (a rotation of the world
// about x under the light, which stays fixed in eye space).
constexpr GLfixed CAMERA_TILT_DEGREES = 12 * ONE;

// The light, in eye space (placed under the identity modelview), above the
// floor in front of the cubes, where its marker is in view between them.
const std::array<GLfixed, 4> LIGHT_POSITION = {-ONE / 2, hundredths(90), -3 * ONE, ONE};

struct Geometry {
  // The cube: each face a grid of FACE_CELLS x FACE_CELLS cells, its
  // vertices with the face's normal and texture coordinates from (0, 0) to
  // (1, 1) across the face.
  std::vector<GLfixed> cube_xyz, cube_normals, cube_st;
  std::vector<GLushort> cube_indices;
  // The floor: (FLOOR_CELLS + 1)^2 vertices at y = -1 from x = -4 to 4 and
  // z = -1 to -9, the texture repeated FLOOR_REPEATS times each way.
  std::vector<GLfixed> floor_xyz, floor_st;
  std::vector<GLushort> floor_indices;
  // The light's marker: one large point and four small ones around it.
  std::array<GLfixed, 5 * 3> marker_xyz;
};

Geometry g_geometry;

// Corner k of CUBE_FACE_CORNERS is at +-1/2 on each axis by its bits.
GLfixed corner_coordinate(unsigned corner, unsigned axis) {
  return (corner >> axis) & 1 ? ONE / 2 : -ONE / 2;
}

void build_cube() {
  Geometry& g = g_geometry;
  g.cube_xyz.clear(), g.cube_normals.clear(), g.cube_st.clear(), g.cube_indices.clear();
  // A face's corners 0, 1, 3 span it: vertex (i, j) is corner 0 + i / N of
  // the way to corner 1 + j / N of the way to corner 3, with s, t = i / N,
  // j / N; (i, j), (i + 1, j), (i + 1, j + 1) keeps the corners' winding.
  for (unsigned face = 0; face < 6; ++face) {
    const auto& corners = CUBE_FACE_CORNERS[face];
    const auto base = static_cast<GLushort>(g.cube_xyz.size() / 3);
    for (int j = 0; j <= FACE_CELLS; ++j)
      for (int i = 0; i <= FACE_CELLS; ++i) {
        for (unsigned axis = 0; axis < 3; ++axis) {
          const GLfixed origin = corner_coordinate(corners[0], axis);
          const GLfixed along_i = corner_coordinate(corners[1], axis) - origin;
          const GLfixed along_j = corner_coordinate(corners[3], axis) - origin;
          g.cube_xyz.push_back(origin + along_i * i / FACE_CELLS + along_j * j / FACE_CELLS);
          // Faces +x, -x, +y, -y, +z, -z.
          g.cube_normals.push_back(axis == face / 2 ? (face % 2 ? -ONE : ONE) : 0);
        }
        g.cube_st.push_back(ONE * i / FACE_CELLS);
        g.cube_st.push_back(ONE * j / FACE_CELLS);
      }
    for (int j = 0; j < FACE_CELLS; ++j)
      for (int i = 0; i < FACE_CELLS; ++i) {
        const auto at = [base](int x, int y) { return GLushort(base + y * (FACE_CELLS + 1) + x); };
        const std::array<GLushort, 6> quad = {at(i, j), at(i + 1, j),     at(i + 1, j + 1),
                                              at(i, j), at(i + 1, j + 1), at(i, j + 1)};
        g.cube_indices.insert(g.cube_indices.end(), quad.begin(), quad.end());
      }
  }
  static_assert(6 * FACE_VERTICES < 65536, "16-bit indices");
}

void build_floor() {
  Geometry& g = g_geometry;
  g.floor_xyz.clear(), g.floor_st.clear(), g.floor_indices.clear();
  // Row j runs from z = -1 away to z = -9, column i from x = -4 to 4, so
  // (i, j), (i + 1, j), (i + 1, j + 1) is counter-clockwise seen from above.
  for (int j = 0; j <= FLOOR_CELLS; ++j)
    for (int i = 0; i <= FLOOR_CELLS; ++i) {
      g.floor_xyz.push_back(-4 * ONE + 8 * ONE * i / FLOOR_CELLS);
      g.floor_xyz.push_back(-ONE);
      g.floor_xyz.push_back(-ONE - 8 * ONE * j / FLOOR_CELLS);
      g.floor_st.push_back(FLOOR_REPEATS * ONE * i / FLOOR_CELLS);
      g.floor_st.push_back(FLOOR_REPEATS * ONE * j / FLOOR_CELLS);
    }
  for (int j = 0; j < FLOOR_CELLS; ++j)
    for (int i = 0; i < FLOOR_CELLS; ++i) {
      const auto at = [](int x, int y) { return GLushort(y * (FLOOR_CELLS + 1) + x); };
      const std::array<GLushort, 6> quad = {at(i, j), at(i + 1, j),     at(i + 1, j + 1),
                                            at(i, j), at(i + 1, j + 1), at(i, j + 1)};
      g.floor_indices.insert(g.floor_indices.end(), quad.begin(), quad.end());
    }
}

void build_marker() {
  const std::array<std::array<GLfixed, 3>, 5> offsets = {
      {{0, 0, 0}, {-hundredths(15), 0, 0}, {hundredths(15), 0, 0}, {0, -hundredths(15), 0}, {0, hundredths(15), 0}}};
  for (size_t p = 0; p < offsets.size(); ++p)
    for (size_t axis = 0; axis < 3; ++axis)
      g_geometry.marker_xyz[3 * p + axis] = LIGHT_POSITION[axis] + offsets[p][axis];
}

// The frustum of a 45-degree vertical view from near 1 to far 20: top =
// tan(22.5 degrees) = 0.41421 (27146 / 65536), right = top x width / height.
void set_frustum(int width, int height) {
  glViewport(0, 0, width, height);
  const int64_t top = 27146;
  const auto right = static_cast<GLfixed>(top * (width > 0 ? width : 1) / (height > 0 ? height : 1));
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustumx(-right, right, -static_cast<GLfixed>(top), static_cast<GLfixed>(top), ONE, 20 * ONE);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
}

void set_up_lighting() {
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  const GLfixed model_ambient[4] = {hundredths(10), hundredths(10), hundredths(12), ONE};
  glLightModelxv(GL_LIGHT_MODEL_AMBIENT, model_ambient);
  const GLfixed ambient[4] = {hundredths(15), hundredths(15), hundredths(15), ONE};
  const GLfixed diffuse[4] = {hundredths(95), hundredths(90), hundredths(80), ONE};
  const GLfixed specular[4] = {hundredths(70), hundredths(70), hundredths(70), ONE};
  glLightxv(GL_LIGHT0, GL_POSITION, LIGHT_POSITION.data());
  glLightxv(GL_LIGHT0, GL_AMBIENT, ambient);
  glLightxv(GL_LIGHT0, GL_DIFFUSE, diffuse);
  glLightxv(GL_LIGHT0, GL_SPECULAR, specular);
  const GLfixed material[4] = {hundredths(90), hundredths(90), hundredths(90), ONE};
  const GLfixed material_specular[4] = {hundredths(50), hundredths(50), hundredths(50), ONE};
  glMaterialxv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, material);
  glMaterialxv(GL_FRONT_AND_BACK, GL_SPECULAR, material_specular);
  glMaterialx(GL_FRONT_AND_BACK, GL_SHININESS, 16 * ONE);
}

void set_up_texture() {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  const std::vector<std::array<unsigned char, 3>> colours = {{200, 60, 50}, {60, 150, 210}, {230, 190, 60}};
  const std::vector<unsigned char> texels = checkerboard_rgba8(TEXTURE_SIZE, SQUARE_SIZE, 235, colours, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, TEXTURE_SIZE, TEXTURE_SIZE, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  // Enums travel unscaled through the x commands.
  glTexParameterx(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameterx(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameterx(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameterx(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glTexEnvx(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("fixed_point", args, error)) return false;
  build_cube();
  build_floor();
  build_marker();
  set_frustum(width, height);
  glClearColorx(hundredths(6), hundredths(7), hundredths(12), ONE);
  glClearDepthx(ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glShadeModel(GL_SMOOTH);
  glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
  set_up_lighting();
  set_up_texture();
  return true;
}

// The turn after `frame` frames at `degrees_per_frame`, kept within one
// turn in integers (a long run never overflows 16.16).
GLfixed turn(int frame, const CubeInstance& cube) {
  const int64_t degrees = cube.start_degrees + static_cast<int64_t>(frame) * cube.degrees_per_frame;
  return static_cast<GLfixed>(degrees % (360 * static_cast<int64_t>(ONE)));
}

void draw(int frame) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glRotatex(CAMERA_TILT_DEGREES, ONE, 0, 0);

  // Lit and textured: the floor with one normal for all (glNormal3x), the
  // cubes with a normal array.
  glEnable(GL_LIGHTING);
  glEnable(GL_TEXTURE_2D);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glNormal3x(0, ONE, 0);
  glVertexPointer(3, GL_FIXED, 0, g_geometry.floor_xyz.data());
  glTexCoordPointer(2, GL_FIXED, 0, g_geometry.floor_st.data());
  glDrawElements(GL_TRIANGLES, GLsizei(g_geometry.floor_indices.size()), GL_UNSIGNED_SHORT,
                 g_geometry.floor_indices.data());

  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FIXED, 0, g_geometry.cube_xyz.data());
  glNormalPointer(GL_FIXED, 0, g_geometry.cube_normals.data());
  glTexCoordPointer(2, GL_FIXED, 0, g_geometry.cube_st.data());
  for (const CubeInstance& cube : CUBES) {
    glPushMatrix();
    glTranslatex(cube.position[0], cube.position[1], cube.position[2]);
    glRotatex(turn(frame, cube), cube.axis[0], cube.axis[1], cube.axis[2]);
    glScalex(cube.scale, cube.scale, cube.scale);
    glDrawElements(GL_TRIANGLES, GLsizei(g_geometry.cube_indices.size()), GL_UNSIGNED_SHORT,
                   g_geometry.cube_indices.data());
    glPopMatrix();
  }
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);

  // Unlit, untextured: the light's marker in a flat colour, in eye space
  // where the light is.
  glLoadIdentity();
  glDisable(GL_LIGHTING);
  glDisable(GL_TEXTURE_2D);
  glColor4x(ONE, hundredths(90), hundredths(40), ONE);
  glVertexPointer(3, GL_FIXED, 0, g_geometry.marker_xyz.data());
  glPointSizex(7 * ONE);
  glDrawArrays(GL_POINTS, 0, 1);
  glPointSizex(3 * ONE);
  glDrawArrays(GL_POINTS, 1, 4);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene fixed_point_scene() {
  return {"fixed_point",
          "textured, lit cubes turning over a textured floor, written only with fixed-point calls and GL_FIXED arrays",
          init, draw};
}

}  // namespace tessera::scenes
