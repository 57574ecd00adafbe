// Unit tests of the GL ES 1.1 and EGL entry points: the error codes the
// specifications require for bad arguments, EGL misuse, and vertices that
// must never reach a renderer (NaN, infinity, huge), on the stand-ins of
// gl_test_fixture.h.
#include <EGL/egl.h>
#include <GLES/gl.h>
#include <GLES/glext.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "device/app_environment.h"
#include "fixtures/backend_table.h"
#include "gl/context.h"
#include "gl/context_internal.h"
#include "gl/runtime.h"
#include "gl_test_fixture.h"
#include "host/cost_units.h"
#include "renderers/backends.h"

using namespace tessera;
using test::GlApi;
using test::RecordingRenderer;
using test::VectorHost;

// Colours and depths through glGetIntegerv: value * (2^31 - 1), rounded to
// nearest, computed exactly in integers. The reference is the product in
// long double (64-bit significand on x86, enough for 24 + 31 bits).
TEST(IntegerQueries, UnitFloatsMapExactlyToTheIntegerRange) {
  auto reference = [](float value) {
    return static_cast<GLint>(std::llround(static_cast<long double>(value) * 2147483647.0L));
  };
  EXPECT_EQ(gl::int_from_unit_float(1.0f), 2147483647);
  EXPECT_EQ(gl::int_from_unit_float(2.0f), 2147483647);
  EXPECT_EQ(gl::int_from_unit_float(-1.0f), -2147483647);
  EXPECT_EQ(gl::int_from_unit_float(-1.5f), std::numeric_limits<GLint>::min());
  EXPECT_EQ(gl::int_from_unit_float(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(gl::int_from_unit_float(0.0f), 0);
  EXPECT_EQ(gl::int_from_unit_float(0.5f), 1073741824);  // 1073741823.5, half away from zero
  float v = 1.0f;
  for (int i = 0; i < 20000; ++i) {
    v = std::nextafter(v, 0.0f);
    ASSERT_EQ(gl::int_from_unit_float(v), reference(v)) << v;
    ASSERT_EQ(gl::int_from_unit_float(-v), reference(-v)) << v;
  }
  for (const float x : {0.2f, 0.3f, 1.0f / 255, 1e-5f, 1e-9f, 2.3283064e-10f, 1e-12f, 1e-40f})
    EXPECT_EQ(gl::int_from_unit_float(x), reference(x)) << x;
  // Other floats: rounded and clamped.
  EXPECT_EQ(gl::int_from_float(2.5f), 3);
  EXPECT_EQ(gl::int_from_float(-2.5f), -3);
  EXPECT_EQ(gl::int_from_float(2147483520.0f), 2147483520);
  EXPECT_EQ(gl::int_from_float(2147483648.0f), 2147483647);
  EXPECT_EQ(gl::int_from_float(-2147483648.0f), std::numeric_limits<GLint>::min());
  EXPECT_EQ(gl::int_from_float(std::numeric_limits<float>::infinity()), 2147483647);
}

TEST_F(GlApi, BadEnumsAreInvalidEnum) {
  glEnable(0x1234);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glDepthFunc(GL_ADD);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glBlendFunc(GL_SRC_ALPHA, GL_DST_COLOR);  // DST_COLOR is not a destination factor
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glDrawArrays(0x20, 0, 3);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glMatrixMode(GL_COLOR_BUFFER_BIT);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, static_cast<float>(GL_NEAREST));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  GLfloat value;
  glGetFloatv(0xdead, &value);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(glGetString(0x1), nullptr);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}

TEST_F(GlApi, BadValuesAreInvalidValue) {
  glViewport(0, 0, -1, 10);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glDrawArrays(GL_TRIANGLES, 0, -3);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glClear(0x1);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  GLuint texture;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  std::vector<uint8_t> pixels(512 * 512 * 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 48, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // not a power of two
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 512, 512, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // above 256
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 64, 64, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // border
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // formats differ
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // nothing defined yet
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glTexSubImage2D(GL_TEXTURE_2D, 0, 60, 60, 8, 8, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // past the edge
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glFrustumf(-1, 1, -1, 1, 0, 10);  // near must be positive
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, 120);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 200);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glPointSize(0);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glVertexPointer(5, GL_FLOAT, 0, nullptr);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
}

// A NaN is in no range: each scalar light and material parameter refuses it
// with GL_INVALID_VALUE and keeps its value (range checks written as
// "v < 0 || v > 128" let NaN through with GL_NO_ERROR).
TEST_F(GlApi, NanLightAndMaterialParametersAreInvalidValue) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const GLenum name :
       {GL_SPOT_EXPONENT, GL_SPOT_CUTOFF, GL_CONSTANT_ATTENUATION, GL_LINEAR_ATTENUATION, GL_QUADRATIC_ATTENUATION}) {
    SCOPED_TRACE("light parameter 0x" + std::to_string(name));
    GLfloat before = -1;
    glGetLightfv(GL_LIGHT0, name, &before);
    glLightf(GL_LIGHT0, name, nan);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
    glLightfv(GL_LIGHT0, name, &nan);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
    GLfloat after = -1;
    glGetLightfv(GL_LIGHT0, name, &after);
    EXPECT_EQ(after, before);
  }
  GLfloat before = -1;
  glGetMaterialfv(GL_FRONT, GL_SHININESS, &before);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, nan);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glMaterialfv(GL_FRONT_AND_BACK, GL_SHININESS, &nan);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  GLfloat after = -1;
  glGetMaterialfv(GL_FRONT, GL_SHININESS, &after);
  EXPECT_EQ(after, before);
  // The ends of the ranges still pass.
  glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, 180);
  glLightf(GL_LIGHT0, GL_SPOT_EXPONENT, 128);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 0);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// Found by fuzz/fuzz_gl.cpp (fuzz/corpus/gl/regress-copy-tex-image-huge-size.bin):
