// The fixed-point entry points of the OpenGL ES 1.1 common profile (the "x"
// commands, ES 1.1 section 2.1.2 and the command summary of chapter 6):
// each converts its S15.16 arguments to float and calls the float command,
// which checks them and records the errors the specification requires of
// both; the queries call the float query and convert its results back,
// rounding to nearest and saturating at the ends of GLfixed's range (6.1.2).
//
// A parameter that names an enum (the texture environment's mode, combiner
// sources and operands, the texture filters and wraps, the fog mode) or a
// boolean (two-sided lighting) carries the value itself and is not scaled,
// as in other ES 1.1 implementations (Mesa's es1_conversion.c); numbers and
// colours are. A null pointer where the command reads or writes values is
// GL_INVALID_VALUE (unless the parameter's name is already wrong, which is
// GL_INVALID_ENUM), where the specification leaves the behaviour undefined.
//
// Each conversion is soft-float work on the ARM: per value an integer to
// float conversion and a multiply by 2^-16 (or 2^16 and the conversion
// back), plus the call into the float command.
#include <GLES/gl.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gl/context.h"
#include "gl/entry_point.h"

using tessera::Op;
using tessera::gl::Context;

namespace {

constexpr float ONE_OVER_FIXED_ONE = 1.0f / 65536.0f;
constexpr float FIXED_ONE = 65536.0f;

float from_fixed(GLfixed x) {
  return static_cast<float>(x) * ONE_OVER_FIXED_ONE;
}

GLfixed to_fixed(float value) {
  if (std::isnan(value)) return 0;
  // Times 2^16 is exact in float (or infinite); every float from 2^23 up
  // is an integer, so the largest below 2^31, 2^31 - 128, fits GLfixed and
  // only 2^31 and beyond clamp (-2^31 is GLfixed's minimum itself).
  constexpr float LIMIT = 2147483648.0f;  // 2^31
  const float scaled = value * FIXED_ONE;
  if (scaled >= LIMIT) return std::numeric_limits<GLfixed>::max();
  if (scaled <= -LIMIT) return std::numeric_limits<GLfixed>::min();
  return static_cast<GLfixed>(std::nearbyint(scaled));
}

// The host's work for `numbers` scaled values and `enums` values passed as
// they are (converted to float, not scaled).
void charge_conversions(Context* c, unsigned numbers, unsigned enums = 0) {
  c->charge(tessera::costs::HostCost::gl_call);
  c->charge(tessera::costs::HostCost::gl_fixed_argument, numbers + enums);
}

// Up to four values, converted from fixed point; `count` of them are read.
std::array<float, 4> from_fixed(const GLfixed* values, int count) {
  std::array<float, 4> out{};
  for (int i = 0; i < count; ++i) out[static_cast<size_t>(i)] = from_fixed(values[i]);
  return out;
}

void put_fixed(const float* values, int count, GLfixed* out) {
  for (int i = 0; i < count; ++i) out[i] = to_fixed(values[i]);
}

// Values of a light's parameter, 0 for a name that is not one.
int light_values(GLenum pname) {
  switch (pname) {
    case GL_AMBIENT:
    case GL_DIFFUSE:
    case GL_SPECULAR:
    case GL_POSITION: return 4;
    case GL_SPOT_DIRECTION: return 3;
    case GL_SPOT_EXPONENT:
    case GL_SPOT_CUTOFF:
    case GL_CONSTANT_ATTENUATION:
    case GL_LINEAR_ATTENUATION:
    case GL_QUADRATIC_ATTENUATION: return 1;
    default: return 0;
  }
}

// Values of a material parameter, 0 for a name that is not one.
int material_values(GLenum pname) {
  switch (pname) {
    case GL_AMBIENT:
    case GL_DIFFUSE:
    case GL_SPECULAR:
    case GL_EMISSION:
    case GL_AMBIENT_AND_DIFFUSE: return 4;
    case GL_SHININESS: return 1;
    default: return 0;
  }
}

int fog_values(GLenum pname) {
  switch (pname) {
    case GL_FOG_COLOR: return 4;
    case GL_FOG_MODE:
    case GL_FOG_DENSITY:
    case GL_FOG_START:
    case GL_FOG_END: return 1;
    default: return 0;
  }
}

int point_parameter_values(GLenum pname) {
  switch (pname) {
    case GL_POINT_DISTANCE_ATTENUATION: return 3;
    case GL_POINT_SIZE_MIN:
    case GL_POINT_SIZE_MAX:
    case GL_POINT_FADE_THRESHOLD_SIZE: return 1;
    default: return 0;
  }
}

// Texture environment parameters whose value is an enum.
bool tex_env_takes_enum(GLenum pname) {
  switch (pname) {
    case GL_TEXTURE_ENV_MODE:
    case GL_COMBINE_RGB:
    case GL_COMBINE_ALPHA:
    case GL_SRC0_RGB:
    case GL_SRC1_RGB:
    case GL_SRC2_RGB:
    case GL_SRC0_ALPHA:
    case GL_SRC1_ALPHA:
    case GL_SRC2_ALPHA:
    case GL_OPERAND0_RGB:
    case GL_OPERAND1_RGB:
    case GL_OPERAND2_RGB:
    case GL_OPERAND0_ALPHA:
    case GL_OPERAND1_ALPHA:
    case GL_OPERAND2_ALPHA:
    case GL_COORD_REPLACE_OES: return true;
    default: return false;
  }
}

// Texture parameters whose value is an enum (all of ES 1.1's).
bool tex_parameter_takes_enum(GLenum pname) {
  switch (pname) {
    case GL_TEXTURE_MIN_FILTER:
    case GL_TEXTURE_MAG_FILTER:
    case GL_TEXTURE_WRAP_S:
    case GL_TEXTURE_WRAP_T:
    case GL_GENERATE_MIPMAP: return true;
    default: return false;
  }
}

// The float value a fixed-point parameter stands for: the value itself for
// an enum, scaled otherwise.
float parameter(GLfixed value, bool takes_enum) {
  return takes_enum ? static_cast<float>(value) : from_fixed(value);
}

// Runs a float query and tells whether it succeeded (a failed query writes
// nothing, and neither may its fixed-point twin). The error flag ends as
// the query left it: an earlier error still sticks.
template <typename Query>
bool query_succeeds(Context* c, Query query) {
  const GLenum earlier = c->get_error();
  query();
  const GLenum error = c->get_error();
  c->error(earlier != GL_NO_ERROR ? earlier : error);
  return error == GL_NO_ERROR;
}

// A vector setter's values: `count` of them read and converted (0 when the
// parameter's name is not one: the float command reports it). False, with
// GL_INVALID_VALUE, for a null pointer where values are read.
bool read_fixed_values(Context* c, const GLfixed* params, int count, std::array<float, 4>& values) {
  if (count <= 0) return true;
  if (!params) {
    c->error(GL_INVALID_VALUE);
    return false;
  }
  charge_conversions(c, static_cast<unsigned>(count));
  values = from_fixed(params, count);
  return true;
}

// As read_fixed_values, for a parameter whose one value is an enum or a
// boolean (`as_value`: carried as it is, not scaled) rather than a number.
bool read_fixed_or_enum(Context* c, const GLfixed* params, int count, bool as_value, std::array<float, 4>& values) {
  if (!as_value || count <= 0) return read_fixed_values(c, params, count, values);
  if (!params) {
    c->error(GL_INVALID_VALUE);
    return false;
  }
  charge_conversions(c, 0, 1);
  values[0] = parameter(params[0], true);
  return true;
}

// A vector query's answer in fixed point: `query` fills up to four floats;
// when it succeeds, `count` of them are converted into `params`.
template <typename Query>
void answer_in_fixed(Context* c, GLfixed* params, int count, Query query) {
  std::array<float, 4> values{};
  if (!query_succeeds(c, [&] { query(values.data()); })) return;
  if (!params) return c->error(GL_INVALID_VALUE);
  charge_conversions(c, static_cast<unsigned>(count));
  put_fixed(values.data(), count, params);
}

}  // namespace

