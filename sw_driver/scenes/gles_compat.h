// The one header through which the built-in scenes reach GL.
//
// Normally that is tessera's OpenGL ES 1.1 (<GLES/gl.h> from sw_driver/include).
// The reference images come from compiling the same scene sources a second
// time with TESSERA_GL_REFERENCE defined, against Mesa's desktop <GL/gl.h>
// (tools/reference/CMakeLists.txt, tessera_add_reference_scenes). Desktop
// GL has every ES 1.1 common-profile float entry point except the ones ES
// renamed to single precision; those are mapped onto their double-precision
// originals below, so a scene calls them by their ES names in both builds.
//
// Rules for scene code, so that both builds draw the same thing:
//  - include this header, never <GLES/gl.h> or <GL/gl.h> directly;
//  - use only ES 1.1 common-profile calls and enums (no glBegin, GL_QUADS,
//    glTexImage2D with internalformat != format, ...): desktop GL accepts
//    more, and the difference would only show up on our side.
#pragma once

#if defined(TESSERA_GL_REFERENCE)

// Buffer objects, multitexture and point parameters are GL 1.3-1.5 entry
// points: glext.h declares them only with prototypes enabled, and libOSMesa
// exports them.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>

#include <cstddef>
#include <vector>
#if defined(TESSERA_GLES_GL_H)
#error "tessera's GLES/gl.h is on the reference build's include path: it must not be"
#endif

namespace tessera::gles_compat {

inline void frustumf(GLfloat left, GLfloat right, GLfloat bottom, GLfloat top, GLfloat near_val, GLfloat far_val) {
  glFrustum(left, right, bottom, top, near_val, far_val);
}
inline void orthof(GLfloat left, GLfloat right, GLfloat bottom, GLfloat top, GLfloat near_val, GLfloat far_val) {
  glOrtho(left, right, bottom, top, near_val, far_val);
}
// glClearDepthf and glDepthRangef exist in GL 4.1, but an OSMesa context
// need not offer them; the GL 1.0 originals always work.
inline void clear_depthf(GLfloat depth) {
  glClearDepth(depth);
}
inline void depth_rangef(GLfloat near_val, GLfloat far_val) {
  glDepthRange(near_val, far_val);
}
inline void clip_planef(GLenum plane, const GLfloat* equation) {
  const GLdouble widened[4] = {equation[0], equation[1], equation[2], equation[3]};
  glClipPlane(plane, widened);
}
inline void get_clip_planef(GLenum plane, GLfloat* equation) {
  GLdouble widened[4] = {};
  glGetClipPlane(plane, widened);
  for (int i = 0; i < 4; ++i) equation[i] = static_cast<GLfloat>(widened[i]);
}

}  // namespace tessera::gles_compat

// Macros rather than functions of the same name: glext.h may already have
// declared glClearDepthf and glDepthRangef with C linkage.
#define glFrustumf ::tessera::gles_compat::frustumf
#define glOrthof ::tessera::gles_compat::orthof
#define glClearDepthf ::tessera::gles_compat::clear_depthf
#define glDepthRangef ::tessera::gles_compat::depth_rangef
#define glClipPlanef ::tessera::gles_compat::clip_planef
#define glGetClipPlanef ::tessera::gles_compat::get_clip_planef

// OES_compressed_paletted_texture is ES only: Mesa's desktop GL refuses the
// GL_PALETTE* formats. The reference build expands a paletted image to
// RGBA here, by the extension's text (palette first, then each level's
// indices without row padding, a 4-bit index pair's first texel in the high
// nibble), and uploads each level with glTexImage2D. It is written apart
// from the driver's decoder (sw_driver/gl/texture_formats.cpp) on purpose:
// the reference must not share the code it checks.
#ifndef GL_PALETTE4_RGB8_OES
#define GL_PALETTE4_RGB8_OES 0x8B90
#define GL_PALETTE4_RGBA8_OES 0x8B91
#define GL_PALETTE4_R5_G6_B5_OES 0x8B92
#define GL_PALETTE4_RGBA4_OES 0x8B93
#define GL_PALETTE4_RGB5_A1_OES 0x8B94
#define GL_PALETTE8_RGB8_OES 0x8B95
#define GL_PALETTE8_RGBA8_OES 0x8B96
#define GL_PALETTE8_R5_G6_B5_OES 0x8B97
#define GL_PALETTE8_RGBA4_OES 0x8B98
#define GL_PALETTE8_RGB5_A1_OES 0x8B99
#endif

