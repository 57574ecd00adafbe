// The ES 1.1 geometry features of the GL front end, through the GL API on a
// recording renderer (64 x 48, a 12-bit depth buffer): user clip planes,
// polygon offset, culling of polygons only, point sizes, point-size arrays,
// point parameters, point sprites and two-sided lighting, with the errors
// the specification gives each new call. Expected values are worked out
// by hand from the specification's formulas, in the comments.
#include <GLES/gl.h>
#include <GLES/glext.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "gl_test_fixture.h"

using namespace tessera;
using tessera::test::GlApi;

namespace {

GLenum error() {
  return glGetError();
}

// The extent of everything drawn, in pixels (9.4 codes / 16).
struct Extent {
  float min_x = 1e9f, max_x = -1e9f, min_y = 1e9f, max_y = -1e9f;
};

Extent extent(const std::vector<gl::Triangle>& triangles, size_t first = 0, size_t count = SIZE_MAX) {
  Extent e;
  for (size_t i = first; i < triangles.size() && i - first < count; ++i)
    for (const gl::ScreenVertex& v : triangles[i].v) {
      e.min_x = std::min(e.min_x, v.x / 16.0f), e.max_x = std::max(e.max_x, v.x / 16.0f);
      e.min_y = std::min(e.min_y, v.y / 16.0f), e.max_y = std::max(e.max_y, v.y / 16.0f);
    }
  return e;
}

uint32_t unorm24(double z) {
  return static_cast<uint32_t>(std::llround(static_cast<float>(z) * double((1u << 24) - 1)));
}

}  // namespace

// ---- Culling ----------------------------------------------------------------

TEST_F(GlApi, CullingFrontAndBackKeepsPointsAndLines) {
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT_AND_BACK);
  const float triangle[] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  draw_triangle(triangle);
  EXPECT_TRUE(renderer.triangles.empty());
  // A point is two triangles, one of them clockwise and one not would be
  // culled whichever way if culling applied to them; both must stay.
  const float points[] = {0.1f, 0.1f, 0, -0.3f, 0.2f, 0};
  glVertexPointer(3, GL_FLOAT, 0, points);
  glPointSize(3);
  glDrawArrays(GL_POINTS, 0, 2);
  EXPECT_EQ(renderer.triangles.size(), 4u);
  glDrawArrays(GL_LINES, 0, 2);
  EXPECT_EQ(renderer.triangles.size(), 6u);
  glCullFace(GL_FRONT);
  glFrontFace(GL_CW);
  glDrawArrays(GL_LINE_LOOP, 0, 2);
  EXPECT_EQ(renderer.triangles.size(), 10u);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

// ---- User clip planes -------------------------------------------------------

