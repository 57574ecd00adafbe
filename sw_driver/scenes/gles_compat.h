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
