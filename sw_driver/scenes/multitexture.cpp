// Two texture units and the texture environments, one panel each, in a
// 4 x 2 grid drawn with an orthographic projection (so that the panels show
// the environments, not perspective):
//   top row    1. a base texture MODULATEd by the vertex colour on unit 0 and
//                 a light map MODULATEd on unit 1, whose texture matrix turns
//                 and slides the light map from frame to frame;
//              2. the base REPLACEd on unit 0, the light map ADDed on unit 1;
//              3. the base MODULATEd, the light map BLENDed on unit 1 with a
//                 blue GL_TEXTURE_ENV_COLOR;
//              4. the base MODULATEd, a window texture (alpha cut-outs) put
//                 on by DECAL on unit 1;
//   bottom row 5. GL_COMBINE INTERPOLATE of the base and the vertex colour
//                 by the constant's alpha on unit 0, then MODULATE by the
//                 light map with RGB_SCALE 2 and an ADD_SIGNED alpha on
//                 unit 1;
//              6. DOT3_RGB of a bump map with a light direction held in the
//                 vertex colour on unit 0, MODULATE with the base and
//                 RGB_SCALE 2 on unit 1;
//              7. SUBTRACT with a ONE_MINUS_SRC_COLOR operand on unit 0,
//                 ADD of the constant with ALPHA_SCALE 4 on unit 1 (and
//                 ONE_MINUS_SRC_ALPHA), blended over the background by its
//                 alpha;
//              8. DOT3_RGBA of the bump map with the constant, RGB_SCALE 2,
//                 on unit 0; INTERPOLATE of that and the base by its alpha
//                 on unit 1.
// Textures use GL_NEAREST so that the comparison with Mesa measures the
// environments rather than two bilinear filters. No arguments.
#include <array>
#include <cmath>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr int BASE_SIZE = 64;
constexpr int MAP_SIZE = 32;
constexpr int COLUMNS = 4, ROWS = 2;
constexpr float MARGIN = 0.06f;

GLuint g_base = 0, g_light = 0, g_window = 0, g_bump = 0;

using Texels = std::array<GLubyte, BASE_SIZE * BASE_SIZE * 4>;

// Bricks: warm colours with mortar lines, alpha falling from left to right.
Texels base_texels() {
  Texels t{};
  for (int y = 0; y < BASE_SIZE; ++y)
    for (int x = 0; x < BASE_SIZE; ++x) {
      GLubyte* p = &t[4 * (y * BASE_SIZE + x)];
      const int row = y / 8, shift = (row % 2) * 8;
      const bool mortar = y % 8 == 0 || (x + shift) % 16 == 0;
      const int brick = ((x + shift) / 16 + row * 5) % 3;
      p[0] = mortar ? 200 : static_cast<GLubyte>(150 + 40 * brick);
      p[1] = mortar ? 200 : static_cast<GLubyte>(60 + 30 * brick);
      p[2] = mortar ? 190 : static_cast<GLubyte>(40 + 10 * brick);
      p[3] = static_cast<GLubyte>(255 - 3 * x);
    }
  return t;
}

// A light map: a bright spot off centre, white in colour, its brightness also
// in alpha.
Texels light_texels() {
  Texels t{};
  for (int y = 0; y < MAP_SIZE; ++y)
    for (int x = 0; x < MAP_SIZE; ++x) {
      GLubyte* p = &t[4 * (y * MAP_SIZE + x)];
      const float dx = (x + 0.5f) / MAP_SIZE - 0.4f, dy = (y + 0.5f) / MAP_SIZE - 0.6f;
      const float light = std::max(0.15f, 1.0f - 2.2f * std::sqrt(dx * dx + dy * dy));
      const auto v = static_cast<GLubyte>(std::lround(255.0f * light));
      p[0] = v;
      p[1] = static_cast<GLubyte>(v * 15 / 16);
      p[2] = static_cast<GLubyte>(v * 13 / 16);
      p[3] = v;
    }
  return t;
}