TEST_F(GlApi, ClipPlaneIsStoredInEyeCoordinates) {
  GLint planes = 0;
  glGetIntegerv(GL_MAX_CLIP_PLANES, &planes);
  EXPECT_EQ(planes, 6);
  // With the modelview a translation by (0, 0, -5), the object-space plane
  // z >= 0 is eye-space z + 5 >= 0: (p1 p2 p3 p4) M^-1 = (0, 0, 1, 5).
  glMatrixMode(GL_MODELVIEW);
  glTranslatef(0, 0, -5);
  const float object_plane[4] = {0, 0, 1, 0};
  glClipPlanef(GL_CLIP_PLANE3, object_plane);
  float eye_plane[4] = {};
  glGetClipPlanef(GL_CLIP_PLANE3, eye_plane);
  EXPECT_FLOAT_EQ(eye_plane[0], 0);
  EXPECT_FLOAT_EQ(eye_plane[1], 0);
  EXPECT_FLOAT_EQ(eye_plane[2], 1);
  EXPECT_FLOAT_EQ(eye_plane[3], 5);
  // A rotation by 90 degrees about z takes object x to eye y: the plane
  // x >= 1 (1, 0, 0, -1) becomes eye y >= 1 (0, 1, 0, -1).
  glLoadIdentity();
  glRotatef(90, 0, 0, 1);
  const float x_plane[4] = {1, 0, 0, -1};
  glClipPlanef(GL_CLIP_PLANE0, x_plane);
  glGetClipPlanef(GL_CLIP_PLANE0, eye_plane);
  EXPECT_NEAR(eye_plane[0], 0, 1e-6);
  EXPECT_NEAR(eye_plane[1], 1, 1e-6);
  EXPECT_NEAR(eye_plane[2], 0, 1e-6);
  EXPECT_NEAR(eye_plane[3], -1, 1e-6);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, ClipPlaneErrors) {
  const float plane[4] = {1, 0, 0, 0};
  glClipPlanef(GL_CLIP_PLANE0 + 6, plane);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  float out[4] = {7, 7, 7, 7};
  glGetClipPlanef(GL_CLIP_PLANE0 + 6, out);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(out[0], 7);
  glEnable(GL_CLIP_PLANE0 + 6);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glEnable(GL_CLIP_PLANE5);
  EXPECT_EQ(glIsEnabled(GL_CLIP_PLANE5), GL_TRUE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, ClipPlaneCutsTrianglesLinesAndPoints) {
  // Identity matrices: eye = clip = NDC. The plane x <= 0.5 (-1, 0, 0, 0.5)
  // is window x <= (0.5 + 1) * 32 = 48 on the 64-pixel-wide viewport.
  const float plane[4] = {-1, 0, 0, 0.5f};
  glClipPlanef(GL_CLIP_PLANE1, plane);
  glEnable(GL_CLIP_PLANE1);
  const float triangle[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0};
  draw_triangle(triangle);
  ASSERT_FALSE(renderer.triangles.empty());
  Extent e = extent(renderer.triangles);
  EXPECT_FLOAT_EQ(e.max_x, 48);
  EXPECT_FLOAT_EQ(e.min_x, 0);

  // A horizontal line from x = -1 to 1 ends at the plane: window x 0 to
  // 48, which the line's placement (half a pixel back along it, as Mesa
  // draws wide lines) makes -0.5 to 47.5, then the view volume 0 to 47.5.
  renderer.triangles.clear();
  const float line[] = {-1, 0.1f, 0, 1, 0.1f, 0};
  glVertexPointer(3, GL_FLOAT, 0, line);
  glDrawArrays(GL_LINES, 0, 2);
  ASSERT_FALSE(renderer.triangles.empty());
  e = extent(renderer.triangles);
  EXPECT_FLOAT_EQ(e.max_x, 47.5f);
  EXPECT_FLOAT_EQ(e.min_x, 0);

  // A point is discarded whole when its centre is outside, kept whole
  // otherwise (a wide point near the plane is not cut).
  renderer.triangles.clear();
  const float points[] = {0.6f, 0, 0, 0.45f, 0, 0};
  glVertexPointer(3, GL_FLOAT, 0, points);
  glPointSize(8);
  glDrawArrays(GL_POINTS, 0, 2);
  ASSERT_EQ(renderer.triangles.size(), 2u);
  e = extent(renderer.triangles);
  // Centre x = 1.45 * 32 = 46.4; an aliased point's left column is
  // floor(46.4 + 3/4 - 8/2) = 43 (as Mesa places it), so it covers 43 to 51.
  EXPECT_FLOAT_EQ(e.min_x, 43);
  EXPECT_FLOAT_EQ(e.max_x, 51);

  // Disabled, it clips nothing.
  renderer.triangles.clear();
  glDisable(GL_CLIP_PLANE1);
  draw_triangle(triangle);
  EXPECT_FLOAT_EQ(extent(renderer.triangles).max_x, 64);
}

TEST_F(GlApi, ClipPlaneFollowsTheModelviewAtDefinition) {
  // Defined under a translation by +0.5 in x, the object-space plane
  // x <= 0 is eye x <= 0.5; changing the modelview afterwards moves the
  // geometry, not the plane.
  glMatrixMode(GL_MODELVIEW);
  glTranslatef(0.5f, 0, 0);
  const float plane[4] = {-1, 0, 0, 0};
  glClipPlanef(GL_CLIP_PLANE0, plane);
  glEnable(GL_CLIP_PLANE0);
  glLoadIdentity();
  const float triangle[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0};
  draw_triangle(triangle);
  ASSERT_FALSE(renderer.triangles.empty());
  EXPECT_FLOAT_EQ(extent(renderer.triangles).max_x, 48);
}

// ---- Polygon offset ---------------------------------------------------------

TEST_F(GlApi, PolygonOffsetAddsSlopeAndUnits) {
  // NDC z 0, 0.5, 0 at window (0, 0), (64, 0), (0, 48): window depth
  // (z + 1) / 2 = 0.5, 0.75, 0.5, so dz/dx = 0.25 / 64 and dz/dy = 0;
  // m = 0.00390625. The recording renderer keeps 12 depth bits: r = 1/4095.
  // o = 2 m + 3 r.
  const float triangle[] = {-1, -1, 0, 1, -1, 0.5f, -1, 1, 0};
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2, 3);
  draw_triangle(triangle);
  ASSERT_EQ(renderer.triangles.size(), 1u);
  const double offset = 2 * 0.00390625 + 3.0 / 4095;
  const gl::Triangle& t = renderer.triangles[0];
  EXPECT_NEAR(double(t.v[0].z), double(unorm24(0.5 + offset)), 1);
  EXPECT_NEAR(double(t.v[1].z), double(unorm24(0.75 + offset)), 1);
  EXPECT_NEAR(double(t.v[2].z), double(unorm24(0.5 + offset)), 1);

  // Negative factor and units pull it towards the viewer.
  renderer.triangles.clear();
  glPolygonOffset(-1, -1);
  draw_triangle(triangle);
  ASSERT_EQ(renderer.triangles.size(), 1u);
  EXPECT_NEAR(double(renderer.triangles[0].v[0].z), double(unorm24(0.5 - 0.00390625 - 1.0 / 4095)), 1);

  // Disabled: no offset.
  renderer.triangles.clear();
  glDisable(GL_POLYGON_OFFSET_FILL);
  draw_triangle(triangle);
  EXPECT_EQ(renderer.triangles[0].v[0].z, unorm24(0.5));
  GLfloat values[2] = {};
  glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &values[0]);
  glGetFloatv(GL_POLYGON_OFFSET_UNITS, &values[1]);
  EXPECT_EQ(values[0], -1);
  EXPECT_EQ(values[1], -1);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, PolygonOffsetIsClampedToTheDepthRange) {
  // Depth range [0.25, 0.75]: NDC z 0 is window depth 0.5; 2000 units of
  // 1/4095 (0.49) push it past 0.75, where it stops.
  glDepthRangef(0.25f, 0.75f);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(0, 2000);
  const float flat[] = {-1, -1, 0, 1, -1, 0, -1, 1, 0};
  draw_triangle(flat);
  ASSERT_EQ(renderer.triangles.size(), 1u);
  for (const gl::ScreenVertex& v : renderer.triangles[0].v) EXPECT_EQ(v.z, unorm24(0.75));
  renderer.triangles.clear();
  glPolygonOffset(0, -2000);
  draw_triangle(flat);
  for (const gl::ScreenVertex& v : renderer.triangles[0].v) EXPECT_EQ(v.z, unorm24(0.25));
}

