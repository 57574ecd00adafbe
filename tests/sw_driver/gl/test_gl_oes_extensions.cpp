// Unit tests of the four extensions ES 1.1 requires that add names to the
// core (gl/gl_oes.cpp, glGetIntegerv in gl/gl_api.cpp): OES_fixed_point
// and OES_single_precision (the OES-suffixed commands set what the core
// commands set, with the same errors), OES_matrix_get (the IEEE 754 bits of
// each matrix through glGetIntegerv) and OES_byte_coordinates (GL_BYTE
// positions and texture coordinates of every size, taken as they are).
// Expected values come from the specifications: the matrices of ES 1.1
// section 2.10.2, the single-precision format's bit layout.
#include <GLES/gl.h>
#include <GLES/glext.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <set>
#include <sstream>
#include <string>

#include "gl_test_fixture.h"

using tessera::test::GlApi;

namespace {

constexpr GLfixed ONE = 1 << 16;

GLenum error() {
  return glGetError();
}

std::array<GLfloat, 16> floats(GLenum name) {
  std::array<GLfloat, 16> m{};
  glGetFloatv(name, m.data());
  return m;
}

std::array<GLint, 16> integers(GLenum name) {
  std::array<GLint, 16> m{};
  glGetIntegerv(name, m.data());
  return m;
}

// The 32 bits of an IEEE 754 single as a GLint.
GLint bits_of(float value) {
  GLint bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

}  // namespace

TEST_F(GlApi, OesExtensionsRequiredByEs11AreListed) {
  const GLubyte* text = glGetString(GL_EXTENSIONS);
  ASSERT_NE(text, nullptr);
  std::istringstream words(reinterpret_cast<const char*>(text));
  std::set<std::string> listed;
  for (std::string word; words >> word;) listed.insert(word);
  for (const char* name :
       {"GL_OES_byte_coordinates", "GL_OES_fixed_point", "GL_OES_single_precision", "GL_OES_matrix_get",
        "GL_OES_read_format", "GL_OES_compressed_paletted_texture", "GL_OES_point_size_array", "GL_OES_point_sprite"})
    EXPECT_EQ(listed.count(name), 1u) << name;
  // The macros <GLES/glext.h> defines for them (GlApi.ExtensionStringMatchesTheHeaders checks all).
  EXPECT_EQ(GL_OES_byte_coordinates + GL_OES_fixed_point + GL_OES_single_precision + GL_OES_matrix_get, 4);
  EXPECT_EQ(GL_FIXED_OES, GL_FIXED);
}

// The OES_fixed_point matrix commands build the matrices of ES 1.1 2.10.2,
// as the core x commands do.
TEST_F(GlApi, OesFixedPointMatricesAreTheSpecificationsMatrices) {
  glMatrixMode(GL_MODELVIEW);
  glTranslatexOES(ONE, 2 * ONE, -3 * ONE);
  auto m = floats(GL_MODELVIEW_MATRIX);
  EXPECT_EQ(m[12], 1.0f);
  EXPECT_EQ(m[13], 2.0f);
  EXPECT_EQ(m[14], -3.0f);
  EXPECT_EQ(m[0], 1.0f);
  glLoadIdentity();
  glScalexOES(ONE / 2, 2 * ONE, 3 * ONE);
  m = floats(GL_MODELVIEW_MATRIX);
  EXPECT_EQ(m[0], 0.5f);
  EXPECT_EQ(m[5], 2.0f);
  EXPECT_EQ(m[10], 3.0f);
  glLoadIdentity();
  // 90 degrees about z: x goes to y, y to -x.
  glRotatexOES(90 * ONE, 0, 0, ONE);
  m = floats(GL_MODELVIEW_MATRIX);
  EXPECT_NEAR(m[0], 0.0f, 1e-6f);
  EXPECT_NEAR(m[1], 1.0f, 1e-6f);
  EXPECT_NEAR(m[4], -1.0f, 1e-6f);
  EXPECT_NEAR(m[5], 0.0f, 1e-6f);

  // Column-major: a translation by (4, 5, 6), then one by (1, 0, 0).
  GLfixed t[16] = {ONE, 0, 0, 0, 0, ONE, 0, 0, 0, 0, ONE, 0, 4 * ONE, 5 * ONE, 6 * ONE, ONE};
  glLoadMatrixxOES(t);
  t[12] = ONE, t[13] = 0, t[14] = 0;
  glMultMatrixxOES(t);
  GLfixed back[16] = {};
  glGetFixedvOES(GL_MODELVIEW_MATRIX, back);
  EXPECT_EQ(back[12], 5 * ONE);
  EXPECT_EQ(back[13], 5 * ONE);
  EXPECT_EQ(back[14], 6 * ONE);
  EXPECT_EQ(back[15], ONE);

  // Frustum (l, r, b, t, n, f) = (-1, 1, -0.5, 0.5, 1, 3): 2n / (r - l) = 1,
  // 2n / (t - b) = 2, -(f + n) / (f - n) = -2, -2fn / (f - n) = -3.
  glMatrixMode(GL_PROJECTION);
  glFrustumxOES(-ONE, ONE, -ONE / 2, ONE / 2, ONE, 3 * ONE);
  m = floats(GL_PROJECTION_MATRIX);
  EXPECT_FLOAT_EQ(m[0], 1.0f);
  EXPECT_FLOAT_EQ(m[5], 2.0f);
  EXPECT_FLOAT_EQ(m[10], -2.0f);
  EXPECT_FLOAT_EQ(m[11], -1.0f);
  EXPECT_FLOAT_EQ(m[14], -3.0f);
  EXPECT_FLOAT_EQ(m[15], 0.0f);
  glLoadIdentity();
  // Ortho (0, 4, 0, 2, -1, 1): 2 / 4, 2 / 2, -2 / 2; translation (-1, -1, 0).
  glOrthoxOES(0, 4 * ONE, 0, 2 * ONE, -ONE, ONE);
  m = floats(GL_PROJECTION_MATRIX);
  EXPECT_FLOAT_EQ(m[0], 0.5f);
  EXPECT_FLOAT_EQ(m[5], 1.0f);
  EXPECT_FLOAT_EQ(m[10], -1.0f);
  EXPECT_FLOAT_EQ(m[12], -1.0f);
  EXPECT_FLOAT_EQ(m[13], -1.0f);
  EXPECT_FLOAT_EQ(m[14], 0.0f);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

// Each remaining OES_fixed_point command sets the state its core twin sets,
// read back through the OES queries.
TEST_F(GlApi, OesFixedPointStateCommandsSetAndReadBack) {
  glColor4xOES(ONE / 2, ONE / 4, 0, ONE);
  GLfixed v[4] = {};
  glGetFixedvOES(GL_CURRENT_COLOR, v);
  EXPECT_EQ(v[0], ONE / 2);
  EXPECT_EQ(v[1], ONE / 4);
  EXPECT_EQ(v[3], ONE);
  glNormal3xOES(0, ONE, 0);
  glGetFixedvOES(GL_CURRENT_NORMAL, v);
  EXPECT_EQ(v[1], ONE);
  glMultiTexCoord4xOES(GL_TEXTURE1, ONE, 2 * ONE, 0, ONE);
  glActiveTexture(GL_TEXTURE1);
  glGetFixedvOES(GL_CURRENT_TEXTURE_COORDS, v);
  EXPECT_EQ(v[0], ONE);
  EXPECT_EQ(v[1], 2 * ONE);
  glActiveTexture(GL_TEXTURE0);

  glClearColorxOES(ONE / 4, ONE / 2, ONE, 0);
  glGetFixedvOES(GL_COLOR_CLEAR_VALUE, v);
  EXPECT_EQ(v[0], ONE / 4);
  EXPECT_EQ(v[2], ONE);
  glClearDepthxOES(ONE / 2);
  glGetFixedvOES(GL_DEPTH_CLEAR_VALUE, v);
  EXPECT_EQ(v[0], ONE / 2);
  glDepthRangexOES(ONE / 4, 3 * ONE / 4);
  glGetFixedvOES(GL_DEPTH_RANGE, v);
  EXPECT_EQ(v[0], ONE / 4);
  EXPECT_EQ(v[1], 3 * ONE / 4);
  glAlphaFuncxOES(GL_GREATER, ONE / 2);
  glGetFixedvOES(GL_ALPHA_TEST_REF, v);
  EXPECT_EQ(v[0], ONE / 2);
  glLineWidthxOES(3 * ONE);
  glGetFixedvOES(GL_LINE_WIDTH, v);
  EXPECT_EQ(v[0], 3 * ONE);
  glPointSizexOES(5 * ONE);
  glGetFixedvOES(GL_POINT_SIZE, v);
  EXPECT_EQ(v[0], 5 * ONE);
  glPointParameterxOES(GL_POINT_SIZE_MIN, 2 * ONE);
  const GLfixed attenuation[3] = {ONE, ONE / 2, ONE / 4};
  glPointParameterxvOES(GL_POINT_DISTANCE_ATTENUATION, attenuation);
  glGetFixedvOES(GL_POINT_SIZE_MIN, v);
  EXPECT_EQ(v[0], 2 * ONE);
  glGetFixedvOES(GL_POINT_DISTANCE_ATTENUATION, v);
  EXPECT_EQ(v[2], ONE / 4);
  glPolygonOffsetxOES(-ONE, -2 * ONE);
  glGetFixedvOES(GL_POLYGON_OFFSET_UNITS, v);
  EXPECT_EQ(v[0], -2 * ONE);
  glSampleCoveragexOES(ONE / 2, GL_TRUE);
  glGetFixedvOES(GL_SAMPLE_COVERAGE_VALUE, v);
  EXPECT_EQ(v[0], ONE / 2);

  const GLfixed diffuse[4] = {ONE, ONE / 2, 0, ONE};
  glLightxvOES(GL_LIGHT1, GL_DIFFUSE, diffuse);
  glLightxOES(GL_LIGHT1, GL_SPOT_CUTOFF, 45 * ONE);
  glGetLightxvOES(GL_LIGHT1, GL_DIFFUSE, v);
  EXPECT_EQ(v[1], ONE / 2);
  glGetLightxvOES(GL_LIGHT1, GL_SPOT_CUTOFF, v);
  EXPECT_EQ(v[0], 45 * ONE);
  glLightModelxOES(GL_LIGHT_MODEL_TWO_SIDE, 1);
  const GLfixed ambient[4] = {ONE / 8, ONE / 8, ONE / 8, ONE};
  glLightModelxvOES(GL_LIGHT_MODEL_AMBIENT, ambient);
  glGetFixedvOES(GL_LIGHT_MODEL_AMBIENT, v);
  EXPECT_EQ(v[0], ONE / 8);
  EXPECT_EQ(glIsEnabled(GL_LIGHTING), GL_FALSE);
  GLboolean two_side = GL_FALSE;
  glGetBooleanv(GL_LIGHT_MODEL_TWO_SIDE, &two_side);
  EXPECT_EQ(two_side, GL_TRUE);
  glMaterialxvOES(GL_FRONT_AND_BACK, GL_SPECULAR, diffuse);
  glMaterialxOES(GL_FRONT_AND_BACK, GL_SHININESS, 20 * ONE);
  glGetMaterialxvOES(GL_FRONT, GL_SPECULAR, v);
  EXPECT_EQ(v[0], ONE);
  glGetMaterialxvOES(GL_BACK, GL_SHININESS, v);
  EXPECT_EQ(v[0], 20 * ONE);

  glFogxOES(GL_FOG_MODE, GL_LINEAR);  // an enum, not scaled
  glFogxOES(GL_FOG_END, 30 * ONE);
  const GLfixed fog_colour[4] = {ONE / 2, ONE / 2, ONE, ONE};
  glFogxvOES(GL_FOG_COLOR, fog_colour);
  GLint mode = 0;
  glGetIntegerv(GL_FOG_MODE, &mode);
  EXPECT_EQ(mode, GL_LINEAR);
  glGetFixedvOES(GL_FOG_END, v);
  EXPECT_EQ(v[0], 30 * ONE);
  glGetFixedvOES(GL_FOG_COLOR, v);
  EXPECT_EQ(v[2], ONE);

  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameterxOES(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  const GLfixed wrap = GL_CLAMP_TO_EDGE;
  glTexParameterxvOES(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &wrap);
  glGetTexParameterxvOES(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, v);
  EXPECT_EQ(v[0], GL_NEAREST);
  glGetTexParameterxvOES(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, v);
  EXPECT_EQ(v[0], GL_CLAMP_TO_EDGE);
  glTexEnvxOES(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_DECAL);
  const GLfixed env_colour[4] = {0, ONE / 2, ONE, ONE};
  glTexEnvxvOES(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, env_colour);
  glGetTexEnvxvOES(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, v);
  EXPECT_EQ(v[0], GL_DECAL);
  glGetTexEnvxvOES(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, v);
  EXPECT_EQ(v[1], ONE / 2);

  // Under the identity modelview the plane is stored as given.
  const GLfixed plane[4] = {ONE, 0, -ONE, ONE / 2};
  glClipPlanexOES(GL_CLIP_PLANE2, plane);
  glGetClipPlanexOES(GL_CLIP_PLANE2, v);
  EXPECT_EQ(v[0], ONE);
  EXPECT_EQ(v[2], -ONE);
  EXPECT_EQ(v[3], ONE / 2);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

// The errors are the core commands' (ES 1.1 2.10.2, 2.11, 3.4, 6.1).
TEST_F(GlApi, OesFixedPointCommandsReportTheSpecifiedErrors) {
  glFrustumxOES(-ONE, ONE, -ONE, ONE, 0, 10 * ONE);  // n <= 0
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glOrthoxOES(ONE, ONE, -ONE, ONE, -ONE, ONE);  // l == r
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glLineWidthxOES(0);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glPointSizexOES(-ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glLightxOES(GL_LIGHT0, GL_SPOT_CUTOFF, 100 * ONE);  // neither in [0, 90] nor 180
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  const GLfixed plane[4] = {ONE, 0, 0, 0};
  glClipPlanexOES(GL_CLIP_PLANE0 + 6, plane);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glTexEnvxOES(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_NEAREST);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  GLfixed untouched[4] = {7, 7, 7, 7};
  glGetFixedvOES(GL_TEXTURE_ENV_MODE, untouched);  // not a glGet name
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(untouched[0], 7);
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixxOES(nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
}

// OES_single_precision: the float commands under OES names, with the core
// commands' values and errors.
TEST_F(GlApi, OesSinglePrecisionCommandsAreTheCoreCommands) {
  glMatrixMode(GL_PROJECTION);
  glFrustumfOES(-1, 1, -0.5f, 0.5f, 1, 3);
  auto m = floats(GL_PROJECTION_MATRIX);
  EXPECT_FLOAT_EQ(m[0], 1.0f);
  EXPECT_FLOAT_EQ(m[5], 2.0f);
  EXPECT_FLOAT_EQ(m[10], -2.0f);
  EXPECT_FLOAT_EQ(m[14], -3.0f);
  const auto with_oes = m;
  glLoadIdentity();
  glFrustumf(-1, 1, -0.5f, 0.5f, 1, 3);
  EXPECT_EQ(floats(GL_PROJECTION_MATRIX), with_oes);
  glLoadIdentity();
  glOrthofOES(0, 4, 0, 2, -1, 1);
  m = floats(GL_PROJECTION_MATRIX);
  EXPECT_FLOAT_EQ(m[0], 0.5f);
  EXPECT_FLOAT_EQ(m[12], -1.0f);
  EXPECT_FLOAT_EQ(m[13], -1.0f);

  glDepthRangefOES(0.25f, 0.75f);
  GLfloat range[2] = {};
  glGetFloatv(GL_DEPTH_RANGE, range);
  EXPECT_EQ(range[0], 0.25f);
  EXPECT_EQ(range[1], 0.75f);
  glDepthRangefOES(-1.0f, 2.0f);  // clamped to [0, 1]
  glGetFloatv(GL_DEPTH_RANGE, range);
  EXPECT_EQ(range[0], 0.0f);
  EXPECT_EQ(range[1], 1.0f);
  glClearDepthfOES(0.5f);
  GLfloat depth = 0;
  glGetFloatv(GL_DEPTH_CLEAR_VALUE, &depth);
  EXPECT_EQ(depth, 0.5f);

  // A clip plane is taken into eye space by the inverse of the modelview
  // (ES 1.1 2.11): after a translation by (0, 0, -2) the plane z = 0 of
  // object space, (0, 0, 1, 0), is z = -2 in eye space, (0, 0, 1, 2).
  glMatrixMode(GL_MODELVIEW);
  glTranslatef(0, 0, -2);
  const GLfloat plane[4] = {0, 0, 1, 0};
  glClipPlanefOES(GL_CLIP_PLANE1, plane);
  GLfloat eye[4] = {};
  glGetClipPlanefOES(GL_CLIP_PLANE1, eye);
  EXPECT_FLOAT_EQ(eye[2], 1.0f);
  EXPECT_FLOAT_EQ(eye[3], 2.0f);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));

  glFrustumfOES(-1, 1, -1, 1, 2, 2);  // n == f
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glOrthofOES(0, 1, 1, 1, 0, 1);  // b == t
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glClipPlanefOES(GL_CLIP_PLANE0 + 6, plane);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  GLfloat untouched[4] = {7, 7, 7, 7};
  glGetClipPlanefOES(GL_LIGHT0, untouched);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(untouched[0], 7.0f);
}

// OES_matrix_get: glGetIntegerv gives each element's IEEE 754 single bits,
// column by column, of the top of the stack named.
TEST_F(GlApi, OesMatrixGetGivesTheFloatBitsOfEachMatrix) {
  const GLfloat modelview[16] = {0.1f, -2.5f, 1e-3f, 0, 3, 1, -0.0f, 0, 0, 0, 1, 0, 1e6f, -7.25f, 0.3f, 1};
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixf(modelview);
  const auto bits = integers(GL_MODELVIEW_MATRIX_FLOAT_AS_INT_BITS_OES);
  for (size_t i = 0; i < 16; ++i) EXPECT_EQ(bits[i], bits_of(modelview[i])) << "element " << i;
  // By the single format's layout (bit 31 sign, 30-23 exponent biased by
  // 127, 22-0 fraction): 1.0 is 0x3F800000, 3.0 0x40400000, -0.0 0x80000000,
  // -7.25 = -1.8125 * 2^2 is 0xC0E80000.
  EXPECT_EQ(static_cast<uint32_t>(bits[15]), 0x3F800000u);
  EXPECT_EQ(static_cast<uint32_t>(bits[4]), 0x40400000u);
  EXPECT_EQ(static_cast<uint32_t>(bits[6]), 0x80000000u);
  EXPECT_EQ(static_cast<uint32_t>(bits[13]), 0xC0E80000u);

  // The projection of glFrustumf(-1, 1, -0.5, 0.5, 1, 3): 1, 2, -2, -1, -3.
  glMatrixMode(GL_PROJECTION);
  glFrustumf(-1, 1, -0.5f, 0.5f, 1, 3);
  const auto projection = integers(GL_PROJECTION_MATRIX_FLOAT_AS_INT_BITS_OES);
  EXPECT_EQ(static_cast<uint32_t>(projection[0]), 0x3F800000u);
  EXPECT_EQ(static_cast<uint32_t>(projection[5]), 0x40000000u);
  EXPECT_EQ(static_cast<uint32_t>(projection[10]), 0xC0000000u);
  EXPECT_EQ(static_cast<uint32_t>(projection[11]), 0xBF800000u);
  EXPECT_EQ(static_cast<uint32_t>(projection[14]), 0xC0400000u);
  EXPECT_EQ(projection[15], 0);
  // A pushed matrix: the top of the stack is what is read.
  glPushMatrix();
  glLoadIdentity();
  EXPECT_EQ(static_cast<uint32_t>(integers(GL_PROJECTION_MATRIX_FLOAT_AS_INT_BITS_OES)[10]), 0x3F800000u);
  glPopMatrix();

  // The texture matrix of the active unit (not the client-active one).
  glMatrixMode(GL_TEXTURE);
  glActiveTexture(GL_TEXTURE1);
  glScalef(0.5f, 4, 1);
  glActiveTexture(GL_TEXTURE0);
  glClientActiveTexture(GL_TEXTURE1);
  EXPECT_EQ(static_cast<uint32_t>(integers(GL_TEXTURE_MATRIX_FLOAT_AS_INT_BITS_OES)[0]), 0x3F800000u);
  glActiveTexture(GL_TEXTURE1);
  const auto texture = integers(GL_TEXTURE_MATRIX_FLOAT_AS_INT_BITS_OES);
  EXPECT_EQ(static_cast<uint32_t>(texture[0]), 0x3F000000u);  // 0.5
  EXPECT_EQ(static_cast<uint32_t>(texture[5]), 0x40800000u);  // 4.0
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));

  // The tokens are accepted by glGetIntegerv only.
  GLfloat f[16] = {7};
  glGetFloatv(GL_MODELVIEW_MATRIX_FLOAT_AS_INT_BITS_OES, f);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(f[0], 7.0f);
  GLboolean b[16] = {GL_FALSE};
  glGetBooleanv(GL_PROJECTION_MATRIX_FLOAT_AS_INT_BITS_OES, b);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  GLfixed x[16] = {7};
  glGetFixedv(GL_TEXTURE_MATRIX_FLOAT_AS_INT_BITS_OES, x);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(x[0], 7);
}

// OES_byte_coordinates: GL_BYTE positions of 2, 3 and 4 components and
// texture coordinates of 2, 3 and 4, their values taken as they are (not
// normalised like a byte colour), the whole range -128 to 127.
TEST_F(GlApi, OesByteCoordinatesOfEverySize) {
  // x in [-128, 128] and y in [-96, 96] onto the 64 x 48 window: window x =
  // (x / w + 128) / 4, window y = (y / w + 96) / 4, in 9.4 sixteenths.
  glMatrixMode(GL_PROJECTION);
  glOrthof(-128, 128, -96, 96, -1, 1);
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  const uint8_t texel[4] = {255, 255, 255, 255};
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glEnable(GL_TEXTURE_2D);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  // Positions (x, y, z, w) and coordinates (s, t, r, q); fewer components
  // take z = 0, w = 1, r = 0, q = 1.
  const int8_t xyzw[12] = {-128, -96, 0, 1, 127, -96, 1, 1, 100, 96, -1, 2};
  const int8_t strq[12] = {-128, 127, 5, 1, 3, -4, 0, 1, 8, 6, 0, 2};
  struct Expected {
    int32_t x, y;
    float s, t;
  };
  for (int size = 2; size <= 4; ++size) {
    SCOPED_TRACE(size);
    renderer.triangles.clear();
    glVertexPointer(size, GL_BYTE, 4, xyzw);  // a stride of 4 bytes: one vertex per row of four
    glTexCoordPointer(size, GL_BYTE, 4, strq);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    ASSERT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
    ASSERT_EQ(renderer.triangles.size(), 1u);
    const float w2 = size == 4 ? 2.0f : 1.0f;  // the third vertex's w and q
    const Expected expected[3] = {
        {4 * (-128 + 128), 4 * (-96 + 96), -128, 127},
        {4 * (127 + 128), 4 * (-96 + 96), 3, -4},
        {static_cast<int32_t>(4 * (100 / w2 + 128)), static_cast<int32_t>(4 * (96 / w2 + 96)), 8 / w2, 6 / w2}};
    const tessera::gl::Triangle& t = renderer.triangles[0];
    for (int v = 0; v < 3; ++v) {
      EXPECT_EQ(t.v[v].x, expected[v].x) << "vertex " << v;
      EXPECT_EQ(t.v[v].y, expected[v].y) << "vertex " << v;
      EXPECT_FLOAT_EQ(t.v[v].tex[0].s, expected[v].s) << "vertex " << v;
      EXPECT_FLOAT_EQ(t.v[v].tex[0].t, expected[v].t) << "vertex " << v;
    }
  }
  // Sizes outside 2 to 4 are GL_INVALID_VALUE, as for every type.
  glVertexPointer(1, GL_BYTE, 0, xyzw);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexCoordPointer(5, GL_BYTE, 0, strq);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  // GL_UNSIGNED_BYTE is no coordinate type (only colours take it).
  glVertexPointer(2, GL_UNSIGNED_BYTE, 0, xyzw);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
}
