// The GL front end's texture units (OpenGL ES 1.1 sections 2.10.2, 3.7.12):
// glActiveTexture / glClientActiveTexture and their errors, per-unit
// enables, bindings, coordinate arrays, current coordinates and texture
// matrices, the texture environment's names and values with the errors the
// specification gives, glGetTexEnv, and what reaches the back end.
#include <GLES/gl.h>

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "gl/context.h"
#include "gl/runtime.h"
#include "gl_test_fixture.h"

using namespace tessera;
using test::GlApi;

namespace {

const float TRIANGLE[] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};

// A 1x1 RGBA texture bound on the active unit.
GLuint one_texel_texture(GLubyte r, GLubyte g, GLubyte b, GLubyte a) {
  GLuint name = 0;
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
  const GLubyte texel[4] = {r, g, b, a};
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
  return name;
}

GLint get_env(GLenum name) {
  GLint value = -1;
  glGetTexEnviv(GL_TEXTURE_ENV, name, &value);
  return value;
}

TEST_F(GlApi, TwoTextureUnitsByDefault) {
  GLint units = 0;
  glGetIntegerv(GL_MAX_TEXTURE_UNITS, &units);
  EXPECT_EQ(units, 2);
  glActiveTexture(GL_TEXTURE1);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  // A unit beyond the count, and a non-unit enum, are GL_INVALID_ENUM and
  // leave the selection alone.
  glActiveTexture(GL_TEXTURE2);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glClientActiveTexture(GL_TEXTURE0 + 31);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glMultiTexCoord4f(GL_TEXTURE2, 0, 0, 0, 1);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  GLint active = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  EXPECT_EQ(active, GL_TEXTURE1);
}

TEST(GlTextureUnits, TheCountComesFromTheConstructor) {
  test::VectorHost host;
  test::RecordingRenderer renderer;
  AppEnvironment env;
  env.host = &host;
  env.heap_base = 4u << 20;
  env.heap_end = 15u << 20;
  gl::set_environment(&env);
  auto context = std::make_unique<gl::Context>(host, renderer, nullptr, 4);
  gl::set_current_context(context.get());
  GLint units = 0;
  glGetIntegerv(GL_MAX_TEXTURE_UNITS, &units);
  EXPECT_EQ(units, 4);
  glActiveTexture(GL_TEXTURE3);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  gl::set_current_context(nullptr);
  gl::set_environment(nullptr);
}

