#include "scenes/scene_common.h"

#include <algorithm>
#include <cmath>

#include "scenes/gles_compat.h"

namespace tessera::scenes {

namespace {

constexpr float PI = 3.14159265358979f;
constexpr float MESH_DISTANCE = 2.6f;
constexpr float MESH_TILT_DEGREES = 20.0f;
constexpr float MESH_DEGREES_PER_FRAME = 0.5f;

}  // namespace

float rotation_degrees(int frame, float degrees_per_frame) {
  return std::fmod(static_cast<float>(frame) * degrees_per_frame, 360.0f);
}

bool expect_no_arguments(const char* scene, const std::vector<std::string>& args, std::string* error) {
  if (args.empty()) return true;
  *error = std::string(scene) + ": takes no arguments, got '" + args.front() + "'";
  return false;
}

bool whole_number_option(const char* scene, const std::vector<std::string>& args, std::size_t i, uint32_t low,
                         uint32_t high, uint32_t* value, std::string* error) {
  const std::string& name = args[i];
  if (i + 1 >= args.size()) {
    *error = std::string(scene) + ": " + name + " needs a value";
    return false;
  }
  const std::string& text = args[i + 1];
  uint64_t parsed = 0;
  bool ok = !text.empty();
  for (char c : text) {
    ok = ok && c >= '0' && c <= '9' && parsed <= high;
    if (ok) parsed = parsed * 10 + static_cast<uint64_t>(c - '0');
  }
  if (!ok || parsed < low || parsed > high) {
    *error = std::string(scene) + ": " + name + " takes a whole number from " + std::to_string(low) + " to " +
             std::to_string(high) + ", not '" + text + "'";
    return false;
  }
  *value = static_cast<uint32_t>(parsed);
  return true;
}

void set_perspective(int width, int height, float fovy_degrees, float near_plane, float far_plane) {
  glViewport(0, 0, width, height);
  const float aspect = float(std::max(width, 1)) / float(std::max(height, 1));
  const float top = near_plane * std::tan(fovy_degrees * PI / 360.0f);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustumf(-top * aspect, top * aspect, -top, top, near_plane, far_plane);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
}

void set_up_lit_mesh(int width, int height, const float diffuse[4]) {
  // At MESH_DISTANCE a 45-degree view is 2.15 units high: the unit sphere just fits.
  set_perspective(width, height, 45.0f, 1.0f, 10.0f);
  glClearColor(0.10f, 0.12f, 0.16f, 1.0f);
  glClearDepthf(1.0f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glShadeModel(GL_SMOOTH);
  // The scenes' models may be open (the teapot's spout, the gap under its
  // lid; OBJ files of any kind), so inner faces can show: no culling.
  glDisable(GL_CULL_FACE);

  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  // w = 0: a directional light from the upper left, behind the viewer. The
  // modelview matrix is identity here, so the direction is in eye space and
  // the light stays put while the model turns.
  const float light_direction[4] = {-1.0f, 1.0f, 1.0f, 0.0f};
  const float light_ambient[4] = {0.15f, 0.15f, 0.15f, 1.0f};
  const float light_diffuse[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  const float light_specular[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  glLightfv(GL_LIGHT0, GL_POSITION, light_direction);
  glLightfv(GL_LIGHT0, GL_AMBIENT, light_ambient);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, light_diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, light_specular);

  // GL ES 1.1 accepts only GL_FRONT_AND_BACK for materials.
  const float material_ambient[4] = {0.3f * diffuse[0], 0.3f * diffuse[1], 0.3f * diffuse[2], 1.0f};
  const float material_specular[4] = {0.7f, 0.7f, 0.7f, 1.0f};
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, material_ambient);
  glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, diffuse);
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, material_specular);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 40.0f);
}

void draw_lit_mesh(const Mesh& mesh, int frame) {
  draw_lit_meshes(&mesh, 1, frame);
}

void draw_lit_meshes(const Mesh* meshes, std::size_t count, int frame) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glTranslatef(0.0f, 0.0f, -MESH_DISTANCE);
  glRotatef(MESH_TILT_DEGREES, 1.0f, 0.0f, 0.0f);
  glRotatef(rotation_degrees(frame, MESH_DEGREES_PER_FRAME), 0.0f, 1.0f, 0.0f);

  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  for (std::size_t i = 0; i < count; ++i) {
    const Mesh& mesh = meshes[i];
    glVertexPointer(3, GL_FLOAT, 0, mesh.positions.data());
    glNormalPointer(GL_FLOAT, 0, mesh.normals.data());
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indices.size()), GL_UNSIGNED_SHORT, mesh.indices.data());
  }
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

const std::array<std::array<unsigned short, 4>, 6> CUBE_FACE_CORNERS = {{
    {{1, 3, 7, 5}},
    {{0, 4, 6, 2}},
    {{2, 6, 7, 3}},
    {{0, 1, 5, 4}},
    {{4, 5, 7, 6}},
    {{0, 2, 3, 1}},
}};

void flat_cube(float half_edge, const std::array<std::array<float, 4>, 6>& face_rgba, std::array<float, 36 * 3>& xyz,
               std::array<float, 36 * 4>& rgba) {
  const int quad_to_triangles[6] = {0, 1, 2, 0, 2, 3};
  for (size_t face = 0; face < 6; ++face)
    for (size_t k = 0; k < 6; ++k) {
      const size_t vertex = 6 * face + k;
      const unsigned corner = CUBE_FACE_CORNERS[face][quad_to_triangles[k]];
      for (size_t axis = 0; axis < 3; ++axis) xyz[3 * vertex + axis] = (corner >> axis) & 1 ? half_edge : -half_edge;
      for (size_t ch = 0; ch < 4; ++ch) rgba[4 * vertex + ch] = face_rgba[face][ch];
    }
}

std::vector<unsigned char> checkerboard_rgba8(int size, int square, unsigned char light,
                                              const std::vector<std::array<unsigned char, 3>>& colours,
                                              int colour_step) {
  std::vector<unsigned char> texels(static_cast<size_t>(size) * size * 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const int sx = x / square, sy = y / square;
      unsigned char* t = &texels[4 * (static_cast<size_t>(y) * size + x)];
      if ((sx + sy) % 2 == 0) {
        t[0] = t[1] = t[2] = light;
      } else {
        const auto& colour = colours[static_cast<size_t>(sx * colour_step + sy) % colours.size()];
        for (int ch = 0; ch < 3; ++ch) t[ch] = colour[ch];
      }
      t[3] = 255;
    }
  return texels;
}

}  // namespace tessera::scenes