namespace tessera::gles_compat {

inline void compressed_tex_image_2d(GLenum target, GLint level, GLenum format, GLsizei width, GLsizei height,
                                    GLint border, GLsizei, const void* data) {
  const unsigned code = format - GL_PALETTE4_RGB8_OES;  // 0..9
  const int bits = code < 5 ? 4 : 8;
  // Entry size in bytes and how an entry reads, by the format's position in
  // each group of five: RGB8, RGBA8, R5_G6_B5, RGBA4, RGB5_A1.
  const unsigned kind = code % 5;
  const int entry_bytes = kind == 0 ? 3 : kind == 1 ? 4 : 2;
  const auto* bytes = static_cast<const GLubyte*>(data);
  const GLubyte* indices = bytes + (1 << bits) * entry_bytes;
  auto scale = [](unsigned value, unsigned max) { return static_cast<GLubyte>((value * 255 + max / 2) / max); };
  for (int k = 0; k <= -level; ++k) {
    const int w = width >> k > 0 ? width >> k : 1, h = height >> k > 0 ? height >> k : 1;
    std::vector<GLubyte> pixels(static_cast<std::size_t>(w) * h * 4);
    GLubyte* rgba = pixels.data();
    for (int n = 0; n < w * h; ++n) {
      const unsigned index = bits == 8 ? indices[n] : (n % 2 ? indices[n / 2] & 15u : indices[n / 2] >> 4);
      const GLubyte* e = bytes + index * entry_bytes;
      const unsigned word = static_cast<unsigned>(e[0] | e[1] << 8);  // a 16-bit entry, little-endian
      GLubyte* out = rgba + 4 * n;
      switch (kind) {
        case 0: out[0] = e[0], out[1] = e[1], out[2] = e[2], out[3] = 255; break;
        case 1: out[0] = e[0], out[1] = e[1], out[2] = e[2], out[3] = e[3]; break;
        case 2:
          out[0] = scale(word >> 11, 31), out[1] = scale((word >> 5) & 63, 63), out[2] = scale(word & 31, 31);
          out[3] = 255;
          break;
        case 3:
          out[0] = scale(word >> 12, 15), out[1] = scale((word >> 8) & 15, 15), out[2] = scale((word >> 4) & 15, 15);
          out[3] = scale(word & 15, 15);
          break;
        default:
          out[0] = scale(word >> 11, 31), out[1] = scale((word >> 6) & 31, 31), out[2] = scale((word >> 1) & 31, 31);
          out[3] = (word & 1) ? 255 : 0;
      }
    }
    // A palette without alpha makes an RGB texture (GL_REPLACE keeps the fragment's alpha).
    const bool rgb = kind == 0 || kind == 2;
    if (rgb)
      for (int n = 0; n < w * h; ++n)
        for (int c = 0; c < 3; ++c) rgba[3 * n + c] = rgba[4 * n + c];
    GLint alignment = 4;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(target, k, rgb ? GL_RGB : GL_RGBA, w, h, border, rgb ? GL_RGB : GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    indices += (w * h * bits + 7) / 8;
  }
}

}  // namespace tessera::gles_compat

#define glCompressedTexImage2D ::tessera::gles_compat::compressed_tex_image_2d

// The fixed-point (S15.16) commands are ES only: desktop GL has their float
// or double originals. Each x form a scene uses is a conversion here, x /
// 65536, into that original; a parameter that names an enum (a texture
// filter, wrap or environment mode) is passed as it is, as ES 1.1 carries
// it. Written here for the reference, apart from the driver's own
// conversions (sw_driver/gl/gl_fixed.cpp).
namespace tessera::gles_compat {

inline GLdouble from_fixed(GLfixed value) {
  return value / 65536.0;
}
// The values of a vector parameter of glLight / glMaterial / glLightModel.
inline int fixed_parameter_count(GLenum pname) {
  switch (pname) {
    case GL_AMBIENT:
    case GL_DIFFUSE:
    case GL_SPECULAR:
    case GL_POSITION:
    case GL_EMISSION:
    case GL_AMBIENT_AND_DIFFUSE:
    case GL_LIGHT_MODEL_AMBIENT: return 4;
    case GL_SPOT_DIRECTION: return 3;
    default: return 1;
  }
}
inline void fixed_to_floats(const GLfixed* values, int count, GLfloat* out) {
  for (int i = 0; i < count; ++i) out[i] = static_cast<GLfloat>(from_fixed(values[i]));
}

inline void clear_colorx(GLfixed r, GLfixed g, GLfixed b, GLfixed a) {
  glClearColor(static_cast<GLfloat>(from_fixed(r)), static_cast<GLfloat>(from_fixed(g)),
               static_cast<GLfloat>(from_fixed(b)), static_cast<GLfloat>(from_fixed(a)));
}
inline void clear_depthx(GLfixed depth) {
  glClearDepth(from_fixed(depth));
}
inline void frustumx(GLfixed l, GLfixed r, GLfixed b, GLfixed t, GLfixed n, GLfixed f) {
  glFrustum(from_fixed(l), from_fixed(r), from_fixed(b), from_fixed(t), from_fixed(n), from_fixed(f));
}
inline void translatex(GLfixed x, GLfixed y, GLfixed z) {
  glTranslated(from_fixed(x), from_fixed(y), from_fixed(z));
}
inline void rotatex(GLfixed angle, GLfixed x, GLfixed y, GLfixed z) {
  glRotated(from_fixed(angle), from_fixed(x), from_fixed(y), from_fixed(z));
}
inline void scalex(GLfixed x, GLfixed y, GLfixed z) {
  glScaled(from_fixed(x), from_fixed(y), from_fixed(z));
}
inline void color4x(GLfixed r, GLfixed g, GLfixed b, GLfixed a) {
  glColor4d(from_fixed(r), from_fixed(g), from_fixed(b), from_fixed(a));
}
inline void normal3x(GLfixed x, GLfixed y, GLfixed z) {
  glNormal3d(from_fixed(x), from_fixed(y), from_fixed(z));
}
inline void lightxv(GLenum light, GLenum pname, const GLfixed* params) {
  GLfloat f[4] = {};
  fixed_to_floats(params, fixed_parameter_count(pname), f);
  glLightfv(light, pname, f);
}
inline void light_modelxv(GLenum pname, const GLfixed* params) {
  if (pname == GL_LIGHT_MODEL_TWO_SIDE) return glLightModeli(pname, params[0]);  // a boolean
  GLfloat f[4] = {};
  fixed_to_floats(params, fixed_parameter_count(pname), f);
  glLightModelfv(pname, f);
}
inline void materialxv(GLenum face, GLenum pname, const GLfixed* params) {
  GLfloat f[4] = {};
  fixed_to_floats(params, fixed_parameter_count(pname), f);
  glMaterialfv(face, pname, f);
}
inline void materialx(GLenum face, GLenum pname, GLfixed param) {
  glMaterialf(face, pname, static_cast<GLfloat>(from_fixed(param)));
}
inline void tex_parameterx(GLenum target, GLenum pname, GLfixed param) {
  glTexParameteri(target, pname, param);  // every ES 1.1 texture parameter is an enum or a boolean
}
inline void tex_envx(GLenum target, GLenum pname, GLfixed param) {
  if (pname == GL_RGB_SCALE || pname == GL_ALPHA_SCALE)
    glTexEnvf(target, pname, static_cast<GLfloat>(from_fixed(param)));
  else
    glTexEnvi(target, pname, param);  // a mode, source or operand
}
inline void point_sizex(GLfixed size) {
  glPointSize(static_cast<GLfloat>(from_fixed(size)));
}

// GL_FIXED vertex arrays do not exist in desktop GL either. A GL_FIXED
// vertex, normal or texture coordinate pointer is recorded here instead of
// given to GL, and each draw call converts the elements it reads (0 up to
// the last index drawn) to a float copy, hands GL that copy and keeps it
// until the array's next pointer or draw, after the draw has read it. Any
// other type goes to GL unchanged, so scenes without GL_FIXED arrays draw
// as before. Client arrays only: a scene that stores GL_FIXED data in a
// buffer object has no reference here.
struct FixedArray {
  GLint size = 0;
  GLsizei stride = 0;
  const GLfixed* pointer = nullptr;  // null: the array is not GL_FIXED
  std::vector<GLfloat> converted;
};
constexpr int FIXED_TEXCOORD_UNITS = 8;
struct FixedArrays {
  FixedArray vertex, normal, texcoord[FIXED_TEXCOORD_UNITS];
};
inline FixedArrays& fixed_arrays() {
  static FixedArrays arrays;
  return arrays;
}
inline int client_active_unit() {
  GLint unit = GL_TEXTURE0;
  glGetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &unit);
  const int index = unit - GL_TEXTURE0;
  return index >= 0 && index < FIXED_TEXCOORD_UNITS ? index : 0;
}
// True when `pointer` was a GL_FIXED one, now recorded.
inline bool record_fixed(FixedArray& array, GLint size, GLenum type, GLsizei stride, const void* pointer) {
  array.pointer = type == GL_FIXED ? static_cast<const GLfixed*>(pointer) : nullptr;
  array.size = size;
  array.stride = stride;
  return array.pointer != nullptr;
}
inline void vertex_pointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  if (!record_fixed(fixed_arrays().vertex, size, type, stride, pointer)) glVertexPointer(size, type, stride, pointer);
}
inline void normal_pointer(GLenum type, GLsizei stride, const void* pointer) {
  if (!record_fixed(fixed_arrays().normal, 3, type, stride, pointer)) glNormalPointer(type, stride, pointer);
}
inline void tex_coord_pointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  if (!record_fixed(fixed_arrays().texcoord[client_active_unit()], size, type, stride, pointer))
    glTexCoordPointer(size, type, stride, pointer);
}
// Converts elements 0 to `count` - 1 of a recorded array, tightly packed.
inline const GLfloat* convert_fixed(FixedArray& array, GLsizei count) {
  const GLsizei stride_bytes = array.stride ? array.stride : array.size * static_cast<GLsizei>(sizeof(GLfixed));
  array.converted.assign(static_cast<std::size_t>(count) * array.size, 0.0f);
  for (GLsizei i = 0; i < count; ++i) {
    const auto* element = reinterpret_cast<const GLfixed*>(reinterpret_cast<const GLubyte*>(array.pointer) +
                                                           static_cast<std::ptrdiff_t>(i) * stride_bytes);
    fixed_to_floats(element, array.size, &array.converted[static_cast<std::size_t>(i) * array.size]);
  }
  return array.converted.data();
}
// Before a draw reading `count` elements: each enabled GL_FIXED array
// converted and given to GL.
inline void prepare_fixed_arrays(GLsizei count) {
  FixedArrays& a = fixed_arrays();
  bool any = a.vertex.pointer || a.normal.pointer;
  for (const FixedArray& t : a.texcoord) any = any || t.pointer;
  if (!any) return;  // no GL call at all for a scene without GL_FIXED arrays
  if (a.vertex.pointer && glIsEnabled(GL_VERTEX_ARRAY))
    glVertexPointer(a.vertex.size, GL_FLOAT, 0, convert_fixed(a.vertex, count));
  if (a.normal.pointer && glIsEnabled(GL_NORMAL_ARRAY)) glNormalPointer(GL_FLOAT, 0, convert_fixed(a.normal, count));
  const int active = client_active_unit();
  for (int unit = 0; unit < FIXED_TEXCOORD_UNITS; ++unit) {
    FixedArray& t = a.texcoord[unit];
    if (!t.pointer) continue;
    glClientActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    if (glIsEnabled(GL_TEXTURE_COORD_ARRAY)) glTexCoordPointer(t.size, GL_FLOAT, 0, convert_fixed(t, count));
  }
  glClientActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + active));
}
inline void draw_arrays(GLenum mode, GLint first, GLsizei count) {
  prepare_fixed_arrays(first + count);
  glDrawArrays(mode, first, count);
}
inline void draw_elements(GLenum mode, GLsizei count, GLenum type, const void* indices) {
  GLsizei elements = 0;
  for (GLsizei i = 0; i < count; ++i) {
    const GLsizei index =
        type == GL_UNSIGNED_BYTE ? static_cast<const GLubyte*>(indices)[i] : static_cast<const GLushort*>(indices)[i];
    if (index + 1 > elements) elements = index + 1;
  }
  prepare_fixed_arrays(elements);
  glDrawElements(mode, count, type, indices);
}

}  // namespace tessera::gles_compat

