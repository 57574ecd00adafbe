// Unit tests of the fixed-point entry points of the ES 1.1 common profile
// (gl/gl_fixed.cpp): each sets what its float twin sets, enum-valued
// parameters are not scaled, queries convert back rounding and saturating,
// the errors are the float commands', a failed query writes nothing, a
// null pointer is an error and not a crash, and the conversions are
// charged to the host.
#include <GLES/gl.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <string>

#include "gl_test_fixture.h"
#include "host/cost_units.h"

using tessera::test::GlApi;

namespace {

constexpr GLfixed ONE = 1 << 16;

constexpr GLfixed fixed(double value) {
  return static_cast<GLfixed>(value * 65536.0);
}

GLenum error() {
  return glGetError();
}

// The current matrix of `mode`, as floats.
std::array<GLfloat, 16> matrix(GLenum mode) {
  std::array<GLfloat, 16> m{};
  glGetFloatv(mode, m.data());
  return m;
}

void expect_same_matrix(const std::array<GLfloat, 16>& a, const std::array<GLfloat, 16>& b) {
  for (size_t i = 0; i < 16; ++i) EXPECT_NEAR(a[i], b[i], 1e-5f) << "element " << i;
}

}  // namespace

TEST_F(GlApi, FixedMatricesEqualTheirFloatTwins) {
  glMatrixMode(GL_MODELVIEW);
  glTranslatex(ONE, 2 * ONE, -3 * ONE);
  glRotatex(90 * ONE, 0, 0, ONE);
  glScalex(ONE / 2, 2 * ONE, ONE);
  const auto with_fixed = matrix(GL_MODELVIEW_MATRIX);
  glLoadIdentity();
  glTranslatef(1, 2, -3);
  glRotatef(90, 0, 0, 1);
  glScalef(0.5f, 2, 1);
  expect_same_matrix(with_fixed, matrix(GL_MODELVIEW_MATRIX));

  glMatrixMode(GL_PROJECTION);
  glFrustumx(-ONE, ONE, fixed(-0.75), fixed(0.75), ONE, 10 * ONE);
  const auto frustum = matrix(GL_PROJECTION_MATRIX);
  glLoadIdentity();
  glFrustumf(-1, 1, -0.75f, 0.75f, 1, 10);
  expect_same_matrix(frustum, matrix(GL_PROJECTION_MATRIX));
  glLoadIdentity();
  glOrthox(0, 320 * ONE, 0, 240 * ONE, -ONE, ONE);
  const auto ortho = matrix(GL_PROJECTION_MATRIX);
  glLoadIdentity();
  glOrthof(0, 320, 0, 240, -1, 1);
  expect_same_matrix(ortho, matrix(GL_PROJECTION_MATRIX));

  // Column-major like glLoadMatrixf; a translation by (4, 5, 6), then by 1 in x.
  GLfixed m[16] = {ONE, 0, 0, 0, 0, ONE, 0, 0, 0, 0, ONE, 0, 4 * ONE, 5 * ONE, 6 * ONE, ONE};
  glLoadMatrixx(m);
  m[12] = ONE, m[13] = 0, m[14] = 0;
  glMultMatrixx(m);
  GLfixed back[16];
  glGetFixedv(GL_PROJECTION_MATRIX, back);
  EXPECT_EQ(back[12], 5 * ONE);
  EXPECT_EQ(back[13], 5 * ONE);
  EXPECT_EQ(back[14], 6 * ONE);
  EXPECT_EQ(back[15], ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, FixedAttributesAndFramebufferStateReadBack) {
  glColor4x(ONE, ONE / 2, ONE / 4, ONE);
  GLfloat color[4];
  glGetFloatv(GL_CURRENT_COLOR, color);
  EXPECT_FLOAT_EQ(color[1], 0.5f);
  EXPECT_FLOAT_EQ(color[2], 0.25f);
  GLfixed values[4];
  glGetFixedv(GL_CURRENT_COLOR, values);
  EXPECT_EQ(values[0], ONE);
  EXPECT_EQ(values[1], ONE / 2);
  glNormal3x(0, -ONE, ONE / 2);
  glGetFixedv(GL_CURRENT_NORMAL, values);
  EXPECT_EQ(values[1], -ONE);
  EXPECT_EQ(values[2], ONE / 2);
  glMultiTexCoord4x(GL_TEXTURE0, ONE / 8, 3 * ONE, 0, ONE);
  glGetFixedv(GL_CURRENT_TEXTURE_COORDS, values);
  EXPECT_EQ(values[0], ONE / 8);
  EXPECT_EQ(values[1], 3 * ONE);

  glClearColorx(0, ONE / 2, ONE, 2 * ONE);  // clamped to [0, 1] like glClearColor
  glGetFixedv(GL_COLOR_CLEAR_VALUE, values);
  EXPECT_EQ(values[1], ONE / 2);
  EXPECT_EQ(values[3], ONE);
  glClearDepthx(ONE / 4);
  glGetFixedv(GL_DEPTH_CLEAR_VALUE, values);
  EXPECT_EQ(values[0], ONE / 4);
  glDepthRangex(ONE / 4, 3 * ONE / 4);
  glGetFixedv(GL_DEPTH_RANGE, values);
  EXPECT_EQ(values[0], ONE / 4);
  EXPECT_EQ(values[1], 3 * ONE / 4);
  glAlphaFuncx(GL_GREATER, ONE / 2);
  glGetFixedv(GL_ALPHA_TEST_REF, values);
  EXPECT_EQ(values[0], ONE / 2);
  glPointSizex(4 * ONE);
  glGetFixedv(GL_POINT_SIZE, values);
  EXPECT_EQ(values[0], 4 * ONE);
  glLineWidthx(3 * ONE / 2);
  glGetFixedv(GL_LINE_WIDTH, values);
  EXPECT_EQ(values[0], 3 * ONE / 2);
  glPolygonOffsetx(2 * ONE, -ONE);
  glGetFixedv(GL_POLYGON_OFFSET_FACTOR, values);
  EXPECT_EQ(values[0], 2 * ONE);
  glGetFixedv(GL_POLYGON_OFFSET_UNITS, values);
  EXPECT_EQ(values[0], -ONE);
  glSampleCoveragex(ONE / 2, GL_TRUE);
  glGetFixedv(GL_SAMPLE_COVERAGE_VALUE, values);
  EXPECT_EQ(values[0], ONE / 2);
  GLfixed plane[4] = {ONE, 0, -ONE, ONE / 2};
  glClipPlanex(GL_CLIP_PLANE2, plane);
  GLfixed plane_back[4] = {0, 0, 0, 0};
  glGetClipPlanex(GL_CLIP_PLANE2, plane_back);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(plane_back[i], plane[i]) << i;
  glPointParameterx(GL_POINT_SIZE_MIN, ONE);
  const GLfixed attenuation[3] = {ONE, 0, 0};
  glPointParameterxv(GL_POINT_DISTANCE_ATTENUATION, attenuation);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

// Integers, enums and booleans are converted to fixed point too (times
// 2^16); what does not fit saturates.
TEST_F(GlApi, GetFixedConvertsEveryKindOfStateAndSaturates) {
  GLfixed value = 0;
  glGetFixedv(GL_MAX_LIGHTS, &value);
  EXPECT_EQ(value, 8 * ONE);
  glEnable(GL_DEPTH_TEST);
  glGetFixedv(GL_DEPTH_WRITEMASK, &value);
  EXPECT_EQ(value, ONE);
  glGetFixedv(GL_DEPTH_FUNC, &value);
  EXPECT_EQ(value, static_cast<GLfixed>(GL_LESS) * ONE);
  glTranslatef(1e6f, -1e6f, 0.5f / 65536 / 4);
  GLfixed m[16];
  glGetFixedv(GL_MODELVIEW_MATRIX, m);
  EXPECT_EQ(m[12], std::numeric_limits<GLfixed>::max());
  EXPECT_EQ(m[13], std::numeric_limits<GLfixed>::min());
  EXPECT_EQ(m[14], 0);  // an eighth of the smallest step rounds to 0
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, FixedLightsMaterialsAndFog) {
  const GLfixed diffuse[4] = {ONE / 2, ONE / 4, 0, ONE};
  glLightxv(GL_LIGHT1, GL_DIFFUSE, diffuse);
  glLightx(GL_LIGHT1, GL_SPOT_CUTOFF, 45 * ONE);
  GLfixed values[4] = {0, 0, 0, 0};
  glGetLightxv(GL_LIGHT1, GL_DIFFUSE, values);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(values[i], diffuse[i]) << i;
  glGetLightxv(GL_LIGHT1, GL_SPOT_CUTOFF, values);
  EXPECT_EQ(values[0], 45 * ONE);

  const GLfixed ambient[4] = {ONE / 10, ONE / 10, ONE / 10, ONE};
  glLightModelxv(GL_LIGHT_MODEL_AMBIENT, ambient);
  glLightModelx(GL_LIGHT_MODEL_TWO_SIDE, 1);  // a boolean: 1, not 1.0
  GLboolean two_side = GL_FALSE;
  glGetBooleanv(GL_LIGHT_MODEL_TWO_SIDE, &two_side);
  EXPECT_EQ(two_side, GL_TRUE);
  glGetFixedv(GL_LIGHT_MODEL_AMBIENT, values);
  EXPECT_EQ(values[0], ambient[0]);

  const GLfixed specular[4] = {ONE, ONE, ONE, ONE};
  glMaterialxv(GL_FRONT_AND_BACK, GL_SPECULAR, specular);
  glMaterialx(GL_FRONT_AND_BACK, GL_SHININESS, 40 * ONE);
  glGetMaterialxv(GL_FRONT, GL_SPECULAR, values);
  EXPECT_EQ(values[0], ONE);
  glGetMaterialxv(GL_FRONT, GL_SHININESS, values);
  EXPECT_EQ(values[0], 40 * ONE);

  glFogx(GL_FOG_MODE, GL_LINEAR);  // an enum: not scaled
  glFogx(GL_FOG_DENSITY, ONE / 2);
  const GLfixed fog_color[4] = {ONE, 0, ONE / 2, ONE};
  glFogxv(GL_FOG_COLOR, fog_color);
  const GLfixed exp2 = GL_EXP2;
  glFogxv(GL_FOG_MODE, &exp2);
  GLint mode = 0;
  glGetIntegerv(GL_FOG_MODE, &mode);
  EXPECT_EQ(mode, GL_EXP2);
  glGetFixedv(GL_FOG_DENSITY, values);
  EXPECT_EQ(values[0], ONE / 2);
  glGetFixedv(GL_FOG_COLOR, values);
  EXPECT_EQ(values[2], ONE / 2);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, FixedTextureParametersCarryEnumsUnscaled) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameterx(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  const GLfixed clamp = GL_CLAMP_TO_EDGE;
  glTexParameterxv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &clamp);
  GLfixed value = 0;
  glGetTexParameterxv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &value);
  EXPECT_EQ(value, GL_LINEAR);
  glGetTexParameterxv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &value);
  EXPECT_EQ(value, GL_CLAMP_TO_EDGE);

  glTexEnvx(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glGetTexEnvxv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &value);
  EXPECT_EQ(value, GL_REPLACE);
  const GLfixed decal = GL_DECAL;
  glTexEnvxv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &decal);
  GLint mode = 0;
  glGetTexEnviv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &mode);
  EXPECT_EQ(mode, GL_DECAL);
  const GLfixed color[4] = {ONE, ONE / 2, 0, ONE};
  glTexEnvxv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, color);
  GLfixed color_back[4] = {0, 0, 0, 0};
  glGetTexEnvxv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, color_back);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(color_back[i], color[i]) << i;
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