TEST_F(GlApi, EachUnitHasItsOwnEnableBindingAndMatrix) {
  const GLuint a = one_texel_texture(255, 0, 0, 255);
  glEnable(GL_TEXTURE_2D);
  glActiveTexture(GL_TEXTURE1);
  EXPECT_EQ(glIsEnabled(GL_TEXTURE_2D), GL_FALSE);
  GLint bound = -1;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  EXPECT_EQ(bound, 0);
  const GLuint b = one_texel_texture(0, 255, 0, 255);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  EXPECT_EQ(static_cast<GLuint>(bound), b);
  glMatrixMode(GL_TEXTURE);
  glTranslatef(0.5f, 0.25f, 0);
  glPushMatrix();
  GLint depth = 0;
  glGetIntegerv(GL_TEXTURE_STACK_DEPTH, &depth);
  EXPECT_EQ(depth, 2);
  glActiveTexture(GL_TEXTURE0);
  glGetIntegerv(GL_TEXTURE_STACK_DEPTH, &depth);
  EXPECT_EQ(depth, 1);
  GLfloat m[16];
  glGetFloatv(GL_TEXTURE_MATRIX, m);
  EXPECT_EQ(m[12], 0.0f);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  EXPECT_EQ(static_cast<GLuint>(bound), a);
  EXPECT_EQ(glIsEnabled(GL_TEXTURE_2D), GL_TRUE);
  // Deleting a texture unbinds it from every unit.
  glDeleteTextures(1, &b);
  glActiveTexture(GL_TEXTURE1);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  EXPECT_EQ(bound, 0);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, UnitsReachTheBackEndWithTheirOwnCoordinates) {
  // Unit 0: array coordinates, identity matrix. Unit 1: the current
  // coordinates of glMultiTexCoord4f, through a matrix that scales s by 2
  // and adds 0.25 to t, divided by q.
  one_texel_texture(255, 0, 0, 255);
  glEnable(GL_TEXTURE_2D);
  glActiveTexture(GL_TEXTURE1);
  one_texel_texture(0, 255, 0, 255);
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_ADD);
  glMatrixMode(GL_TEXTURE);
  glTranslatef(0, 0.25f, 0);
  glScalef(2, 1, 1);
  glMultiTexCoord4f(GL_TEXTURE1, 0.125f, 0.5f, 0, 2);
  const float st0[] = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f};
  glClientActiveTexture(GL_TEXTURE0);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glTexCoordPointer(2, GL_FLOAT, 0, st0);
  draw_triangle(TRIANGLE);
  glFinish();
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  ASSERT_FALSE(renderer.triangles.empty());
  const gl::RasterState& s = renderer.state;
  EXPECT_TRUE(s.unit[0].enabled);
  EXPECT_TRUE(s.unit[1].enabled);
  EXPECT_FALSE(s.unit[2].enabled);
  EXPECT_EQ(s.unit[0].env, gl::TexEnvMode::modulate);
  EXPECT_EQ(s.unit[1].env, gl::TexEnvMode::add);
  EXPECT_NE(s.unit[0].tex.address, s.unit[1].tex.address);
  // (2 * 0.125 / 2, (0.5 + 0.25 * 2) / 2) = (0.125, 0.5) at every vertex:
  // the matrix applies to (s, t, r, q), then s and t are divided by q.
  for (const gl::ScreenVertex& v : renderer.triangles.back().v) {
    EXPECT_FLOAT_EQ(v.tex[1].s, 0.125f);
    EXPECT_FLOAT_EQ(v.tex[1].t, 0.5f);
  }
  float s_sum = 0, t_sum = 0;
  for (const gl::ScreenVertex& v : renderer.triangles.back().v) s_sum += v.tex[0].s, t_sum += v.tex[0].t;
  EXPECT_FLOAT_EQ(s_sum, 1.0f);
  EXPECT_FLOAT_EQ(t_sum, 1.0f);
}

TEST_F(GlApi, ClientStateIsPerClientUnit) {
  glClientActiveTexture(GL_TEXTURE1);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  const float st[] = {0, 0};
  glTexCoordPointer(3, GL_FLOAT, 0, st);
  GLint size = 0;
  glGetIntegerv(GL_TEXTURE_COORD_ARRAY_SIZE, &size);
  EXPECT_EQ(size, 3);
  EXPECT_EQ(glIsEnabled(GL_TEXTURE_COORD_ARRAY), GL_TRUE);
  glClientActiveTexture(GL_TEXTURE0);
  glGetIntegerv(GL_TEXTURE_COORD_ARRAY_SIZE, &size);
  EXPECT_EQ(size, 4);
  EXPECT_EQ(glIsEnabled(GL_TEXTURE_COORD_ARRAY), GL_FALSE);
  // The current coordinates follow the server's active unit.
  glMultiTexCoord4f(GL_TEXTURE1, 0.5f, 0.25f, 0, 1);
  GLfloat current[4];
  glGetFloatv(GL_CURRENT_TEXTURE_COORDS, current);
  EXPECT_EQ(current[0], 0.0f);
  glActiveTexture(GL_TEXTURE1);
  glGetFloatv(GL_CURRENT_TEXTURE_COORDS, current);
  EXPECT_EQ(current[0], 0.5f);
  EXPECT_EQ(current[1], 0.25f);
}

