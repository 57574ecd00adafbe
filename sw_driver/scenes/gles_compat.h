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