TEST_F(GlApi, PolygonOffsetLeavesPointsAndLines) {
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(0, 1000);
  const float points[] = {0.1f, 0.1f, 0, -0.3f, 0.2f, 0};
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, points);
  glPointSize(3);
  glDrawArrays(GL_POINTS, 0, 2);
  glDrawArrays(GL_LINES, 0, 2);
  ASSERT_EQ(renderer.triangles.size(), 6u);
  for (const gl::Triangle& t : renderer.triangles)
    for (const gl::ScreenVertex& v : t.v) EXPECT_EQ(v.z, unorm24(0.5));
}

// ---- Points -----------------------------------------------------------------

TEST_F(GlApi, PointSizeArrayGivesEachPointItsSize) {
  const float points[] = {-0.5f, 0, 0, 0.5f, 0, 0};
  const float sizes[] = {2, 6};
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, points);
  glEnableClientState(GL_POINT_SIZE_ARRAY_OES);
  EXPECT_EQ(glIsEnabled(GL_POINT_SIZE_ARRAY_OES), GL_TRUE);
  glPointSizePointerOES(GL_FLOAT, 0, sizes);
  glDrawArrays(GL_POINTS, 0, 2);
  ASSERT_EQ(renderer.triangles.size(), 4u);
  Extent first = extent(renderer.triangles, 0, 2), second = extent(renderer.triangles, 2, 2);
  EXPECT_FLOAT_EQ(first.max_x - first.min_x, 2);
  EXPECT_FLOAT_EQ(second.max_x - second.min_x, 6);

  // GL_FIXED, with a stride: 5.0 and 3.0 in S15.16 with a word between.
  const GLfixed fixed_sizes[] = {5 << 16, 0, 3 << 16};
  glPointSizePointerOES(GL_FIXED, 8, fixed_sizes);
  renderer.triangles.clear();
  glDrawArrays(GL_POINTS, 0, 2);
  ASSERT_EQ(renderer.triangles.size(), 4u);
  first = extent(renderer.triangles, 0, 2), second = extent(renderer.triangles, 2, 2);
  EXPECT_FLOAT_EQ(first.max_y - first.min_y, 5);
  EXPECT_FLOAT_EQ(second.max_y - second.min_y, 3);

  GLint value = 0;
  glGetIntegerv(GL_POINT_SIZE_ARRAY_TYPE_OES, &value);
  EXPECT_EQ(value, GL_FIXED);
  glGetIntegerv(GL_POINT_SIZE_ARRAY_STRIDE_OES, &value);
  EXPECT_EQ(value, 8);
  void* pointer = nullptr;
  glGetPointerv(GL_POINT_SIZE_ARRAY_POINTER_OES, &pointer);
  EXPECT_EQ(pointer, static_cast<const void*>(fixed_sizes));

  // Disabled: glPointSize again.
  glDisableClientState(GL_POINT_SIZE_ARRAY_OES);
  glPointSize(4);
  renderer.triangles.clear();
  glDrawArrays(GL_POINTS, 0, 1);
  EXPECT_FLOAT_EQ(extent(renderer.triangles).max_x - extent(renderer.triangles).min_x, 4);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, PointSizePointerErrors) {
  const float sizes[] = {1};
  glPointSizePointerOES(GL_SHORT, 0, sizes);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glPointSizePointerOES(GL_FLOAT, -4, sizes);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  GLint type = 0;
  glGetIntegerv(GL_POINT_SIZE_ARRAY_TYPE_OES, &type);
  EXPECT_EQ(type, GL_FLOAT);  // the initial value, unchanged by the failed calls
}

