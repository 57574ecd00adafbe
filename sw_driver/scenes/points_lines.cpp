// Points and lines of every kind ES 1.1 has, in rows on a pixel-exact
// orthographic view (units are pixels, so sizes and widths are pixels):
//  1. points of several sizes (glPointSize), integer and not;
//  2. point sprites (OES_point_sprite) with GL_COORD_REPLACE_OES, textured
//     with a checkerboard whose texture coordinates run across each point;
//  3. points whose sizes come from a point-size array (OES_point_size_array),
//     GL_FLOAT and GL_FIXED;
//  4. points attenuated by their eye distance (glPointParameter, distance
//     attenuation, with GL_POINT_SIZE_MAX clamping the nearest);
//  5. wide lines (glLineWidth) at several angles, a strip and a loop.
// Everything is drawn with GL_CULL_FACE on and glCullFace(GL_FRONT_AND_BACK):
// that removes every polygon (the triangle drawn last must vanish), never a
// point or a line. Positions sit off pixel centres and edges so that no
// coverage decision is a tie. The picture does not change over frames.
//
// Desktop GL, on which the reference is drawn, has no point-size array:
// there the points of row 3 are drawn one by one with glPointSize of their
// array value, which is what the array means (the size of each vertex).
#include <array>
#include <cmath>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr int TEXTURE_SIZE = 8;
constexpr int POINTS_PER_ROW = 6;

int g_width = 0, g_height = 0;
GLuint g_texture = 0;

// Position of column i (0..POINTS_PER_ROW-1) of row `row` (0 at the top) of
// five, in pixels, a third of a pixel off the pixel grid.
void place(int row, int i, GLfloat* xyz) {
  const float column_width = float(g_width) / (POINTS_PER_ROW + 1);
  const float row_height = float(g_height) / 6;
  xyz[0] = std::floor(column_width * float(i + 1)) + 0.3f;
  xyz[1] = std::floor(float(g_height) - row_height * float(row + 1)) + 0.6f;
  xyz[2] = -1.0f;
}

constexpr std::array<std::array<GLfloat, 4>, POINTS_PER_ROW> COLOURS = {{
    {{0.95f, 0.25f, 0.2f, 1.0f}},
    {{0.25f, 0.9f, 0.3f, 1.0f}},
    {{0.3f, 0.45f, 1.0f, 1.0f}},
    {{1.0f, 0.9f, 0.25f, 1.0f}},
    {{0.25f, 0.9f, 0.95f, 1.0f}},
    {{0.9f, 0.35f, 0.9f, 1.0f}},
}};

void draw_point(const GLfloat* xyz, const GLfloat* rgba) {
  glColor4f(rgba[0], rgba[1], rgba[2], rgba[3]);
  glVertexPointer(3, GL_FLOAT, 0, xyz);
  glDrawArrays(GL_POINTS, 0, 1);
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("points_lines", args, error)) return false;
  g_width = width, g_height = height;
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrthof(0.0f, float(width), 0.0f, float(height), 0.5f, 50.0f);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0.08f, 0.08f, 0.12f, 1.0f);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT_AND_BACK);

  // A checkerboard of white and one colour per quadrant, so that a sprite
  // shows which way its s and t run.
  std::array<GLubyte, TEXTURE_SIZE * TEXTURE_SIZE * 4> texels{};
  for (int y = 0; y < TEXTURE_SIZE; ++y)
    for (int x = 0; x < TEXTURE_SIZE; ++x) {
      GLubyte* texel = &texels[4 * (y * TEXTURE_SIZE + x)];
      const bool white = (x + y) % 2 == 0;
      texel[0] = white ? 255 : (x < TEXTURE_SIZE / 2 ? 230 : 30);
      texel[1] = white ? 255 : (y < TEXTURE_SIZE / 2 ? 40 : 200);
      texel[2] = white ? 255 : 60;
      texel[3] = 255;
    }
  glGenTextures(1, &g_texture);
  glBindTexture(GL_TEXTURE_2D, g_texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, TEXTURE_SIZE, TEXTURE_SIZE, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  return true;
}

void draw_sized_points() {
  static constexpr GLfloat SIZES[POINTS_PER_ROW] = {1.0f, 2.0f, 3.0f, 4.0f, 6.0f, 9.0f};
  for (int i = 0; i < POINTS_PER_ROW; ++i) {
    GLfloat xyz[3];
    place(0, i, xyz);
    glPointSize(SIZES[i]);
    draw_point(xyz, COLOURS[i].data());
  }
}