// The float commands' errors, and what only the fixed-point commands can
// meet: a null pointer.
TEST_F(GlApi, FixedCommandsReportTheSpecifiedErrors) {
  glFrustumx(-ONE, ONE, -ONE, ONE, 0, 10 * ONE);  // near must be positive
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glLightx(GL_LIGHT0, GL_SPOT_CUTOFF, 120 * ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glLightx(GL_LIGHT0 + 8, GL_SPOT_EXPONENT, ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glLightxv(GL_LIGHT0, GL_SHININESS, nullptr);  // a material's parameter, not a light's
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glMaterialx(GL_FRONT, GL_SHININESS, ONE);  // ES 1.1: GL_FRONT_AND_BACK only
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glMaterialx(GL_FRONT_AND_BACK, GL_SHININESS, 200 * ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glPointSizex(0);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glLineWidthx(-ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glFogx(GL_FOG_MODE, 0x1234);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glFogx(GL_FOG_DENSITY, -ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexEnvx(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_NEAREST);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glTexParameterx(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glPointParameterx(GL_POINT_SIZE_MIN, -ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glPointParameterxv(GL_FOG_MODE, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glAlphaFuncx(GL_ADD, 0);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glClipPlanex(GL_CLIP_PLANE0 + 6, nullptr);  // a wrong name comes before the null pointer
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glTexEnvxv(GL_TEXTURE_ENV, GL_FOG_MODE, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glTexParameterxv(GL_TEXTURE_2D, GL_FOG_MODE, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));

  // Null pointers where values are read or written.
  glLoadMatrixx(nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glMultMatrixx(nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glLightxv(GL_LIGHT0, GL_DIFFUSE, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glMaterialxv(GL_FRONT_AND_BACK, GL_DIFFUSE, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glFogxv(GL_FOG_COLOR, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexEnvxv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexParameterxv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glClipPlanex(GL_CLIP_PLANE0, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glGetFixedv(GL_VIEWPORT, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  glGetLightxv(GL_LIGHT0, GL_DIFFUSE, nullptr);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_VALUE));
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, FailedFixedQueriesWriteNothingAndKeepTheFirstError) {
  GLfixed values[4] = {7, 7, 7, 7};
  glGetFixedv(0xdead, values);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glGetLightxv(GL_LIGHT0 + 9, GL_DIFFUSE, values);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glGetMaterialxv(GL_FRONT_AND_BACK, GL_DIFFUSE, values);  // a query names one face
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glGetTexEnvxv(GL_TEXTURE_2D, GL_TEXTURE_ENV_MODE, values);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glGetTexParameterxv(GL_TEXTURE_2D, GL_TEXTURE_ENV_MODE, values);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  glGetClipPlanex(GL_CLIP_PLANE0 + 6, values);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  for (GLfixed v : values) EXPECT_EQ(v, 7);
  // An error raised before a successful query still sticks.
  glEnable(0x1234);
  glGetLightxv(GL_LIGHT0, GL_DIFFUSE, values);
  EXPECT_EQ(values[0], ONE);
  EXPECT_EQ(error(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(error(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, FixedConversionsAreChargedToTheHost) {
  tessera::test::take_cost_units();
  glTranslatef(1, 2, 3);
  std::map<std::string, uint64_t> with_float = tessera::test::take_cost_units();
  glTranslatex(ONE, 2 * ONE, 3 * ONE);
  std::map<std::string, uint64_t> with_fixed = tessera::test::take_cost_units();
  // A call of its own, and a conversion per value, beside the float call's charges.
  EXPECT_EQ(with_fixed["gl_fixed_argument"], 3u);
  EXPECT_EQ(with_fixed["gl_call"], with_float["gl_call"] + 1);
  EXPECT_EQ(with_fixed["gl_matrix_multiply"], with_float["gl_matrix_multiply"]);
  EXPECT_EQ(with_float["gl_fixed_argument"], 0u);
}

TEST(GlFixedWithoutContext, CallsDoNothing) {
  tessera::gl::set_current_context(nullptr);
  glTranslatex(ONE, 0, 0);
  GLfixed value = 7;
  glGetFixedv(GL_MAX_LIGHTS, &value);
  EXPECT_EQ(value, 7);
  glLoadMatrixx(nullptr);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}