#define glClearColorx ::tessera::gles_compat::clear_colorx
#define glClearDepthx ::tessera::gles_compat::clear_depthx
#define glFrustumx ::tessera::gles_compat::frustumx
#define glTranslatex ::tessera::gles_compat::translatex
#define glRotatex ::tessera::gles_compat::rotatex
#define glScalex ::tessera::gles_compat::scalex
#define glColor4x ::tessera::gles_compat::color4x
#define glNormal3x ::tessera::gles_compat::normal3x
#define glLightxv ::tessera::gles_compat::lightxv
#define glLightModelxv ::tessera::gles_compat::light_modelxv
#define glMaterialxv ::tessera::gles_compat::materialxv
#define glMaterialx ::tessera::gles_compat::materialx
#define glTexParameterx ::tessera::gles_compat::tex_parameterx
#define glTexEnvx ::tessera::gles_compat::tex_envx
#define glPointSizex ::tessera::gles_compat::point_sizex
#define glVertexPointer ::tessera::gles_compat::vertex_pointer
#define glNormalPointer ::tessera::gles_compat::normal_pointer
#define glTexCoordPointer ::tessera::gles_compat::tex_coord_pointer
#define glDrawArrays ::tessera::gles_compat::draw_arrays
#define glDrawElements ::tessera::gles_compat::draw_elements

// ES names that desktop GL spells differently (same values).
#ifndef GL_POINT_SPRITE_OES
#define GL_POINT_SPRITE_OES GL_POINT_SPRITE
#endif
#ifndef GL_COORD_REPLACE_OES
#define GL_COORD_REPLACE_OES GL_COORD_REPLACE
#endif
// GL_VERSION_ES_CM_1_1 is deliberately left undefined: it tells a scene
// which build it is in, should it ever need to know.

#else

#include <GLES/gl.h>

#endif

// Polygon antialiasing is desktop GL only (GL_POLYGON_SMOOTH, 0x0B41).
// tessera's driver accepts the same value in glEnable/glDisable/glIsEnabled
// and passes it to the back ends (RasterState::polygon_smooth): the raster
// back end computes edge coverage (EASA), the arm back end ignores it. One
// name for both builds, so that a scene can ask for it.
#if defined(TESSERA_GL_REFERENCE)
#define TESSERA_POLYGON_SMOOTH GL_POLYGON_SMOOTH
#else
#define TESSERA_POLYGON_SMOOTH 0x0B41
#endif
