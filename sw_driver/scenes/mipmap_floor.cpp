// A textured floor receding to the horizon, in six strips side by side, one
// per minification filter: from the left GL_NEAREST, GL_LINEAR,
// GL_NEAREST_MIPMAP_NEAREST, GL_LINEAR_MIPMAP_NEAREST,
// GL_NEAREST_MIPMAP_LINEAR and GL_LINEAR_MIPMAP_LINEAR. The texture is a
// 64 x 64 checkerboard of coloured squares. The first two strips use level
// 0 alone; the NEAREST_MIPMAP_* strips take their levels from
// GL_GENERATE_MIPMAP, the LINEAR_MIPMAP_* strips from levels the scene
// filters itself and uploads with glTexImage2D at levels 1 to 6, each
// tinted by its level so that the level choice shows. The magnification
// filter is the minification filter's own (NEAREST for the NEAREST* strips),
// so that the switch point c is 0 throughout. The camera glides forward one
// texture repeat every 64 frames. No arguments.
#include <array>
#include <vector>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr int TEXTURE_SIZE = 64;
constexpr int SQUARE_SIZE = 8;
constexpr int STRIPS = 6;
constexpr int FIRST_STRIP_OFFSET = STRIPS / 2;  // strips from -3 to +3 strip widths, centred
constexpr float STRIP_WIDTH = 0.4f;
constexpr float FLOOR_Y = -1.0f;
constexpr float NEAR_Z = -1.0f, FAR_Z = -80.0f;
constexpr float REPEATS_PER_UNIT = 2.0f;  // texture repeats per world unit, across and along

const GLint MIN_FILTERS[STRIPS] = {GL_NEAREST,
                                   GL_LINEAR,
                                   GL_NEAREST_MIPMAP_NEAREST,
                                   GL_LINEAR_MIPMAP_NEAREST,
                                   GL_NEAREST_MIPMAP_LINEAR,
                                   GL_LINEAR_MIPMAP_LINEAR};

const std::vector<std::array<GLubyte, 3>> SQUARE_COLOURS = {{
    {{230, 50, 40}},
    {{40, 170, 70}},
    {{60, 90, 230}},
    {{240, 210, 40}},
    {{40, 200, 210}},
}};

// The tint of each uploaded level (level 0 has none).
constexpr GLubyte LEVEL_TINTS[7][3] = {{0, 0, 0},     {255, 0, 0},   {0, 255, 0},  {0, 0, 255},
                                       {255, 255, 0}, {0, 255, 255}, {255, 0, 255}};
const GLushort STRIP_TRIANGLES[] = {0, 1, 2, 0, 2, 3};

GLuint g_textures[STRIPS] = {};

// The next level by a 2 x 2 average, rounded, tinted towards a colour of
// its own (a quarter of the way) so that each level is told apart.
std::vector<GLubyte> next_level(const std::vector<GLubyte>& in, int size, int level) {
  const int half = size / 2;
  std::vector<GLubyte> out(static_cast<size_t>(half) * half * 4);
  for (int y = 0; y < half; ++y)
    for (int x = 0; x < half; ++x)
      for (int c = 0; c < 4; ++c) {
        auto at = [&](int i, int j) { return in[4 * ((2 * y + j) * size + 2 * x + i) + c]; };
        int v = (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1) + 2) / 4;
        if (c < 3) v = (3 * v + LEVEL_TINTS[level][c] + 2) / 4;
        out[4 * (y * half + x) + c] = static_cast<GLubyte>(v);
      }
  return out;
}

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("mipmap_floor", args, error)) return false;
  set_perspective(width, height, 50.0f, 0.5f, 100.0f);
  glClearColor(0.55f, 0.7f, 0.9f, 1.0f);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_LIGHTING);
  glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);

  const std::vector<GLubyte> base = checkerboard_rgba8(TEXTURE_SIZE, SQUARE_SIZE, 250, SQUARE_COLOURS, 2);
  glGenTextures(STRIPS, g_textures);
  for (int k = 0; k < STRIPS; ++k) {
    glBindTexture(GL_TEXTURE_2D, g_textures[k]);
    const GLint filter = MIN_FILTERS[k];
    const bool nearest =
        filter == GL_NEAREST || filter == GL_NEAREST_MIPMAP_NEAREST || filter == GL_NEAREST_MIPMAP_LINEAR;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, nearest ? GL_NEAREST : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    const bool generated = filter == GL_NEAREST_MIPMAP_NEAREST || filter == GL_NEAREST_MIPMAP_LINEAR;
    const bool uploaded = filter == GL_LINEAR_MIPMAP_NEAREST || filter == GL_LINEAR_MIPMAP_LINEAR;
    if (generated) glTexParameteri(GL_TEXTURE_2D, GL_GENERATE_MIPMAP, GL_TRUE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, TEXTURE_SIZE, TEXTURE_SIZE, 0, GL_RGBA, GL_UNSIGNED_BYTE, base.data());
    if (uploaded) {
      std::vector<GLubyte> level_texels = base;
      for (int level = 1, size = TEXTURE_SIZE; size > 1; ++level, size /= 2) {
        level_texels = next_level(level_texels, size, level);
        glTexImage2D(GL_TEXTURE_2D, level, GL_RGBA, size / 2, size / 2, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                     level_texels.data());
      }
    }
  }
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glEnable(GL_TEXTURE_2D);
  return true;
}

void draw(int frame) {
  glClear(GL_COLOR_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  const float glide = static_cast<float>(frame % 64) / 64.0f / REPEATS_PER_UNIT;
  glTranslatef(0.0f, 0.0f, glide);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  for (int k = 0; k < STRIPS; ++k) {
    const float x0 = static_cast<float>(k - FIRST_STRIP_OFFSET) * STRIP_WIDTH, x1 = x0 + STRIP_WIDTH;
    const GLfloat xyz[] = {x0, FLOOR_Y, NEAR_Z, x1, FLOOR_Y, NEAR_Z, x1, FLOOR_Y, FAR_Z, x0, FLOOR_Y, FAR_Z};
    const float s0 = x0 * REPEATS_PER_UNIT, s1 = x1 * REPEATS_PER_UNIT;
    const float t0 = -NEAR_Z * REPEATS_PER_UNIT, t1 = -FAR_Z * REPEATS_PER_UNIT;
    const GLfloat st[] = {s0, t0, s1, t0, s1, t1, s0, t1};
    glBindTexture(GL_TEXTURE_2D, g_textures[k]);
    glVertexPointer(3, GL_FLOAT, 0, xyz);
    glTexCoordPointer(2, GL_FLOAT, 0, st);
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, STRIP_TRIANGLES);
  }
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene mipmap_floor_scene() {
  return {"mipmap_floor",
          "A checkerboard floor receding to the horizon in six strips, one per minification filter (NEAREST, "
          "LINEAR and the four mipmap filters), with generated and uploaded mipmaps",
          init, draw};
}

}  // namespace tessera::scenes