// A window: opaque blue-grey frame, transparent panes (alpha 0) with a faint
// tint, and a half-transparent cross.
Texels window_texels() {
  Texels t{};
  for (int y = 0; y < MAP_SIZE; ++y)
    for (int x = 0; x < MAP_SIZE; ++x) {
      GLubyte* p = &t[4 * (y * MAP_SIZE + x)];
      const bool frame = x < 3 || y < 3 || x >= MAP_SIZE - 3 || y >= MAP_SIZE - 3;
      const bool cross = std::abs(x - MAP_SIZE / 2) < 2 || std::abs(y - MAP_SIZE / 2) < 2;
      p[0] = 70;
      p[1] = 90;
      p[2] = 140;
      p[3] = frame ? 255 : cross ? 128 : 0;
    }
  return t;
}

// A bump map: normals of a field of bumps, packed as n * 0.5 + 0.5.
Texels bump_texels() {
  Texels t{};
  for (int y = 0; y < MAP_SIZE; ++y)
    for (int x = 0; x < MAP_SIZE; ++x) {
      GLubyte* p = &t[4 * (y * MAP_SIZE + x)];
      const float u = (x + 0.5f) / 8.0f, v = (y + 0.5f) / 8.0f;
      const float nx = -0.6f * std::cos(6.2831853f * u) * std::sin(6.2831853f * v);
      const float ny = -0.6f * std::sin(6.2831853f * u) * std::cos(6.2831853f * v);
      const float len = std::sqrt(nx * nx + ny * ny + 1.0f);
      const float n[3] = {nx / len, ny / len, 1.0f / len};
      for (int c = 0; c < 3; ++c) p[c] = static_cast<GLubyte>(std::lround(255.0f * (n[c] * 0.5f + 0.5f)));
      p[3] = static_cast<GLubyte>(128 + 4 * x);
    }
  return t;
}

GLuint make_texture(const Texels& texels, int size) {
  GLuint name = 0;
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, size, size, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return name;
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("multitexture", args, error)) return false;
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrthof(0.0f, static_cast<GLfloat>(COLUMNS), 0.0f, static_cast<GLfloat>(ROWS), -1.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0.1f, 0.12f, 0.15f, 1.0f);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_LIGHTING);
  glShadeModel(GL_SMOOTH);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  g_base = make_texture(base_texels(), BASE_SIZE);
  g_light = make_texture(light_texels(), MAP_SIZE);
  g_window = make_texture(window_texels(), MAP_SIZE);
  g_bump = make_texture(bump_texels(), MAP_SIZE);
  return true;
}

// Unit `unit` textured with `texture` (0: off) in environment `mode`, its
// texture matrix the identity.
void set_unit(GLenum unit, GLuint texture, GLint mode) {
  glActiveTexture(unit);
  glMatrixMode(GL_TEXTURE);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  if (texture == 0) {
    glDisable(GL_TEXTURE_2D);
    return;
  }
  glEnable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, mode);
  glTexEnvi(GL_TEXTURE_ENV, GL_RGB_SCALE, 1);
  glTexEnvi(GL_TEXTURE_ENV, GL_ALPHA_SCALE, 1);
}

// One GL_COMBINE half: function, three sources and three operands.
void combine(GLenum which, GLint function, const GLint sources[3], const GLint operands[3]) {
  const bool rgb = which == GL_COMBINE_RGB;
  glTexEnvi(GL_TEXTURE_ENV, which, function);
  for (int i = 0; i < 3; ++i) {
    glTexEnvi(GL_TEXTURE_ENV, static_cast<GLenum>((rgb ? GL_SRC0_RGB : GL_SRC0_ALPHA) + i), sources[i]);
    glTexEnvi(GL_TEXTURE_ENV, static_cast<GLenum>((rgb ? GL_OPERAND0_RGB : GL_OPERAND0_ALPHA) + i), operands[i]);
  }
}

void set_env_color(float r, float g, float b, float a) {
  const GLfloat color[4] = {r, g, b, a};
  glTexEnvfv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, color);
}