TEST_F(GlApi, TexEnvDefaultsAreThoseOfTheSpecification) {
  EXPECT_EQ(get_env(GL_TEXTURE_ENV_MODE), GL_MODULATE);
  EXPECT_EQ(get_env(GL_COMBINE_RGB), GL_MODULATE);
  EXPECT_EQ(get_env(GL_COMBINE_ALPHA), GL_MODULATE);
  EXPECT_EQ(get_env(GL_SRC0_RGB), GL_TEXTURE);
  EXPECT_EQ(get_env(GL_SRC1_RGB), GL_PREVIOUS);
  EXPECT_EQ(get_env(GL_SRC2_RGB), GL_CONSTANT);
  EXPECT_EQ(get_env(GL_SRC0_ALPHA), GL_TEXTURE);
  EXPECT_EQ(get_env(GL_SRC1_ALPHA), GL_PREVIOUS);
  EXPECT_EQ(get_env(GL_SRC2_ALPHA), GL_CONSTANT);
  EXPECT_EQ(get_env(GL_OPERAND0_RGB), GL_SRC_COLOR);
  EXPECT_EQ(get_env(GL_OPERAND1_RGB), GL_SRC_COLOR);
  EXPECT_EQ(get_env(GL_OPERAND2_RGB), GL_SRC_ALPHA);
  EXPECT_EQ(get_env(GL_OPERAND0_ALPHA), GL_SRC_ALPHA);
  EXPECT_EQ(get_env(GL_OPERAND1_ALPHA), GL_SRC_ALPHA);
  EXPECT_EQ(get_env(GL_OPERAND2_ALPHA), GL_SRC_ALPHA);
  EXPECT_EQ(get_env(GL_RGB_SCALE), 1);
  EXPECT_EQ(get_env(GL_ALPHA_SCALE), 1);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, TexEnvCombineStateReadsBackPerUnit) {
  glActiveTexture(GL_TEXTURE1);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_COMBINE);
  glTexEnvi(GL_TEXTURE_ENV, GL_COMBINE_RGB, GL_DOT3_RGBA);
  glTexEnvi(GL_TEXTURE_ENV, GL_COMBINE_ALPHA, GL_INTERPOLATE);
  glTexEnvi(GL_TEXTURE_ENV, GL_SRC1_RGB, GL_PRIMARY_COLOR);
  glTexEnvi(GL_TEXTURE_ENV, GL_SRC2_ALPHA, GL_TEXTURE);
  glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND0_RGB, GL_ONE_MINUS_SRC_ALPHA);
  glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND2_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glTexEnvf(GL_TEXTURE_ENV, GL_RGB_SCALE, 4.0f);
  glTexEnvi(GL_TEXTURE_ENV, GL_ALPHA_SCALE, 2);
  const GLfloat color[4] = {0.2f, 0.4f, 0.6f, 1.5f};
  glTexEnvfv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, color);
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(get_env(GL_TEXTURE_ENV_MODE), GL_COMBINE);
  EXPECT_EQ(get_env(GL_COMBINE_RGB), GL_DOT3_RGBA);
  EXPECT_EQ(get_env(GL_COMBINE_ALPHA), GL_INTERPOLATE);
  EXPECT_EQ(get_env(GL_SRC1_RGB), GL_PRIMARY_COLOR);
  EXPECT_EQ(get_env(GL_SRC2_ALPHA), GL_TEXTURE);
  EXPECT_EQ(get_env(GL_OPERAND0_RGB), GL_ONE_MINUS_SRC_ALPHA);
  EXPECT_EQ(get_env(GL_OPERAND2_ALPHA), GL_ONE_MINUS_SRC_ALPHA);
  EXPECT_EQ(get_env(GL_RGB_SCALE), 4);
  EXPECT_EQ(get_env(GL_ALPHA_SCALE), 2);
  GLfloat back[4];
  glGetTexEnvfv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, back);
  EXPECT_FLOAT_EQ(back[2], 0.6f);
  EXPECT_FLOAT_EQ(back[3], 1.0f);  // clamped to [0, 1]
  // Unit 0 kept its defaults.
  glActiveTexture(GL_TEXTURE0);
  EXPECT_EQ(get_env(GL_TEXTURE_ENV_MODE), GL_MODULATE);
  EXPECT_EQ(get_env(GL_RGB_SCALE), 1);

  // And the back end gets the codes: 0.2 * 255 = 51, 0.4 * 255 = 102,
  // 0.6 * 255 = 153, 255.
  glActiveTexture(GL_TEXTURE1);
  one_texel_texture(1, 2, 3, 4);
  glEnable(GL_TEXTURE_2D);
  draw_triangle(TRIANGLE);
  glFinish();
  const gl::TextureUnit& unit = renderer.state.unit[1];
  EXPECT_EQ(unit.env, gl::TexEnvMode::combine);
  EXPECT_EQ(unit.combine_rgb.func, gl::CombineFunc::dot3_rgba);
  EXPECT_EQ(unit.combine_alpha.func, gl::CombineFunc::interpolate);
  EXPECT_EQ(unit.combine_rgb.source[1], gl::CombineSource::primary_color);
  EXPECT_EQ(unit.combine_alpha.source[2], gl::CombineSource::texture);
  EXPECT_EQ(unit.combine_rgb.operand[0], gl::CombineOperand::one_minus_src_alpha);
  EXPECT_EQ(unit.combine_alpha.operand[2], gl::CombineOperand::one_minus_src_alpha);
  EXPECT_EQ(unit.combine_rgb.scale, 4);
  EXPECT_EQ(unit.combine_alpha.scale, 2);
  EXPECT_EQ(unit.env_color[0], 51);
  EXPECT_EQ(unit.env_color[1], 102);
  EXPECT_EQ(unit.env_color[2], 153);
  EXPECT_EQ(unit.env_color[3], 255);
  EXPECT_FALSE(renderer.state.unit[0].enabled);
}