void draw_sprites() {
  static constexpr GLfloat SIZES[POINTS_PER_ROW] = {8.0f, 10.0f, 12.0f, 14.0f, 16.0f, 20.0f};
  glEnable(GL_TEXTURE_2D);
  glEnable(GL_POINT_SPRITE_OES);
  glTexEnvi(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, GL_TRUE);
  for (int i = 0; i < POINTS_PER_ROW; ++i) {
    GLfloat xyz[3];
    place(1, i, xyz);
    glPointSize(SIZES[i]);
    const GLfloat white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    draw_point(xyz, i % 2 == 0 ? white : COLOURS[i].data());
  }
  glTexEnvi(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, GL_FALSE);
  glDisable(GL_POINT_SPRITE_OES);
  glDisable(GL_TEXTURE_2D);
}

void draw_size_array() {
  static constexpr GLfloat FLOAT_SIZES[POINTS_PER_ROW / 2] = {2.0f, 5.0f, 7.0f};
  static constexpr GLfixed FIXED_SIZES[POINTS_PER_ROW / 2] = {3 << 16, 8 << 16, 11 << 16};
  GLfloat xyz[POINTS_PER_ROW * 3];
  GLfloat rgba[POINTS_PER_ROW * 4];
  for (int i = 0; i < POINTS_PER_ROW; ++i) {
    place(2, i, &xyz[3 * i]);
    for (int c = 0; c < 4; ++c) rgba[4 * i + c] = COLOURS[POINTS_PER_ROW - 1 - i][c];
  }
  glEnableClientState(GL_COLOR_ARRAY);
  glColorPointer(4, GL_FLOAT, 0, rgba);
  glVertexPointer(3, GL_FLOAT, 0, xyz);
#if defined(TESSERA_GL_REFERENCE)
  for (int i = 0; i < POINTS_PER_ROW; ++i) {
    const int k = i % (POINTS_PER_ROW / 2);
    glPointSize(i < POINTS_PER_ROW / 2 ? FLOAT_SIZES[k] : float(FIXED_SIZES[k]) / 65536.0f);
    glDrawArrays(GL_POINTS, i, 1);
  }
#else
  glEnableClientState(GL_POINT_SIZE_ARRAY_OES);
  glPointSizePointerOES(GL_FLOAT, 0, FLOAT_SIZES);
  glDrawArrays(GL_POINTS, 0, POINTS_PER_ROW / 2);
  // The fixed-point sizes for the second half, whose positions and colours
  // start the arrays here.
  glVertexPointer(3, GL_FLOAT, 0, &xyz[3 * (POINTS_PER_ROW / 2)]);
  glColorPointer(4, GL_FLOAT, 0, &rgba[4 * (POINTS_PER_ROW / 2)]);
  glPointSizePointerOES(GL_FIXED, 0, FIXED_SIZES);
  glDrawArrays(GL_POINTS, 0, POINTS_PER_ROW / 2);
  glDisableClientState(GL_POINT_SIZE_ARRAY_OES);
#endif
  glDisableClientState(GL_COLOR_ARRAY);
}

void draw_attenuated_points() {
  // size * sqrt(1 / (0.2 + 0.01 d^2)) at eye distances d = 2, 4, ... 12,
  // then clamped to at most 14: 14 (clamped from 16.3), 13.3, 10.7, 8.7,
  // 7.3, 6.2 for size 8. Each point sits on the eye's axis (x = y = 0),
  // so its distance is |z| however an implementation measures it, and its
  // own projection puts it in its column.
  const GLfloat attenuation[3] = {0.2f, 0.0f, 0.01f};
  glPointParameterfv(GL_POINT_DISTANCE_ATTENUATION, attenuation);
  glPointParameterf(GL_POINT_SIZE_MAX, 14.0f);
  glPointSize(8.0f);
  glColor4f(0.95f, 0.75f, 0.3f, 1.0f);
  glMatrixMode(GL_PROJECTION);
  glPushMatrix();
  for (int i = 0; i < POINTS_PER_ROW; ++i) {
    GLfloat at[3];
    place(3, i, at);
    glLoadIdentity();
    glOrthof(-at[0], float(g_width) - at[0], -at[1], float(g_height) - at[1], 0.5f, 50.0f);
    const GLfloat xyz[3] = {0.0f, 0.0f, -2.0f - 2.0f * float(i)};
    glVertexPointer(3, GL_FLOAT, 0, xyz);
    glDrawArrays(GL_POINTS, 0, 1);
  }
  glPopMatrix();
  glMatrixMode(GL_MODELVIEW);
  const GLfloat none[3] = {1.0f, 0.0f, 0.0f};
  glPointParameterfv(GL_POINT_DISTANCE_ATTENUATION, none);
  glPointParameterf(GL_POINT_SIZE_MAX, 64.0f);
}