// The panel in column c, row r (0 = bottom) with per-corner colours, unit 0
// and unit 1 coordinates covering [0, repeat0] and [0, 1].
void draw_panel(int c, int r, const GLubyte colors[16], float repeat0) {
  const float x0 = c + MARGIN, x1 = c + 1 - MARGIN, y0 = r + MARGIN, y1 = r + 1 - MARGIN;
  const GLfloat xy[] = {x0, y0, x1, y0, x1, y1, x0, y1};
  const GLfloat st0[] = {0, 0, repeat0, 0, repeat0, repeat0, 0, repeat0};
  const GLfloat st1[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const GLushort triangles[] = {0, 1, 2, 0, 2, 3};
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, xy);
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, colors);
  glClientActiveTexture(GL_TEXTURE0);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glTexCoordPointer(2, GL_FLOAT, 0, st0);
  glClientActiveTexture(GL_TEXTURE1);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glTexCoordPointer(2, GL_FLOAT, 0, st1);
  glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, triangles);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glClientActiveTexture(GL_TEXTURE0);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

const GLubyte WARM[16] = {255, 255, 255, 255, 255, 220, 160, 255, 180, 220, 255, 255, 255, 180, 220, 255};
const GLubyte GREYS[16] = {255, 255, 255, 255, 200, 200, 200, 200, 120, 120, 120, 160, 60, 60, 60, 255};
// A light direction per corner, packed as l * 0.5 + 0.5 (for DOT3).
const GLubyte LIGHT_DIRECTIONS[16] = {200, 200, 230, 255, 60, 190, 220, 255, 70, 70, 230, 255, 190, 60, 220, 255};