TEST_F(GlApi, PointParametersAttenuateAndClamp) {
  // Eye distance d = 2 (a point at eye z = -2 on the axis; the projection
  // is an orthographic one that keeps z = -2 inside). With attenuation
  // (0, 0, 1): size * sqrt(1 / d^2) = size / 2.
  glMatrixMode(GL_PROJECTION);
  glOrthof(-1, 1, -1, 1, 1, 3);
  glMatrixMode(GL_MODELVIEW);
  const float point[] = {0, 0, -2};
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, point);
  const float attenuation[3] = {0, 0, 1};
  glPointParameterfv(GL_POINT_DISTANCE_ATTENUATION, attenuation);
  glPointSize(12);
  glDrawArrays(GL_POINTS, 0, 1);
  Extent e = extent(renderer.triangles);
  EXPECT_FLOAT_EQ(e.max_x - e.min_x, 6);
  // GL_POINT_SIZE_MAX 4 clamps the 6 to 4; GL_POINT_SIZE_MIN 10 raises it.
  glPointParameterf(GL_POINT_SIZE_MAX, 4);
  renderer.triangles.clear();
  glDrawArrays(GL_POINTS, 0, 1);
  e = extent(renderer.triangles);
  EXPECT_FLOAT_EQ(e.max_x - e.min_x, 4);
  glPointParameterf(GL_POINT_SIZE_MAX, 64);
  glPointParameterf(GL_POINT_SIZE_MIN, 10);
  renderer.triangles.clear();
  glDrawArrays(GL_POINTS, 0, 1);
  e = extent(renderer.triangles);
  EXPECT_FLOAT_EQ(e.max_x - e.min_x, 10);

  float values[3] = {};
  glGetFloatv(GL_POINT_DISTANCE_ATTENUATION, values);
  EXPECT_EQ(values[0], 0);
  EXPECT_EQ(values[1], 0);
  EXPECT_EQ(values[2], 1);
  glGetFloatv(GL_POINT_SIZE_MIN, values);
  EXPECT_EQ(values[0], 10);
  glGetFloatv(GL_POINT_FADE_THRESHOLD_SIZE, values);
  EXPECT_EQ(values[0], 1);  // ES 1.1's initial value
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, PointParameterErrors) {
  glPointParameterf(GL_POINT_DISTANCE_ATTENUATION, 1);  // needs three values
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glPointParameterf(GL_POINT_SIZE_MIN, -1);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glPointParameterf(GL_POINT_FADE_THRESHOLD_SIZE, -0.5f);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glPointParameterf(GL_POINT_SIZE, 1);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  float value = 0;
  glGetFloatv(GL_POINT_SIZE_MIN, &value);
  EXPECT_EQ(value, 0);  // unchanged
  glGetFloatv(GL_POINT_SIZE_MAX, &value);
  EXPECT_EQ(value, 64);
}