// the copies allocated width x height x 4 bytes before any check of the size.
TEST_F(GlApi, CopiesLargerThanAnyTextureAreInvalidValue) {
  const GLsizei huge = std::numeric_limits<GLsizei>::max();
  glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 0, 0, huge, huge, 0);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 0, 0, 257, 1, 0);  // MAX_TEXTURE_SIZE is 256
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, huge, huge);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  GLint size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &size);
  glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 0, 0, size, size, 0);  // the largest is still a texture
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// Issue 14: a float that is not exactly an enum names none. glTexParameterf,
// glTexEnvf and glFogf used to cast 1e30 and NaN straight to GLenum
// (undefined behaviour, reported by -fsanitize=float-cast-overflow); each is
// GL_INVALID_ENUM and leaves the state as it was, and the exact value still
// works.
TEST_F(GlApi, FloatParametersThatAreNoExactEnumAreInvalidEnum) {
  GLuint texture;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  // The state before the bad calls.
  GLint min_filter = 0, wrap_s = 0, env_mode = 0, fog_mode = 0;
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &min_filter);
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &wrap_s);
  glGetTexEnviv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &env_mode);
  glGetIntegerv(GL_FOG_MODE, &fog_mode);
  EXPECT_EQ(wrap_s, GL_REPEAT);      // GL ES 1.1 table 6.14
  EXPECT_EQ(env_mode, GL_MODULATE);  // table 6.16
  EXPECT_EQ(fog_mode, GL_EXP);       // table 6.9
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float infinity = std::numeric_limits<float>::infinity();
  const float not_enums[] = {
      1e30f, -1e30f, nan, -nan, infinity, -infinity, 4294967296.0f, -1.0f, static_cast<float>(GL_LINEAR) + 0.5f};
  for (const float value : not_enums) {
    SCOPED_TRACE(value);
    glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, value);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
    glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, value);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
    glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, value);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
    glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, &value);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
    glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, value);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
    glTexEnvfv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &value);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
    glFogf(GL_FOG_MODE, value);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
    glFogfv(GL_FOG_MODE, &value);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  }
  // The state is as it was...
  GLint value = 0;
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &value);
  EXPECT_EQ(value, min_filter);
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &value);
  EXPECT_EQ(value, wrap_s);
  glGetTexEnviv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &value);
  EXPECT_EQ(value, env_mode);
  glGetIntegerv(GL_FOG_MODE, &value);
  EXPECT_EQ(value, fog_mode);
  // ...and exact values are taken.
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<float>(GL_LINEAR));
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, static_cast<float>(GL_CLAMP_TO_EDGE));
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, static_cast<float>(GL_REPLACE));
  glFogf(GL_FOG_MODE, static_cast<float>(GL_LINEAR));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &value);
  EXPECT_EQ(value, GL_LINEAR);
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &value);
  EXPECT_EQ(value, GL_CLAMP_TO_EDGE);
  glGetTexEnviv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &value);
  EXPECT_EQ(value, GL_REPLACE);
  glGetIntegerv(GL_FOG_MODE, &value);
  EXPECT_EQ(value, GL_LINEAR);
}

// A float answered through glGetIntegerv is rounded and, beyond GLint,
// clamped (NaN as 0) instead of converted out of range.
TEST_F(GlApi, IntegerQueriesOfHugeFloatsSaturate) {
  GLint value = 0;
  glFogf(GL_FOG_END, 1e30f);
  glGetIntegerv(GL_FOG_END, &value);
  EXPECT_EQ(value, std::numeric_limits<GLint>::max());
  glFogf(GL_FOG_END, -1e30f);
  glGetIntegerv(GL_FOG_END, &value);
  EXPECT_EQ(value, std::numeric_limits<GLint>::min());
  glFogf(GL_FOG_END, std::numeric_limits<float>::quiet_NaN());
  glGetIntegerv(GL_FOG_END, &value);
  EXPECT_EQ(value, 0);
  glFogf(GL_FOG_END, 2.5f);
  glGetIntegerv(GL_FOG_END, &value);
  EXPECT_EQ(value, 3);  // to nearest, halves away from zero
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// Rectangles and offsets near INT_MAX: x + width used to overflow a GLint in
// glTexSubImage2D; each is GL_INVALID_VALUE (or, for a buffer, the error
// GL specifies) and nothing is written.
TEST_F(GlApi, OffsetsNearIntMaxAreRefusedWithoutOverflow) {
  constexpr GLint BIG = std::numeric_limits<GLint>::max();
  GLuint texture;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  std::vector<uint8_t> pixels(64 * 64 * 4, 0x5A);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glTexSubImage2D(GL_TEXTURE_2D, 0, BIG, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, BIG, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexSubImage2D(GL_TEXTURE_2D, 0, 1, 1, BIG, BIG, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexSubImage2D(GL_TEXTURE_2D, 0, 63, 63, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // the last texel
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  // A copy larger than any texture is refused before it is allocated.
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, BIG, BIG);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 0, 0, BIG, 1, 0);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  // A copy from x = INT_MAX lies outside the window: no error, no overflow.
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, BIG, BIG, 2, 2);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  std::vector<uint8_t> read(2 * 2 * 4, 0xEE);
  glReadPixels(BIG, BIG - 1, 2, 2, GL_RGBA, GL_UNSIGNED_BYTE, read.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(read, std::vector<uint8_t>(2 * 2 * 4, 0));

  // Buffers: offset + size and a huge index offset.
  GLuint buffer;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffer);
  const uint16_t indices[3] = {0, 1, 2};
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof indices, indices, GL_STATIC_DRAW);
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, std::numeric_limits<GLintptr>::max(), 2, indices);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 2, std::numeric_limits<GLsizeiptr>::max(), indices);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  // An offset into the bound buffer, passed as a pointer as GL does.
  const auto far_offset =
      reinterpret_cast<const void*>(~static_cast<uintptr_t>(0) - 1);  // NOLINT(performance-no-int-to-ptr)
  glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_SHORT, far_offset);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
}