TEST_F(GlApi, TexEnvErrors) {
  struct Case {
    GLenum target, name;
    GLint value;
    GLenum error;
  };
  const Case cases[] = {
      {GL_TEXTURE_2D, GL_TEXTURE_ENV_MODE, GL_MODULATE, GL_INVALID_ENUM},  // bad target
      {GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_SUBTRACT, GL_INVALID_ENUM},
      {GL_TEXTURE_ENV, GL_COMBINE_RGB, GL_DECAL, GL_INVALID_ENUM},
      // The dot products are colour functions only.
      {GL_TEXTURE_ENV, GL_COMBINE_ALPHA, GL_DOT3_RGB, GL_INVALID_ENUM},
      {GL_TEXTURE_ENV, GL_COMBINE_ALPHA, GL_DOT3_RGBA, GL_INVALID_ENUM},
      {GL_TEXTURE_ENV, GL_SRC0_RGB, GL_TEXTURE0, GL_INVALID_ENUM},
      {GL_TEXTURE_ENV, GL_SRC2_ALPHA, GL_SRC_COLOR, GL_INVALID_ENUM},
      {GL_TEXTURE_ENV, GL_OPERAND1_RGB, GL_TEXTURE, GL_INVALID_ENUM},
      // An alpha operand reads alpha only.
      {GL_TEXTURE_ENV, GL_OPERAND0_ALPHA, GL_SRC_COLOR, GL_INVALID_ENUM},
      {GL_TEXTURE_ENV, GL_OPERAND2_ALPHA, GL_ONE_MINUS_SRC_COLOR, GL_INVALID_ENUM},
      // Scales are 1, 2 or 4.
      {GL_TEXTURE_ENV, GL_RGB_SCALE, 3, GL_INVALID_VALUE},
      {GL_TEXTURE_ENV, GL_ALPHA_SCALE, 0, GL_INVALID_VALUE},
      {GL_TEXTURE_ENV, GL_ALPHA_SCALE, 8, GL_INVALID_VALUE},
      {GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR + 100, GL_MODULATE, GL_INVALID_ENUM},  // bad name
  };
  for (const Case& c : cases) {
    glTexEnvi(c.target, c.name, c.value);
    EXPECT_EQ(glGetError(), c.error) << std::hex << c.name << " " << c.value;
  }
  // Nothing was changed by the refused calls.
  EXPECT_EQ(get_env(GL_TEXTURE_ENV_MODE), GL_MODULATE);
  EXPECT_EQ(get_env(GL_COMBINE_ALPHA), GL_MODULATE);
  EXPECT_EQ(get_env(GL_RGB_SCALE), 1);
  GLint value = 0;
  glGetTexEnviv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR + 100, &value);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glGetTexEnviv(GL_TEXTURE_2D, GL_TEXTURE_ENV_MODE, &value);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  // A non-integral float for an enum-valued name is no enum.
  glTexEnvf(GL_TEXTURE_ENV, GL_COMBINE_RGB, static_cast<GLfloat>(GL_ADD) + 0.5f);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}

}  // namespace