TEST_F(GlApi, PointSpriteCoordinatesRunAcrossThePoint) {
  // Texturing needs a defined texture for texture coordinates to be drawn.
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  const GLubyte texels[4] = {255, 255, 255, 255};
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
  glEnable(GL_TEXTURE_2D);
  glEnable(GL_POINT_SPRITE_OES);
  EXPECT_EQ(glIsEnabled(GL_POINT_SPRITE_OES), GL_TRUE);
  glTexEnvi(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, GL_TRUE);
  GLint replace = 0;
  glGetTexEnviv(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, &replace);
  EXPECT_EQ(replace, GL_TRUE);
  const float point[] = {0, 0, 0};
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, point);
  glPointSize(8);
  glDrawArrays(GL_POINTS, 0, 1);
  ASSERT_EQ(renderer.triangles.size(), 2u);
  // OES_point_sprite: s = 1/2 + (x - x_centre) / size, t = 1/2 - (y - y_centre) / size:
  // s = 0 on the left, 1 on the right; t = 0 at the top, 1 at the bottom.
  const Extent e = extent(renderer.triangles);
  for (const gl::Triangle& t : renderer.triangles)
    for (const gl::ScreenVertex& v : t.v) {
      EXPECT_FLOAT_EQ(v.tex[0].s, v.x / 16.0f == e.min_x ? 0.0f : 1.0f);
      EXPECT_FLOAT_EQ(v.tex[0].t, v.y / 16.0f == e.max_y ? 0.0f : 1.0f);
    }
  // Without GL_COORD_REPLACE_OES the point keeps its vertex's coordinates.
  glTexEnvi(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, GL_FALSE);
  glMultiTexCoord4f(GL_TEXTURE0, 0.25f, 0.75f, 0, 1);
  renderer.triangles.clear();
  glDrawArrays(GL_POINTS, 0, 1);
  for (const gl::Triangle& t : renderer.triangles)
    for (const gl::ScreenVertex& v : t.v)
      EXPECT_EQ(std::vector<float>({v.tex[0].s, v.tex[0].t}), std::vector<float>({0.25f, 0.75f}));
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