TEST_F(GlApi, MatrixStackOverflowAndUnderflow) {
  glMatrixMode(GL_MODELVIEW);
  glPopMatrix();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_STACK_UNDERFLOW));
  GLint depth = 0;
  glGetIntegerv(GL_MAX_MODELVIEW_STACK_DEPTH, &depth);
  EXPECT_GE(depth, 16);  // GL ES 1.1 minimum
  for (GLint i = 1; i < depth; ++i) glPushMatrix();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glPushMatrix();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_STACK_OVERFLOW));
  glMatrixMode(GL_PROJECTION);
  glPushMatrix();
  glPushMatrix();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_STACK_OVERFLOW));
}

TEST_F(GlApi, FirstErrorSticksUntilRead) {
  glEnable(0x1234);          // INVALID_ENUM
  glViewport(0, 0, -1, -1);  // INVALID_VALUE, not recorded
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, StateQueriesReadBackWhatWasSet) {
  glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
  GLfloat color[4];
  glGetFloatv(GL_COLOR_CLEAR_VALUE, color);
  EXPECT_FLOAT_EQ(color[1], 0.5f);
  glDepthFunc(GL_LEQUAL);
  GLint func;
  glGetIntegerv(GL_DEPTH_FUNC, &func);
  EXPECT_EQ(func, GL_LEQUAL);
  glTranslatef(1, 2, 3);
  GLfloat m[16];
  glGetFloatv(GL_MODELVIEW_MATRIX, m);
  EXPECT_FLOAT_EQ(m[12], 1);
  EXPECT_FLOAT_EQ(m[13], 2);
  EXPECT_FLOAT_EQ(m[14], 3);
  glEnable(GL_DEPTH_TEST);
  EXPECT_EQ(glIsEnabled(GL_DEPTH_TEST), GL_TRUE);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// The GL enums become the hardware codes of common/fixed_function.def on
// their way to the back end, and glGet gives the GL enums back.
TEST_F(GlApi, FixedFunctionStateReachesTheRendererAsTableCodes) {
  glBlendFunc(GL_DST_COLOR, GL_ONE_MINUS_SRC_ALPHA);
  glStencilOp(GL_INVERT, GL_INCR, GL_REPLACE);
  glStencilFunc(GL_GEQUAL, 3, 0xff);
  glLogicOp(GL_XOR);
  glAlphaFunc(GL_NOTEQUAL, 0.5f);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_DECAL);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  const float positions[] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0, 0.5f, 0};
  draw_triangle(positions);
  glFinish();
  const gl::RasterState& s = renderer.state;
  EXPECT_EQ(code_of(s.blend_src), 8u);  // dst_color
  EXPECT_EQ(code_of(s.blend_dst), 5u);  // one_minus_src_alpha
  EXPECT_EQ(s.stencil_fail, StencilOp::invert);
  EXPECT_EQ(code_of(s.depth_fail), 3u);
  EXPECT_EQ(s.depth_pass, StencilOp::replace);
  EXPECT_EQ(code_of(s.stencil_func), 6u);
  EXPECT_EQ(s.logic_op_mode, LogicOp::xor_);
  EXPECT_EQ(code_of(s.alpha_func), 5u);
  EXPECT_EQ(s.unit[0].env, tessera::gl::TexEnvMode::decal);
  const std::pair<GLenum, GLint> queries[] = {{GL_BLEND_SRC, GL_DST_COLOR},
                                              {GL_BLEND_DST, GL_ONE_MINUS_SRC_ALPHA},
                                              {GL_STENCIL_FAIL, GL_INVERT},
                                              {GL_STENCIL_PASS_DEPTH_FAIL, GL_INCR},
                                              {GL_STENCIL_PASS_DEPTH_PASS, GL_REPLACE},
                                              {GL_STENCIL_FUNC, GL_GEQUAL},
                                              {GL_LOGIC_OP_MODE, GL_XOR},
                                              {GL_ALPHA_TEST_FUNC, GL_NOTEQUAL}};
  for (const auto& [name, value] : queries) {
    GLint got = 0;
    glGetIntegerv(name, &got);
    EXPECT_EQ(got, value) << std::hex << name;
  }
  // What GL does not accept leaves the state as it was.
  glBlendFunc(GL_SRC_COLOR, GL_ZERO);  // SRC_COLOR is not a source factor
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glBlendFunc(GL_ONE, GL_SRC_ALPHA_SATURATE);  // nor SRC_ALPHA_SATURATE a destination factor
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glLogicOp(GL_SET + 1);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glStencilOp(GL_KEEP, GL_KEEP, GL_DECR + 1);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  GLint src = 0, op = 0;
  glGetIntegerv(GL_BLEND_SRC, &src);
  glGetIntegerv(GL_LOGIC_OP_MODE, &op);
  EXPECT_EQ(src, GL_DST_COLOR);
  EXPECT_EQ(op, GL_XOR);
}