void draw_lines() {
  const float w = float(g_width), h = float(g_height);
  const float top = std::floor(h / 6.0f) + 0.4f;  // the band of the last row
  // Separate segments: horizontal, shallow, steep and vertical, one width each.
  const GLfloat segments[8 * 3] = {
      w * 0.06f + 0.3f, top,         -1.0f, w * 0.26f + 0.3f, top,         -1.0f,  // horizontal
      w * 0.30f + 0.3f, top - 4.0f,  -1.0f, w * 0.48f + 0.3f, top + 6.3f,  -1.0f,  // shallow
      w * 0.52f + 0.3f, top - 9.0f,  -1.0f, w * 0.57f + 0.3f, top + 10.4f, -1.0f,  // steep
      w * 0.62f + 0.3f, top - 10.0f, -1.0f, w * 0.62f + 0.3f, top + 10.0f, -1.0f,  // vertical
  };
  const GLfloat segment_rgba[8 * 4] = {1, 0.3f, 0.3f, 1, 1,    1, 0.3f, 1, 0.3f, 1,    0.3f, 1, 0.3f, 0.4f, 1,    1,
                                       1, 0.5f, 0.1f, 1, 0.5f, 1, 1,    1, 0.8f, 0.8f, 0.8f, 1, 0.8f, 0.3f, 0.9f, 1};
  glEnableClientState(GL_COLOR_ARRAY);
  glColorPointer(4, GL_FLOAT, 0, segment_rgba);
  glVertexPointer(3, GL_FLOAT, 0, segments);
  const GLfloat widths[4] = {1.0f, 2.0f, 3.0f, 5.0f};
  for (int i = 0; i < 4; ++i) {
    glLineWidth(widths[i]);
    glDrawArrays(GL_LINES, 2 * i, 2);
  }
  glDisableClientState(GL_COLOR_ARRAY);

  // A strip and a loop (a triangle's outline), 2 pixels wide.
  const GLfloat strip[4 * 3] = {w * 0.68f + 0.3f, top - 8.0f, -1.0f, w * 0.74f + 0.3f, top + 9.3f, -1.0f,
                                w * 0.80f + 0.3f, top - 7.6f, -1.0f, w * 0.86f + 0.3f, top + 8.7f, -1.0f};
  glLineWidth(2.0f);
  glColor4f(0.4f, 0.9f, 1.0f, 1.0f);
  glVertexPointer(3, GL_FLOAT, 0, strip);
  glDrawArrays(GL_LINE_STRIP, 0, 4);
  const GLfloat loop[3 * 3] = {w * 0.88f + 0.3f, top - 9.0f, -1.0f, w * 0.97f + 0.3f, top - 8.6f, -1.0f,
                               w * 0.92f + 0.3f, top + 9.4f, -1.0f};
  glLineWidth(1.0f);
  glColor4f(1.0f, 0.85f, 0.4f, 1.0f);
  glVertexPointer(3, GL_FLOAT, 0, loop);
  glDrawArrays(GL_LINE_LOOP, 0, 3);
}

void draw(int /*frame*/) {
  glClear(GL_COLOR_BUFFER_BIT);
  glEnableClientState(GL_VERTEX_ARRAY);
  draw_sized_points();
  draw_sprites();
  draw_size_array();
  draw_attenuated_points();
  draw_lines();
  // A triangle across the middle: culled, as every polygon is here.
  const GLfloat triangle[3 * 3] = {
      0.0f, 0.0f, -1.0f, float(g_width), 0.0f, -1.0f, float(g_width) * 0.5f, float(g_height), -1.0f};
  glColor4f(1.0f, 1.0f, 1.0f, 1.0f);
  glVertexPointer(3, GL_FLOAT, 0, triangle);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene points_lines_scene() {
  return {"points_lines",
          "Sized points, point sprites, point-size arrays, attenuated points and wide lines, with every polygon culled",
          init, draw};
}

}  // namespace tessera::scenes