// GL_COORD_REPLACE_OES is per texture unit: with it on unit 1 only, unit 1
// gets the sprite's coordinates and unit 0 keeps its current coordinates.
TEST_F(GlApi, PointSpriteReplacesCoordinatesOnlyInTheUnitsThatAskForIt) {
  const GLubyte texels[4] = {255, 255, 255, 255};
  GLuint textures[2] = {0, 0};
  glGenTextures(2, textures);
  for (unsigned u = 0; u < 2; ++u) {
    glActiveTexture(GL_TEXTURE0 + u);
    glBindTexture(GL_TEXTURE_2D, textures[u]);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    glEnable(GL_TEXTURE_2D);
  }
  glEnable(GL_POINT_SPRITE_OES);
  glActiveTexture(GL_TEXTURE1);
  glTexEnvi(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, GL_TRUE);
  glMultiTexCoord4f(GL_TEXTURE0, 0.25f, 0.75f, 0, 1);
  const float point[] = {0, 0, 0};
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, point);
  glPointSize(8);
  glDrawArrays(GL_POINTS, 0, 1);
  ASSERT_EQ(renderer.triangles.size(), 2u);
  const Extent e = extent(renderer.triangles);
  for (const gl::Triangle& t : renderer.triangles)
    for (const gl::ScreenVertex& v : t.v) {
      EXPECT_FLOAT_EQ(v.tex[0].s, 0.25f);
      EXPECT_FLOAT_EQ(v.tex[0].t, 0.75f);
      EXPECT_FLOAT_EQ(v.tex[1].s, v.x / 16.0f == e.min_x ? 0.0f : 1.0f);
      EXPECT_FLOAT_EQ(v.tex[1].t, v.y / 16.0f == e.max_y ? 0.0f : 1.0f);
    }
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, PointSpriteEnvironmentErrors) {
  glTexEnvi(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, 2);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexEnvi(GL_POINT_SPRITE_OES, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  float value = 5;
  glGetTexEnvfv(GL_POINT_SPRITE_OES, GL_TEXTURE_ENV_MODE, &value);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  // The fixed-point form carries the boolean unscaled.
  glTexEnvx(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, GL_TRUE);
  glGetTexEnvfv(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, &value);
  EXPECT_EQ(value, 1);
  // Per texture unit: unit 1 has its own.
  glActiveTexture(GL_TEXTURE1);
  glGetTexEnvfv(GL_POINT_SPRITE_OES, GL_COORD_REPLACE_OES, &value);
  EXPECT_EQ(value, 0);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

// ---- Two-sided lighting -----------------------------------------------------

TEST_F(GlApi, TwoSidedLightingLightsBackFacesWithTheReversedNormal) {
  // Light 0: directional from +z, white diffuse; default material (ambient
  // 0.2, diffuse 0.8, no specular), light-model ambient 0.2; normal +z.
  // Front colour: 0.2 * 0.2 + 0.8 * 1 = 0.84 -> 214. With the normal
  // reversed n.l = -1 < 0: ambient only, 0.04 -> 10.
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  const float clockwise[] = {-1, -1, 0, -1, 1, 0, 1, -1, 0};  // a back face
  const float counter_clockwise[] = {-1, -1, 0, 1, -1, 0, -1, 1, 0};
  draw_triangle(clockwise);
  ASSERT_EQ(renderer.triangles.size(), 1u);
  EXPECT_EQ(renderer.triangles[0].v[0].r, 214);  // one-sided: the front colour on both faces
  glLightModelf(GL_LIGHT_MODEL_TWO_SIDE, 1);
  renderer.triangles.clear();
  draw_triangle(clockwise);
  ASSERT_EQ(renderer.triangles.size(), 1u);
  for (const gl::ScreenVertex& v : renderer.triangles[0].v)
    EXPECT_EQ(std::vector<int>({v.r, v.g, v.b}), std::vector<int>({10, 10, 10}));
  renderer.triangles.clear();
  draw_triangle(counter_clockwise);
  for (const gl::ScreenVertex& v : renderer.triangles[0].v) EXPECT_EQ(v.r, 214);
  // GL_CW makes the first triangle the front face.
  glFrontFace(GL_CW);
  renderer.triangles.clear();
  draw_triangle(clockwise);
  EXPECT_EQ(renderer.triangles[0].v[0].r, 214);
  // Flat shading takes the provoking vertex's back colour.
  glFrontFace(GL_CCW);
  glShadeModel(GL_FLAT);
  renderer.triangles.clear();
  draw_triangle(clockwise);
  EXPECT_EQ(renderer.triangles[0].v[1].r, 10);
  // Points and lines are never back faces.
  renderer.triangles.clear();
  glVertexPointer(3, GL_FLOAT, 0, clockwise);
  glDrawArrays(GL_POINTS, 0, 3);
  for (const gl::Triangle& t : renderer.triangles)
    for (const gl::ScreenVertex& v : t.v) EXPECT_EQ(v.r, 214);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, ExtensionsListPointSpritesAndSizeArrays) {
  const std::string extensions = reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS));
  EXPECT_NE(extensions.find("GL_OES_point_sprite"), std::string::npos);
  EXPECT_NE(extensions.find("GL_OES_point_size_array"), std::string::npos);
}