TEST_F(GlApi, TriangleReachesTheRendererInScreenFormats) {
  const float positions[] = {-1, -1, 0, 1, -1, 0, -1, 1, 0};
  draw_triangle(positions);
  ASSERT_EQ(renderer.triangles.size(), 1u);
  const gl::Triangle& t = renderer.triangles[0];
  EXPECT_EQ(t.v[0].x, 0);
  EXPECT_EQ(t.v[1].x, 64 * 16);
  EXPECT_EQ(t.v[2].y, 48 * 16);
  EXPECT_EQ(t.v[0].r, 255);          // current colour: white
  EXPECT_GT(host.operations(), 0u);  // the geometry was charged to the host
}

TEST_F(GlApi, NonFiniteAndHugeVerticesDrawNothing) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float with_nan[] = {nan, -1, 0, 1, -1, 0, -1, 1, 0};
  const float with_inf[] = {-1, -1, 0, inf, -1, 0, -1, 1, 0};
  const float huge[] = {-1e38f, -1e38f, 0, 1e38f, -1e38f, 0, -1e38f, 1e38f, 0};
  const float degenerate[] = {0, 0, 0, 0.5f, 0.5f, 0, 1, 1, 0};
  draw_triangle(with_nan);
  draw_triangle(with_inf);
  draw_triangle(degenerate);
  EXPECT_TRUE(renderer.triangles.empty());
  // A huge triangle is clipped to the view volume: whatever is drawn lies on screen.
  draw_triangle(huge);
  for (const auto& t : renderer.triangles)
    for (const auto& v : t.v) {
      EXPECT_GE(v.x, 0);
      EXPECT_LE(v.x, 64 * 16);
      EXPECT_GE(v.y, 0);
      EXPECT_LE(v.y, 48 * 16);
    }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// Vertices on the line y = x / 2, collinear in float, which snapping to 9.4
// moves apart into a sliver. No such triangle may reach the back end,
// whatever the matrices, while a thin but real one still does.
TEST_F(GlApi, CollinearTrianglesReachNoBackEnd) {
  const float collinear[] = {-0.9f, -0.45f, 0, 0.13f, 0.065f, 0, 0.77f, 0.385f, 0};
  gl::Viewport viewport;
  viewport.width = 64;
  viewport.height = 48;
  gl::ScreenVertex snapped[3];
  for (int i = 0; i < 3; ++i) {
    gl::ClipVertex v{};  // colour and texture coordinates too: to_screen reads them
    v.position = {collinear[3 * i], collinear[3 * i + 1], 0, 1};
    ASSERT_TRUE(gl::to_screen(v, viewport, &snapped[i]));
  }
  ASSERT_NE(gl::signed_area(snapped[0], snapped[1], snapped[2]), 0) << "snapping keeps these on one line";
  draw_triangle(collinear);
  EXPECT_TRUE(renderer.triangles.empty());
  // Through a perspective projection and a rotated, translated modelview
  // the vertices stay on one line, up to float rounding.
  glMatrixMode(GL_PROJECTION);
  glFrustumf(-1, 1, -0.75f, 0.75f, 1, 10);
  glMatrixMode(GL_MODELVIEW);
  glTranslatef(0.1f, -0.2f, -3);
  glRotatef(37, 0.3f, 1, 0.2f);
  draw_triangle(collinear);
  EXPECT_TRUE(renderer.triangles.empty());
  glLoadIdentity();
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  // Half a pixel thick (0.02 of 24 pixels per unit): drawn.
  const float thin[] = {-0.9f, -0.45f, 0, 0.13f, 0.085f, 0, 0.77f, 0.385f, 0};
  draw_triangle(thin);
  EXPECT_EQ(renderer.triangles.size(), 1u);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// A frame's first draw call is charged gl_draw_first beside gl_draw, the
// later ones gl_draw alone; once the frame's units are taken (at the swap),
// the next draw is a frame's first again (docs/calibration.md, "A frame's
// first draw").
TEST_F(GlApi, OnlyAFramesFirstDrawIsChargedAsFirst) {
  const float triangle[] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0, 0.5f, 0};
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, triangle);
  tessera::test::take_cost_units();
  for (int draw = 0; draw < 3; ++draw) glDrawArrays(GL_TRIANGLES, 0, 3);
  std::map<std::string, uint64_t> units = tessera::test::take_cost_units();
  EXPECT_EQ(units["gl_draw"], 3u);
  EXPECT_EQ(units["gl_draw_first"], 1u);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  units = tessera::test::take_cost_units();
  EXPECT_EQ(units["gl_draw"], 1u);
  EXPECT_EQ(units["gl_draw_first"], 1u);
  // A call that draws nothing (no vertex array) charges neither.
  glDisableClientState(GL_VERTEX_ARRAY);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  units = tessera::test::take_cost_units();
  EXPECT_EQ(units["gl_draw"], 0u);
  EXPECT_EQ(units["gl_draw_first"], 0u);
}