extern "C" {

// ---- Current attributes and matrices ----------------------------------

GL_API void GL_APIENTRY glColor4x(GLfixed red, GLfixed green, GLfixed blue, GLfixed alpha) {
  WITH_CONTEXT()
  charge_conversions(c, 4);
  glColor4f(from_fixed(red), from_fixed(green), from_fixed(blue), from_fixed(alpha));
}

GL_API void GL_APIENTRY glNormal3x(GLfixed nx, GLfixed ny, GLfixed nz) {
  WITH_CONTEXT()
  charge_conversions(c, 3);
  glNormal3f(from_fixed(nx), from_fixed(ny), from_fixed(nz));
}

GL_API void GL_APIENTRY glMultiTexCoord4x(GLenum texture, GLfixed s, GLfixed t, GLfixed r, GLfixed q) {
  WITH_CONTEXT()
  charge_conversions(c, 4);
  glMultiTexCoord4f(texture, from_fixed(s), from_fixed(t), from_fixed(r), from_fixed(q));
}

GL_API void GL_APIENTRY glLoadMatrixx(const GLfixed* m) {
  WITH_CONTEXT()
  if (!m) return c->error(GL_INVALID_VALUE);
  charge_conversions(c, 16);
  GLfloat f[16];
  for (int i = 0; i < 16; ++i) f[i] = from_fixed(m[i]);
  glLoadMatrixf(f);
}

GL_API void GL_APIENTRY glMultMatrixx(const GLfixed* m) {
  WITH_CONTEXT()
  if (!m) return c->error(GL_INVALID_VALUE);
  charge_conversions(c, 16);
  GLfloat f[16];
  for (int i = 0; i < 16; ++i) f[i] = from_fixed(m[i]);
  glMultMatrixf(f);
}

GL_API void GL_APIENTRY glRotatex(GLfixed angle, GLfixed x, GLfixed y, GLfixed z) {
  WITH_CONTEXT()
  charge_conversions(c, 4);
  glRotatef(from_fixed(angle), from_fixed(x), from_fixed(y), from_fixed(z));
}

GL_API void GL_APIENTRY glScalex(GLfixed x, GLfixed y, GLfixed z) {
  WITH_CONTEXT()
  charge_conversions(c, 3);
  glScalef(from_fixed(x), from_fixed(y), from_fixed(z));
}

GL_API void GL_APIENTRY glTranslatex(GLfixed x, GLfixed y, GLfixed z) {
  WITH_CONTEXT()
  charge_conversions(c, 3);
  glTranslatef(from_fixed(x), from_fixed(y), from_fixed(z));
}

GL_API void GL_APIENTRY glFrustumx(GLfixed l, GLfixed r, GLfixed b, GLfixed t, GLfixed n, GLfixed f) {
  WITH_CONTEXT()
  charge_conversions(c, 6);
  glFrustumf(from_fixed(l), from_fixed(r), from_fixed(b), from_fixed(t), from_fixed(n), from_fixed(f));
}

GL_API void GL_APIENTRY glOrthox(GLfixed l, GLfixed r, GLfixed b, GLfixed t, GLfixed n, GLfixed f) {
  WITH_CONTEXT()
  charge_conversions(c, 6);
  glOrthof(from_fixed(l), from_fixed(r), from_fixed(b), from_fixed(t), from_fixed(n), from_fixed(f));
}

GL_API void GL_APIENTRY glDepthRangex(GLfixed n, GLfixed f) {
  WITH_CONTEXT()
  charge_conversions(c, 2);
  glDepthRangef(from_fixed(n), from_fixed(f));
}

GL_API void GL_APIENTRY glClipPlanex(GLenum plane, const GLfixed* equation) {
  WITH_CONTEXT()
  const std::array<float, 4> none{};
  if (plane < GL_CLIP_PLANE0 || plane > GL_CLIP_PLANE5) return glClipPlanef(plane, none.data());  // reports it
  if (!equation) return c->error(GL_INVALID_VALUE);
  charge_conversions(c, 4);
  const std::array<float, 4> f = from_fixed(equation, 4);
  glClipPlanef(plane, f.data());
}

GL_API void GL_APIENTRY glGetClipPlanex(GLenum plane, GLfixed* equation) {
  WITH_CONTEXT()
  answer_in_fixed(c, equation, 4, [&](GLfloat* f) { glGetClipPlanef(plane, f); });
}

// ---- Lighting and fog ---------------------------------------------------

GL_API void GL_APIENTRY glLightx(GLenum light, GLenum pname, GLfixed param) {
  WITH_CONTEXT()
  charge_conversions(c, 1);
  glLightf(light, pname, from_fixed(param));
}

GL_API void GL_APIENTRY glLightxv(GLenum light, GLenum pname, const GLfixed* params) {
  WITH_CONTEXT()
  std::array<float, 4> f{};
  if (!read_fixed_values(c, params, light_values(pname), f)) return;
  glLightfv(light, pname, f.data());
}

GL_API void GL_APIENTRY glGetLightxv(GLenum light, GLenum pname, GLfixed* params) {
  WITH_CONTEXT()
  answer_in_fixed(c, params, light_values(pname), [&](GLfloat* f) { glGetLightfv(light, pname, f); });
}

GL_API void GL_APIENTRY glLightModelx(GLenum pname, GLfixed param) {
  WITH_CONTEXT()
  const bool boolean = pname == GL_LIGHT_MODEL_TWO_SIDE;
  charge_conversions(c, boolean ? 0 : 1, boolean ? 1 : 0);
  glLightModelf(pname, parameter(param, boolean));
}

GL_API void GL_APIENTRY glLightModelxv(GLenum pname, const GLfixed* params) {
  WITH_CONTEXT()
  const int count = pname == GL_LIGHT_MODEL_AMBIENT ? 4 : pname == GL_LIGHT_MODEL_TWO_SIDE ? 1 : 0;
  std::array<float, 4> f{};
  if (!read_fixed_or_enum(c, params, count, pname == GL_LIGHT_MODEL_TWO_SIDE, f)) return;
  glLightModelfv(pname, f.data());
}

GL_API void GL_APIENTRY glMaterialx(GLenum face, GLenum pname, GLfixed param) {
  WITH_CONTEXT()
  charge_conversions(c, 1);
  glMaterialf(face, pname, from_fixed(param));
}

GL_API void GL_APIENTRY glMaterialxv(GLenum face, GLenum pname, const GLfixed* params) {
  WITH_CONTEXT()
  std::array<float, 4> f{};
  if (!read_fixed_values(c, params, material_values(pname), f)) return;
  glMaterialfv(face, pname, f.data());
}

GL_API void GL_APIENTRY glGetMaterialxv(GLenum face, GLenum pname, GLfixed* params) {
  WITH_CONTEXT()
  answer_in_fixed(c, params, material_values(pname), [&](GLfloat* f) { glGetMaterialfv(face, pname, f); });
}

GL_API void GL_APIENTRY glFogx(GLenum pname, GLfixed param) {
  WITH_CONTEXT()
  const bool mode = pname == GL_FOG_MODE;
  charge_conversions(c, mode ? 0 : 1, mode ? 1 : 0);
  glFogf(pname, parameter(param, mode));
}

GL_API void GL_APIENTRY glFogxv(GLenum pname, const GLfixed* params) {
  WITH_CONTEXT()
  std::array<float, 4> f{};
  if (!read_fixed_or_enum(c, params, fog_values(pname), pname == GL_FOG_MODE, f)) return;
  glFogfv(pname, f.data());
}

// ---- Rasterization and per-fragment state -------------------------------

GL_API void GL_APIENTRY glPointSizex(GLfixed size) {
  WITH_CONTEXT()
  charge_conversions(c, 1);
  glPointSize(from_fixed(size));
}

GL_API void GL_APIENTRY glPointParameterx(GLenum pname, GLfixed param) {
  WITH_CONTEXT()
  charge_conversions(c, 1);
  glPointParameterf(pname, from_fixed(param));
}

GL_API void GL_APIENTRY glPointParameterxv(GLenum pname, const GLfixed* params) {
  WITH_CONTEXT()
  const int count = point_parameter_values(pname);
  if (count == 0) {
    c->charge_call();
    return c->error(GL_INVALID_ENUM);
  }
  if (!params) return c->error(GL_INVALID_VALUE);
  charge_conversions(c, static_cast<unsigned>(count));
  const std::array<float, 4> f = from_fixed(params, count);
  glPointParameterfv(pname, f.data());
}

GL_API void GL_APIENTRY glLineWidthx(GLfixed width) {
  WITH_CONTEXT()
  charge_conversions(c, 1);
  glLineWidth(from_fixed(width));
}

GL_API void GL_APIENTRY glPolygonOffsetx(GLfixed factor, GLfixed units) {
  WITH_CONTEXT()
  charge_conversions(c, 2);
  glPolygonOffset(from_fixed(factor), from_fixed(units));
}

GL_API void GL_APIENTRY glSampleCoveragex(GLclampx value, GLboolean invert) {
  WITH_CONTEXT()
  charge_conversions(c, 1);
  glSampleCoverage(from_fixed(value), invert);
}

GL_API void GL_APIENTRY glAlphaFuncx(GLenum func, GLfixed ref) {
  WITH_CONTEXT()
  charge_conversions(c, 1);
  glAlphaFunc(func, from_fixed(ref));
}

GL_API void GL_APIENTRY glClearColorx(GLfixed red, GLfixed green, GLfixed blue, GLfixed alpha) {
  WITH_CONTEXT()
  charge_conversions(c, 4);
  glClearColor(from_fixed(red), from_fixed(green), from_fixed(blue), from_fixed(alpha));
}

GL_API void GL_APIENTRY glClearDepthx(GLfixed depth) {
  WITH_CONTEXT()
  charge_conversions(c, 1);
  glClearDepthf(from_fixed(depth));
}

// ---- Textures -------------------------------------------------------------

GL_API void GL_APIENTRY glTexEnvx(GLenum target, GLenum pname, GLfixed param) {
  WITH_CONTEXT()
  const bool takes_enum = tex_env_takes_enum(pname);
  charge_conversions(c, takes_enum ? 0 : 1, takes_enum ? 1 : 0);
  glTexEnvf(target, pname, parameter(param, takes_enum));
}

GL_API void GL_APIENTRY glTexEnvxv(GLenum target, GLenum pname, const GLfixed* params) {
  WITH_CONTEXT()
  const bool known =
      pname == GL_TEXTURE_ENV_COLOR || pname == GL_RGB_SCALE || pname == GL_ALPHA_SCALE || tex_env_takes_enum(pname);
  if (!known) return glTexEnvf(target, pname, 0);  // reports the name
  if (!params) return c->error(GL_INVALID_VALUE);
  if (pname != GL_TEXTURE_ENV_COLOR) return glTexEnvx(target, pname, params[0]);
  charge_conversions(c, 4);
  const std::array<float, 4> f = from_fixed(params, 4);
  glTexEnvfv(target, pname, f.data());
}

GL_API void GL_APIENTRY glGetTexEnvxv(GLenum target, GLenum pname, GLfixed* params) {
  WITH_CONTEXT()
  std::array<float, 4> f{};
  if (!query_succeeds(c, [&] { glGetTexEnvfv(target, pname, f.data()); })) return;
  if (!params) return c->error(GL_INVALID_VALUE);
  if (pname == GL_TEXTURE_ENV_COLOR) {
    charge_conversions(c, 4);
    put_fixed(f.data(), 4, params);
  } else {
    charge_conversions(c, 0, 1);
    params[0] = static_cast<GLfixed>(f[0]);  // an enum
  }
}

GL_API void GL_APIENTRY glTexParameterx(GLenum target, GLenum pname, GLfixed param) {
  WITH_CONTEXT()
  const bool takes_enum = tex_parameter_takes_enum(pname);
  charge_conversions(c, takes_enum ? 0 : 1, takes_enum ? 1 : 0);
  glTexParameterf(target, pname, parameter(param, takes_enum));
}

GL_API void GL_APIENTRY glTexParameterxv(GLenum target, GLenum pname, const GLfixed* params) {
  WITH_CONTEXT()
  if (!tex_parameter_takes_enum(pname)) return glTexParameterf(target, pname, 0);  // reports the name
  if (!params) return c->error(GL_INVALID_VALUE);
  glTexParameterx(target, pname, params[0]);
}

GL_API void GL_APIENTRY glGetTexParameterxv(GLenum target, GLenum pname, GLfixed* params) {
  WITH_CONTEXT()
  GLfloat f = 0;
  if (!query_succeeds(c, [&] { glGetTexParameterfv(target, pname, &f); })) return;
  if (!params) return c->error(GL_INVALID_VALUE);
  charge_conversions(c, 0, 1);
  params[0] = static_cast<GLfixed>(f);  // every ES 1.1 texture parameter is an enum or a boolean
}

// ---- State queries ----------------------------------------------------------

// Every value as fixed point, as glGetFloatv would give it: booleans become
// 0 or 1.0, integers and enums their value times 2^16 (saturating).
GL_API void GL_APIENTRY glGetFixedv(GLenum pname, GLfixed* params) {
  WITH_CONTEXT()
  std::array<float, 16> f{};
  if (!query_succeeds(c, [&] { glGetFloatv(pname, f.data()); })) return;  // an unknown name
  if (!params) return c->error(GL_INVALID_VALUE);
  const int count = c->query_count(pname);
  charge_conversions(c, static_cast<unsigned>(count));
  put_fixed(f.data(), count, params);
}

}  // extern "C"
