// Antialiased polygons, after the Red Book's `aapoly`: a wheel of 24 thin,
// flat-coloured spokes around a centre, drawn with polygon antialiasing and
// source-alpha blending over a black background. Every spoke is one long,
// thin triangle: its long edges run at all angles, and their coverage comes
// from normalised edge functions E / (|dx| + |dy|) whose long-edge operands
// are where the reciprocal unit's Method 1 is least accurate
// (docs/rasterizer.md).
//
// GL_POLYGON_SMOOTH is desktop GL only; tessera's driver accepts its value
// (TESSERA_POLYGON_SMOOTH, gles_compat.h) and the raster back end computes
// the coverage (EASA); the arm back end ignores it and draws aliased edges.
// The Red Book blends with (SRC_ALPHA_SATURATE, ONE) front to back, which
// needs destination alpha; an RGB565 display has none, so this scene blends
// with (SRC_ALPHA, ONE_MINUS_SRC_ALPHA) and keeps the spokes apart (they
// touch only near the centre). The picture does not change over frames.
#include <algorithm>
#include <cmath>

#include "scenes/gles_compat.h"
#include "scenes/scene_common.h"

namespace tessera::scenes {

namespace {

constexpr int SPOKES = 24;
constexpr float INNER_RADIUS = 0.12f;  // in units of the shorter half-side of the window
constexpr float OUTER_RADIUS = 0.95f;
constexpr float HALF_WIDTH_DEGREES = 2.5f;  // half the angle a spoke's outer end subtends

GLfloat g_xy[SPOKES * 3 * 2];
GLfloat g_rgba[SPOKES * 3 * 4];

bool init(int width, int height, const std::vector<std::string>& args, std::string* error) {
  if (!expect_no_arguments("aapoly", args, error)) return false;
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  // Square units, the shorter side spanning -1..1.
  const float aspect = float(width) / float(height);
  if (aspect >= 1.0f)
    glOrthof(-aspect, aspect, -1.0f, 1.0f, -1.0f, 1.0f);
  else
    glOrthof(-1.0f, 1.0f, -1.0f / aspect, 1.0f / aspect, -1.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glDisable(GL_DEPTH_TEST);
  glShadeModel(GL_FLAT);
  glEnable(TESSERA_POLYGON_SMOOTH);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

  constexpr float PI = 3.14159265358979f;
  for (int i = 0; i < SPOKES; ++i) {
    // Offset by a third of a step so that no spoke is axis-aligned.
    const float angle = 2.0f * PI * (static_cast<float>(i) + 1.0f / 3.0f) / SPOKES;
    const float half = HALF_WIDTH_DEGREES * PI / 180.0f;
    const float xy[3][2] = {{INNER_RADIUS * std::cos(angle), INNER_RADIUS * std::sin(angle)},
                            {OUTER_RADIUS * std::cos(angle - half), OUTER_RADIUS * std::sin(angle - half)},
                            {OUTER_RADIUS * std::cos(angle + half), OUTER_RADIUS * std::sin(angle + half)}};
    // A colour wheel: hue from the angle, full saturation.
    const float hue = 6.0f * static_cast<float>(i) / SPOKES;
    const auto ramp = [hue](float offset) {
      const float h = std::fmod(hue + offset, 6.0f);
      return std::clamp(std::fabs(h - 3.0f) - 1.0f, 0.0f, 1.0f);
    };
    const GLfloat rgba[4] = {ramp(0.0f), ramp(4.0f), ramp(2.0f), 1.0f};
    for (int v = 0; v < 3; ++v) {
      g_xy[(3 * i + v) * 2 + 0] = xy[v][0];
      g_xy[(3 * i + v) * 2 + 1] = xy[v][1];
      for (int c = 0; c < 4; ++c) g_rgba[(3 * i + v) * 4 + c] = rgba[c];
    }
  }
  return true;
}

void draw(int /*frame*/) {
  glClear(GL_COLOR_BUFFER_BIT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, g_xy);
  glColorPointer(4, GL_FLOAT, 0, g_rgba);
  glDrawArrays(GL_TRIANGLES, 0, 3 * SPOKES);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Scene aapoly_scene() {
  return {"aapoly",
          "A wheel of thin flat-coloured spokes drawn with polygon antialiasing (after the Red Book's aapoly)", init,
          draw};
}

}  // namespace tessera::scenes