// glDrawElements transforms each distinct vertex of a call once (the
// post-transform vertex cache) and charges the host for those alone, and
// draws exactly what the same triangles drawn from an unindexed array draw.
TEST_F(GlApi, RepeatedIndicesAreTransformedOnce) {
  ActivityCounters counters;
  context = std::make_unique<gl::Context>(host, renderer, &counters);
  gl::set_current_context(context.get());
  // A 3x3 grid of vertices, two triangles per cell: 9 vertices, 24 indices.
  std::vector<float> grid;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) grid.insert(grid.end(), {x * 0.8f - 0.8f, y * 0.8f - 0.8f, 0.1f * x});
  std::vector<GLushort> indices;
  for (GLushort y = 0; y < 2; ++y)
    for (GLushort x = 0; x < 2; ++x) {
      const GLushort a = y * 3 + x, b = a + 1, c = a + 3, d = c + 1;
      indices.insert(indices.end(), {a, b, c, c, b, d});
    }
  const float normal[3] = {0, 0, 1};
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glNormal3f(normal[0], normal[1], normal[2]);
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, grid.data());

  uint64_t start = host.operations();
  tessera::test::take_cost_units();
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_SHORT, indices.data());
  const uint64_t indexed_cost = host.operations() - start;
  std::map<std::string, uint64_t> units = tessera::test::take_cost_units();
  // The host is charged the transform of each vertex once, and a look-up per index.
  EXPECT_EQ(units["gl_vertex"], 9u);
  EXPECT_EQ(units["gl_vertex_light"], 9u);
  EXPECT_EQ(units["gl_vertex_cache_lookup"], 24u);
  EXPECT_EQ(counters.value("vertices_transformed"), 9u);
  EXPECT_EQ(counters.value("vertex_cache.misses"), 9u);
  EXPECT_EQ(counters.value("vertex_cache.hits"), 15u);
  const std::vector<gl::Triangle> indexed = renderer.triangles;
  ASSERT_EQ(indexed.size(), 8u);

  // The same triangles from an unindexed array: every vertex transformed,
  // no cache look-ups, and the same screen triangles.
  std::vector<float> expanded;
  for (GLushort index : indices) expanded.insert(expanded.end(), &grid[3 * index], &grid[3 * index] + 3);
  renderer.triangles.clear();
  glVertexPointer(3, GL_FLOAT, 0, expanded.data());
  start = host.operations();
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(indices.size()));
  const uint64_t unindexed_cost = host.operations() - start;
  units = tessera::test::take_cost_units();
  EXPECT_EQ(units["gl_vertex"], 24u);
  EXPECT_EQ(units["gl_vertex_light"], 24u);
  EXPECT_EQ(units["gl_vertex_cache_lookup"], 0u);
  EXPECT_EQ(counters.value("vertices_transformed"), 9u + 24u);
  EXPECT_EQ(counters.value("vertex_cache.misses"), 9u);
  EXPECT_EQ(counters.value("vertex_cache.hits"), 15u);
  ASSERT_EQ(renderer.triangles.size(), indexed.size());
  for (size_t t = 0; t < indexed.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const gl::ScreenVertex &a = renderer.triangles[t].v[k], &b = indexed[t].v[k];
      EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z && a.inv_w == b.inv_w && a.r == b.r && a.g == b.g &&
                  a.b == b.b && a.a == b.a && a.tex[0].s == b.tex[0].s && a.tex[0].t == b.tex[0].t)
          << "triangle " << t << ", vertex " << k;
    }
  // The cache saved the transforms (measured costs: each primitive's own
  // work, the same in both, is most of either).
  EXPECT_LT(indexed_cost, unindexed_cost);

  // Every call starts with an empty cache: the next one transforms its
  // vertices again, with the state of its own time.
  renderer.triangles.clear();
  glVertexPointer(3, GL_FLOAT, 0, grid.data());
  glDisable(GL_LIGHTING);
  glColor4f(1, 0, 0, 1);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_SHORT, indices.data());
  EXPECT_EQ(counters.value("vertices_transformed"), 9u + 24u + 9u);
  EXPECT_EQ(counters.value("vertex_cache.hits"), 30u);
  ASSERT_EQ(renderer.triangles.size(), 8u);
  for (const gl::Triangle& t : renderer.triangles)
    for (const gl::ScreenVertex& v : t.v) EXPECT_EQ(std::vector<int>({v.r, v.g, v.b}), std::vector<int>({255, 0, 0}));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, CullingDropsBackFaces) {
  const float clockwise[] = {-1, -1, 0, -1, 1, 0, 1, -1, 0};
  glEnable(GL_CULL_FACE);
  draw_triangle(clockwise);
  EXPECT_TRUE(renderer.triangles.empty());
  glFrontFace(GL_CW);
  draw_triangle(clockwise);
  EXPECT_EQ(renderer.triangles.size(), 1u);
}

TEST_F(GlApi, PointsAndLinesBecomeTriangles) {
  const float points[] = {0, 0, 0, 0.5f, 0.5f, 0};
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, points);
  glPointSize(4);
  glDrawArrays(GL_POINTS, 0, 2);
  EXPECT_EQ(renderer.triangles.size(), 4u);
  renderer.triangles.clear();
  glDrawArrays(GL_LINES, 0, 2);
  EXPECT_EQ(renderer.triangles.size(), 2u);
  renderer.triangles.clear();
  glDrawArrays(GL_LINE_LOOP, 0, 2);
  EXPECT_EQ(renderer.triangles.size(), 4u);
}