void draw(int frame) {
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_BLEND);
  const GLint texture_previous_constant[3] = {GL_TEXTURE, GL_PREVIOUS, GL_CONSTANT};
  const GLint colours[3] = {GL_SRC_COLOR, GL_SRC_COLOR, GL_SRC_ALPHA};
  const GLint alphas[3] = {GL_SRC_ALPHA, GL_SRC_ALPHA, GL_SRC_ALPHA};

  // 1. Base x vertex colour, x light map; unit 1's texture matrix moves.
  set_unit(GL_TEXTURE0, g_base, GL_MODULATE);
  set_unit(GL_TEXTURE1, g_light, GL_MODULATE);
  glMatrixMode(GL_TEXTURE);
  glTranslatef(0.5f, 0.5f, 0.0f);
  glRotatef(rotation_degrees(frame, 3.0f), 0.0f, 0.0f, 1.0f);
  glTranslatef(-0.5f + 0.02f * static_cast<float>(frame % 50), -0.5f, 0.0f);
  glMatrixMode(GL_MODELVIEW);
  draw_panel(0, 1, WARM, 2.0f);

  // 2. Base REPLACE, light map ADD.
  set_unit(GL_TEXTURE0, g_base, GL_REPLACE);
  set_unit(GL_TEXTURE1, g_light, GL_ADD);
  draw_panel(1, 1, WARM, 2.0f);

  // 3. Base MODULATE, light map BLEND towards a blue constant.
  set_unit(GL_TEXTURE0, g_base, GL_MODULATE);
  set_unit(GL_TEXTURE1, g_light, GL_BLEND);
  set_env_color(0.2f, 0.4f, 0.9f, 0.5f);
  draw_panel(2, 1, WARM, 2.0f);

  // 4. Base MODULATE, window DECAL.
  set_unit(GL_TEXTURE0, g_base, GL_MODULATE);
  set_unit(GL_TEXTURE1, g_window, GL_DECAL);
  draw_panel(3, 1, GREYS, 1.0f);

  // 5. INTERPOLATE(base, vertex colour, constant alpha); then
  //    light map x previous, RGB_SCALE 2, alpha ADD_SIGNED.
  set_unit(GL_TEXTURE0, g_base, GL_COMBINE);
  set_env_color(0.0f, 0.0f, 0.0f, 0.35f);
  {
    const GLint sources[3] = {GL_TEXTURE, GL_PRIMARY_COLOR, GL_CONSTANT};
    combine(GL_COMBINE_RGB, GL_INTERPOLATE, sources, colours);
    combine(GL_COMBINE_ALPHA, GL_REPLACE, sources, alphas);
  }
  set_unit(GL_TEXTURE1, g_light, GL_COMBINE);
  combine(GL_COMBINE_RGB, GL_MODULATE, texture_previous_constant, colours);
  combine(GL_COMBINE_ALPHA, GL_ADD_SIGNED, texture_previous_constant, alphas);
  glTexEnvi(GL_TEXTURE_ENV, GL_RGB_SCALE, 2);
  draw_panel(0, 0, GREYS, 2.0f);

  // 6. DOT3_RGB(bump, light direction in the vertex colour); x base, scale 2.
  set_unit(GL_TEXTURE0, g_bump, GL_COMBINE);
  {
    const GLint sources[3] = {GL_TEXTURE, GL_PRIMARY_COLOR, GL_CONSTANT};
    combine(GL_COMBINE_RGB, GL_DOT3_RGB, sources, colours);
    combine(GL_COMBINE_ALPHA, GL_REPLACE, sources, alphas);
  }
  set_unit(GL_TEXTURE1, g_base, GL_COMBINE);
  combine(GL_COMBINE_RGB, GL_MODULATE, texture_previous_constant, colours);
  combine(GL_COMBINE_ALPHA, GL_MODULATE, texture_previous_constant, alphas);
  glTexEnvi(GL_TEXTURE_ENV, GL_RGB_SCALE, 2);
  draw_panel(1, 0, LIGHT_DIRECTIONS, 1.0f);

  // 7. base - (1 - vertex colour); + constant, ALPHA_SCALE 4 with
  //    1 - alpha; drawn blended by its alpha.
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  set_unit(GL_TEXTURE0, g_base, GL_COMBINE);
  {
    const GLint sources[3] = {GL_TEXTURE, GL_PRIMARY_COLOR, GL_CONSTANT};
    const GLint operands[3] = {GL_SRC_COLOR, GL_ONE_MINUS_SRC_COLOR, GL_SRC_ALPHA};
    combine(GL_COMBINE_RGB, GL_SUBTRACT, sources, operands);
    const GLint alpha_operands[3] = {GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_SRC_ALPHA};
    combine(GL_COMBINE_ALPHA, GL_SUBTRACT, sources, alpha_operands);
  }
  set_unit(GL_TEXTURE1, g_light, GL_COMBINE);
  set_env_color(0.1f, 0.25f, 0.05f, 0.1f);
  {
    const GLint sources[3] = {GL_PREVIOUS, GL_CONSTANT, GL_TEXTURE};
    combine(GL_COMBINE_RGB, GL_ADD, sources, colours);
    const GLint alpha_operands[3] = {GL_ONE_MINUS_SRC_ALPHA, GL_SRC_ALPHA, GL_SRC_ALPHA};
    combine(GL_COMBINE_ALPHA, GL_ADD, sources, alpha_operands);
  }
  glTexEnvi(GL_TEXTURE_ENV, GL_ALPHA_SCALE, 4);
  draw_panel(2, 0, GREYS, 2.0f);
  glDisable(GL_BLEND);

  // 8. DOT3_RGBA(bump, constant) with RGB_SCALE 2; then INTERPOLATE(previous,
  //    base, previous alpha) and the alpha of the base.
  set_unit(GL_TEXTURE0, g_bump, GL_COMBINE);
  set_env_color(0.6f, 0.55f, 0.7f, 1.0f);
  {
    const GLint sources[3] = {GL_TEXTURE, GL_CONSTANT, GL_PRIMARY_COLOR};
    combine(GL_COMBINE_RGB, GL_DOT3_RGBA, sources, colours);
  }
  glTexEnvi(GL_TEXTURE_ENV, GL_RGB_SCALE, 2);
  set_unit(GL_TEXTURE1, g_base, GL_COMBINE);
  {
    const GLint sources[3] = {GL_PREVIOUS, GL_TEXTURE, GL_PREVIOUS};
    combine(GL_COMBINE_RGB, GL_INTERPOLATE, sources, colours);
    const GLint alpha_sources[3] = {GL_TEXTURE, GL_PREVIOUS, GL_CONSTANT};
    combine(GL_COMBINE_ALPHA, GL_REPLACE, alpha_sources, alphas);
  }
  draw_panel(3, 0, WARM, 1.0f);

  set_unit(GL_TEXTURE1, 0, GL_MODULATE);
  set_unit(GL_TEXTURE0, 0, GL_MODULATE);
}

}  // namespace

Scene multitexture_scene() {
  return {"multitexture",
          "Two texture units: light map, ADD, BLEND, DECAL and GL_COMBINE (INTERPOLATE, DOT3, SUBTRACT, scales) in "
          "eight panels, unit 1's texture matrix moving",
          init, draw};
}

}  // namespace tessera::scenes