// ---- A viewport partly off the screen ----------------------------------------

TEST_F(GlApi, ViewportPartlyOffTheScreenIsCutAtTheScreen) {
  // glViewport(-32, -24, 64, 48): NDC -1..1 maps to window x -32..32 and
  // y -24..24. A quad over the whole view volume keeps its on-screen
  // quarter, x 0..32 and y 0..24 (it was dropped whole before).
  glViewport(-32, -24, 64, 48);
  const float lower[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0};
  const float upper[] = {-1, -1, 0, 1, 1, 0, -1, 1, 0};
  draw_triangle(lower);
  draw_triangle(upper);
  ASSERT_FALSE(renderer.triangles.empty());
  Extent e = extent(renderer.triangles);
  EXPECT_FLOAT_EQ(e.min_x, 0);
  EXPECT_FLOAT_EQ(e.max_x, 32);
  EXPECT_FLOAT_EQ(e.min_y, 0);
  EXPECT_FLOAT_EQ(e.max_y, 24);

  // A triangle whose NDC corners (-0.5, -0.5), (0.5, -0.5), (0.5, 0.5) are
  // at window (-16, -12), (16, -12), (16, 12): cut at x = 0 and y = 0, it
  // keeps the part right of x = 0 and above y = 0 under its hypotenuse
  // y = 0.75 x (window): x 0..16, y 0..12.
  renderer.triangles.clear();
  const float small[] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0};
  draw_triangle(small);
  ASSERT_FALSE(renderer.triangles.empty());
  e = extent(renderer.triangles);
  EXPECT_FLOAT_EQ(e.min_x, 0);
  EXPECT_FLOAT_EQ(e.max_x, 16);
  EXPECT_FLOAT_EQ(e.min_y, 0);
  EXPECT_FLOAT_EQ(e.max_y, 12);

  // Past the far edges of the 9.4 range (512 pixels): glViewport(480, 500,
  // 64, 48) reaches x 544 and y 548; the quad is cut at 512, whose code is
  // the last one, 511 15/16 (geometry.cpp, screen_coordinate).
  renderer.triangles.clear();
  glViewport(480, 500, 64, 48);
  draw_triangle(lower);
  draw_triangle(upper);
  ASSERT_FALSE(renderer.triangles.empty());
  e = extent(renderer.triangles);
  EXPECT_FLOAT_EQ(e.min_x, 480);
  EXPECT_FLOAT_EQ(e.max_x, 511.9375f);
  EXPECT_FLOAT_EQ(e.min_y, 500);
  EXPECT_FLOAT_EQ(e.max_y, 511.9375f);

  // Wholly off the screen: nothing.
  renderer.triangles.clear();
  glViewport(-100, 0, 64, 48);
  draw_triangle(lower);
  EXPECT_TRUE(renderer.triangles.empty());
  EXPECT_EQ(error(), GLenum(GL_NO_ERROR));
}