// GL_EXTENSIONS names exactly the extensions whose macros the SDK's
// headers define (GL_OES_read_format, ...), and the driver answers what
// each promises.
TEST_F(GlApi, ExtensionStringMatchesTheHeaders) {
  const char* source = std::getenv("TESSERA_SOURCE_DIR");
  ASSERT_NE(source, nullptr) << "run through ctest, which sets TESSERA_SOURCE_DIR";
  const std::regex extension_macro(R"(\s*#\s*define\s+(GL_[A-Z]+_[a-z][A-Za-z0-9_]*)\s+1\s*)");
  std::set<std::string> declared;
  for (const char* header : {"GLES/gl.h", "GLES/glext.h"}) {
    std::ifstream in(std::string(source) + "/sw_driver/include/" + header);
    ASSERT_TRUE(in) << header;
    std::smatch match;
    for (std::string line; std::getline(in, line);)
      if (std::regex_match(line, match, extension_macro)) declared.insert(match[1]);
  }
  const GLubyte* text = glGetString(GL_EXTENSIONS);
  ASSERT_NE(text, nullptr);
  std::istringstream words(reinterpret_cast<const char*>(text));
  std::set<std::string> listed;
  for (std::string word; words >> word;) listed.insert(word);
  EXPECT_EQ(listed, declared);
  EXPECT_EQ(listed.count("GL_OES_read_format"), 1u);

  GLint format = 0, type = 0;
  glGetIntegerv(GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES, &format);
  glGetIntegerv(GL_IMPLEMENTATION_COLOR_READ_TYPE_OES, &type);
  uint8_t pixel[4];
  glReadPixels(0, 0, 1, 1, static_cast<GLenum>(format), static_cast<GLenum>(type), pixel);
  EXPECT_EQ(format, GL_RGBA);
  EXPECT_EQ(type, GL_UNSIGNED_BYTE);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, ReadPixelsChecksFormatAndType) {
  uint8_t pixels[16];
  glReadPixels(0, 0, 2, 2, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(pixels[0], 0x5a);
  glReadPixels(0, 0, 2, 2, 0x81A5 /* GL_DEPTH_COMPONENT16 */, GL_UNSIGNED_BYTE, pixels);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glReadPixels(0, 0, -2, 2, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
}

TEST(GlWithoutContext, CallsDoNothingAndQueriesReturnZero) {
  gl::set_current_context(nullptr);
  glClear(GL_COLOR_BUFFER_BIT);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(glIsEnabled(GL_DEPTH_TEST), GL_FALSE);
  EXPECT_EQ(glGetString(GL_VERSION), nullptr);
}

// EGL ------------------------------------------------------------------------

TEST(Egl, MisuseGivesTheSpecifiedErrors) {
  VectorHost host;
  AppEnvironment env;
  env.host = &host;
  env.heap_base = 4u << 20;
  env.heap_end = 15u << 20;
  env.frame_buffers[0] = 15u << 20;
  env.frame_buffers[1] = (15u << 20) + 0x10000;
  env.frames = 2;
  env.make_renderer = [](AppEnvironment&) { return std::make_unique<RecordingRenderer>(); };
  env.capabilities = {16, 8};
  gl::set_environment(&env);

  EXPECT_EQ(eglGetDisplay(reinterpret_cast<EGLNativeDisplayType>(0x1234)), EGL_NO_DISPLAY);
  EXPECT_EQ(eglGetError(), EGL_BAD_PARAMETER);
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  ASSERT_NE(display, EGL_NO_DISPLAY);
  EGLint count = 0;
  // Before eglInitialize.
  EXPECT_EQ(eglChooseConfig(display, nullptr, nullptr, 0, &count), EGL_FALSE);
  EXPECT_EQ(eglGetError(), EGL_NOT_INITIALIZED);
  EXPECT_EQ(eglInitialize(reinterpret_cast<EGLDisplay>(0x99), nullptr, nullptr), EGL_FALSE);
  EXPECT_EQ(eglGetError(), EGL_BAD_DISPLAY);
  EGLint major = 0, minor = 0;
  ASSERT_EQ(eglInitialize(display, &major, &minor), EGL_TRUE);
  EXPECT_EQ(major, 1);
  EXPECT_EQ(minor, 4);
  EXPECT_EQ(eglGetError(), EGL_SUCCESS);

  const EGLint unknown_attribute[] = {0x7777, 1, EGL_NONE};
  EXPECT_EQ(eglChooseConfig(display, unknown_attribute, nullptr, 0, &count), EGL_FALSE);
  EXPECT_EQ(eglGetError(), EGL_BAD_ATTRIBUTE);
  const EGLint too_many_samples[] = {EGL_SAMPLES, 4, EGL_NONE};
  ASSERT_EQ(eglChooseConfig(display, too_many_samples, nullptr, 0, &count), EGL_TRUE);
  EXPECT_EQ(count, 0);
  EGLConfig config;
  const EGLint wanted[] = {EGL_RED_SIZE, 5, EGL_DEPTH_SIZE, 16, EGL_NONE};
  ASSERT_EQ(eglChooseConfig(display, wanted, &config, 1, &count), EGL_TRUE);
  ASSERT_EQ(count, 1);

  const EGLint es2[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
  EXPECT_EQ(eglCreateContext(display, config, EGL_NO_CONTEXT, es2), EGL_NO_CONTEXT);
  EXPECT_EQ(eglGetError(), EGL_BAD_MATCH);
  EXPECT_EQ(eglCreateContext(display, reinterpret_cast<EGLConfig>(0x55), EGL_NO_CONTEXT, nullptr), EGL_NO_CONTEXT);
  EXPECT_EQ(eglGetError(), EGL_BAD_CONFIG);
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  ASSERT_NE(context, EGL_NO_CONTEXT);

  EXPECT_EQ(eglMakeCurrent(display, reinterpret_cast<EGLSurface>(0x77), reinterpret_cast<EGLSurface>(0x77), context),
            EGL_FALSE);
  EXPECT_EQ(eglGetError(), EGL_BAD_SURFACE);
  EXPECT_EQ(eglSwapBuffers(display, reinterpret_cast<EGLSurface>(0x77)), EGL_FALSE);
  EXPECT_EQ(eglGetError(), EGL_BAD_SURFACE);
  EXPECT_EQ(eglBindAPI(EGL_OPENVG_API), EGL_FALSE);
  EXPECT_EQ(eglGetError(), EGL_BAD_PARAMETER);

  EGLSurface surface = eglCreateWindowSurface(display, config, static_cast<EGLNativeWindowType>(0), nullptr);
  ASSERT_NE(surface, EGL_NO_SURFACE) << eglGetError();
  EXPECT_EQ(eglCreateWindowSurface(display, config, static_cast<EGLNativeWindowType>(0), nullptr), EGL_NO_SURFACE);
  EXPECT_EQ(eglGetError(), EGL_BAD_ALLOC);  // one screen, one window surface
  ASSERT_EQ(eglMakeCurrent(display, surface, surface, context), EGL_TRUE);
  EGLint width = 0;
  eglQuerySurface(display, surface, EGL_WIDTH, &width);
  EXPECT_EQ(width, 64);
  glClearColor(1, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  // The first swap returns; the second is the run's last frame and ends the program.
  EXPECT_EQ(eglSwapBuffers(display, surface), EGL_TRUE);
  EXPECT_THROW(eglSwapBuffers(display, surface), gl::FramesComplete);
  EXPECT_EQ(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT), EGL_TRUE);
  EXPECT_EQ(eglTerminate(display), EGL_TRUE);
  gl::set_environment(nullptr);
}

// What EGL offers before a surface exists, and what GL reports once the
// back end's renderer is made, are what the back end stores: 16-bit depth
// on arm, 24 on raster, 8-bit stencil on both; ap-tile keeps 16-bit depth
// in CMEM and no stencil; ap-pixel and ap-object a 16-bit depth buffer in
// system memory and no stencil test. Making the array back ends' renderers needs the
// array processor, which this host without devices lacks, so for them only
// EGL's side is checked here (their renderers report the same
// CAPABILITIES).
TEST(Egl, DepthAndStencilBitsAreTheBackEndsOwn) {
  const std::map<std::string, gl::RendererCapabilities> stored = {
      {"arm", {16, 8}}, {"raster", {24, 8}}, {"ap-tile", {16, 0}}, {"ap-pixel", {16, 0}}, {"ap-object", {16, 0}}};
  const std::set<std::string> needs_devices = {"ap-tile", "ap-pixel", "ap-object"};
  for (const std::string& backend : test::back_end_names()) {
    SCOPED_TRACE(backend);
    ASSERT_TRUE(stored.count(backend)) << "say what the new back end stores";
    VectorHost host;
    AppEnvironment env;
    env.host = &host;
    env.heap_base = 4u << 20;
    env.heap_end = 15u << 20;
    env.frame_buffers[0] = 15u << 20;
    env.frame_buffers[1] = (15u << 20) + 0x10000;
    backends::hand_over(backends::backend(backend), env);
    gl::set_environment(&env);
    const gl::RendererCapabilities expected = stored.at(backend);

    EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    ASSERT_EQ(eglInitialize(display, nullptr, nullptr), EGL_TRUE);
    EGLConfig config;
    EGLint count = 0;
    ASSERT_EQ(eglChooseConfig(display, nullptr, &config, 1, &count), EGL_TRUE);
    ASSERT_EQ(count, 1);
    EGLint depth = 0, stencil = 0;
    ASSERT_EQ(eglGetConfigAttrib(display, config, EGL_DEPTH_SIZE, &depth), EGL_TRUE);
    ASSERT_EQ(eglGetConfigAttrib(display, config, EGL_STENCIL_SIZE, &stencil), EGL_TRUE);
    EXPECT_EQ(depth, static_cast<EGLint>(expected.depth_bits));
    EXPECT_EQ(stencil, static_cast<EGLint>(expected.stencil_bits));
    // Sizes are minimums: one bit more than stored matches no configuration.
    const EGLint deeper[] = {EGL_DEPTH_SIZE, depth + 1, EGL_NONE};
    ASSERT_EQ(eglChooseConfig(display, deeper, &config, 1, &count), EGL_TRUE);
    EXPECT_EQ(count, 0);
    const EGLint exact[] = {EGL_DEPTH_SIZE, depth, EGL_STENCIL_SIZE, stencil, EGL_NONE};
    ASSERT_EQ(eglChooseConfig(display, exact, &config, 1, &count), EGL_TRUE);
    ASSERT_EQ(count, 1);
    if (needs_devices.count(backend) != 0) {
      EXPECT_EQ(eglTerminate(display), EGL_TRUE);
      gl::set_environment(nullptr);
      continue;
    }

    EGLSurface surface = eglCreateWindowSurface(display, config, static_cast<EGLNativeWindowType>(0), nullptr);
    ASSERT_NE(surface, EGL_NO_SURFACE) << eglGetError();
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
    ASSERT_EQ(eglMakeCurrent(display, surface, surface, context), EGL_TRUE);
    GLint depth_bits = 0, stencil_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    glGetIntegerv(GL_STENCIL_BITS, &stencil_bits);
    EXPECT_EQ(depth_bits, depth);
    EXPECT_EQ(stencil_bits, stencil);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    EXPECT_EQ(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT), EGL_TRUE);
    EXPECT_EQ(eglDestroyContext(display, context), EGL_TRUE);
    EXPECT_EQ(eglDestroySurface(display, surface), EGL_TRUE);
    EXPECT_EQ(eglTerminate(display), EGL_TRUE);
    gl::set_environment(nullptr);
  }
}

TEST_F(GlApi, DepthAndStencilBitsComeFromTheRenderer) {
  GLint bits = 0;
  glGetIntegerv(GL_DEPTH_BITS, &bits);
  EXPECT_EQ(bits, 12);
  glGetIntegerv(GL_STENCIL_BITS, &bits);
  EXPECT_EQ(bits, 4);
}

// GL_BYTE, GL_SHORT and GL_FIXED vertex and texture-coordinate arrays (ES
// 1.1 section 2.8): integers are taken as they are, GL_FIXED as S15.16.
// With glOrthof over the 64 x 48 window an object coordinate is a window
// coordinate, so (10, 10), (50, 12), (30, 40) arrive in 9.4 as 16 times
// those numbers, and texture coordinates (with texturing on) as given.
TEST_F(GlApi, ByteShortAndFixedArraysGiveTheirValues) {
  glMatrixMode(GL_PROJECTION);
  glOrthof(0, 64, 0, 48, -1, 1);
  GLuint texture;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  const uint8_t texel[4] = {255, 255, 255, 255};
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glEnable(GL_TEXTURE_2D);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  const int position[6] = {10, 10, 50, 12, 30, 40};
  const int coordinate[6] = {0, 1, 2, 3, -4, 5};
  const int8_t bytes[6] = {10, 10, 50, 12, 30, 40};
  const int8_t byte_coordinates[6] = {0, 1, 2, 3, -4, 5};
  const int16_t shorts[6] = {10, 10, 50, 12, 30, 40};
  const int16_t short_coordinates[6] = {0, 1, 2, 3, -4, 5};
  GLfixed fixed[6], fixed_coordinates[6];
  for (int i = 0; i < 6; ++i) {
    fixed[i] = position[i] * 65536;
    fixed_coordinates[i] = coordinate[i] * 65536;
  }
  const struct {
    const char* name;
    GLenum type;
    const void* positions;
    const void* coordinates;
  } cases[] = {{"GL_BYTE", GL_BYTE, bytes, byte_coordinates},
               {"GL_SHORT", GL_SHORT, shorts, short_coordinates},
               {"GL_FIXED", GL_FIXED, fixed, fixed_coordinates}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    renderer.triangles.clear();
    glVertexPointer(2, c.type, 0, c.positions);
    glTexCoordPointer(2, c.type, 0, c.coordinates);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    ASSERT_EQ(renderer.triangles.size(), 1u);
    const gl::Triangle& t = renderer.triangles[0];
    for (int v = 0; v < 3; ++v) {
      EXPECT_EQ(t.v[v].x, 16 * position[2 * v]);
      EXPECT_EQ(t.v[v].y, 16 * position[2 * v + 1]);
      EXPECT_EQ(t.v[v].tex[0].s, static_cast<float>(coordinate[2 * v]));
      EXPECT_EQ(t.v[v].tex[0].t, static_cast<float>(coordinate[2 * v + 1]));
    }
  }
}

// Normal arrays of GL_BYTE and GL_SHORT are normalised (ES 1.1 table 2.7:
// (2 c + 1) / (2^b - 1)), so lighting sees unit-range normals. A light
// along +z with diffuse (1, 1, 1) on a white material, ambient off: the
// vertex colour is the normal's z. Byte 63 is 127 / 255, 0.498 (127 in
// 0.8 after rounding 126.99); byte 127 and short 32767 are 1 (255); short
// -32768 is -1 (0, the light is behind). Left raw, 63 would saturate at 255.
TEST_F(GlApi, ByteAndShortNormalArraysAreNormalised) {
  glMatrixMode(GL_PROJECTION);
  glOrthof(0, 64, 0, 48, -1, 1);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  const float black[4] = {0, 0, 0, 1}, white[4] = {1, 1, 1, 1}, along_z[4] = {0, 0, 1, 0};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, black);
  glLightfv(GL_LIGHT0, GL_AMBIENT, black);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, white);
  glLightfv(GL_LIGHT0, GL_SPECULAR, black);
  glLightfv(GL_LIGHT0, GL_POSITION, along_z);
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, black);
  glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, white);
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, black);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  const float position[6] = {10, 10, 50, 12, 30, 40};
  glVertexPointer(2, GL_FLOAT, 0, position);
  const int8_t bytes[9] = {0, 0, 63, 0, 0, 127, 0, 0, 127};
  const int16_t shorts[9] = {0, 0, 32767, 0, 0, -32768, 0, 0, 32767};
  const struct {
    const char* name;
    GLenum type;
    const void* normals;
    uint8_t expected[3];
  } cases[] = {{"GL_BYTE", GL_BYTE, bytes, {127, 255, 255}}, {"GL_SHORT", GL_SHORT, shorts, {255, 0, 255}}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    renderer.triangles.clear();
    glNormalPointer(c.type, 0, c.normals);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    ASSERT_EQ(renderer.triangles.size(), 1u);
    for (int v = 0; v < 3; ++v) EXPECT_EQ(renderer.triangles[0].v[v].r, c.expected[v]) << "vertex " << v;
  }
}
