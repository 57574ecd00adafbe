// The entry points of OES_fixed_point and OES_single_precision, two of the
// extensions ES 1.1 requires: the extensions came before ES 1.1 and ES 1.1
// took their commands into the core without the suffix, so each OES name
// here is its core command (gl_fixed.cpp, gl_api.cpp) under another name:
// it forwards its arguments unchanged and the core command checks them,
// records the errors and charges the host's work. One implementation, two
// names, so the two cannot drift apart.
//
// OES_matrix_get adds only enums (glGetIntegerv in gl_api.cpp) and
// OES_byte_coordinates only GL_BYTE in glVertexPointer and glTexCoordPointer
// (gl_api.cpp, vertex_fetch.cpp).
#include <GLES/gl.h>
#include <GLES/glext.h>

extern "C" {

// ---- OES_fixed_point ----------------------------------------------------

GL_API void GL_APIENTRY glAlphaFuncxOES(GLenum func, GLfixed ref) {
  glAlphaFuncx(func, ref);
}
GL_API void GL_APIENTRY glClearColorxOES(GLfixed red, GLfixed green, GLfixed blue, GLfixed alpha) {
  glClearColorx(red, green, blue, alpha);
}
GL_API void GL_APIENTRY glClearDepthxOES(GLfixed depth) {
  glClearDepthx(depth);
}
GL_API void GL_APIENTRY glClipPlanexOES(GLenum plane, const GLfixed* equation) {
  glClipPlanex(plane, equation);
}
GL_API void GL_APIENTRY glColor4xOES(GLfixed red, GLfixed green, GLfixed blue, GLfixed alpha) {
  glColor4x(red, green, blue, alpha);
}
GL_API void GL_APIENTRY glDepthRangexOES(GLfixed n, GLfixed f) {
  glDepthRangex(n, f);
}
GL_API void GL_APIENTRY glFogxOES(GLenum pname, GLfixed param) {
  glFogx(pname, param);
}
GL_API void GL_APIENTRY glFogxvOES(GLenum pname, const GLfixed* param) {
  glFogxv(pname, param);
}
GL_API void GL_APIENTRY glFrustumxOES(GLfixed l, GLfixed r, GLfixed b, GLfixed t, GLfixed n, GLfixed f) {
  glFrustumx(l, r, b, t, n, f);
}
GL_API void GL_APIENTRY glGetClipPlanexOES(GLenum plane, GLfixed* equation) {
  glGetClipPlanex(plane, equation);
}
GL_API void GL_APIENTRY glGetFixedvOES(GLenum pname, GLfixed* params) {
  glGetFixedv(pname, params);
}
GL_API void GL_APIENTRY glGetLightxvOES(GLenum light, GLenum pname, GLfixed* params) {
  glGetLightxv(light, pname, params);
}
GL_API void GL_APIENTRY glGetMaterialxvOES(GLenum face, GLenum pname, GLfixed* params) {
  glGetMaterialxv(face, pname, params);
}
GL_API void GL_APIENTRY glGetTexEnvxvOES(GLenum target, GLenum pname, GLfixed* params) {
  glGetTexEnvxv(target, pname, params);
}
GL_API void GL_APIENTRY glGetTexParameterxvOES(GLenum target, GLenum pname, GLfixed* params) {
  glGetTexParameterxv(target, pname, params);
}
GL_API void GL_APIENTRY glLightModelxOES(GLenum pname, GLfixed param) {
  glLightModelx(pname, param);
}
GL_API void GL_APIENTRY glLightModelxvOES(GLenum pname, const GLfixed* param) {
  glLightModelxv(pname, param);
}
GL_API void GL_APIENTRY glLightxOES(GLenum light, GLenum pname, GLfixed param) {
  glLightx(light, pname, param);
}
GL_API void GL_APIENTRY glLightxvOES(GLenum light, GLenum pname, const GLfixed* params) {
  glLightxv(light, pname, params);
}
GL_API void GL_APIENTRY glLineWidthxOES(GLfixed width) {
  glLineWidthx(width);
}
GL_API void GL_APIENTRY glLoadMatrixxOES(const GLfixed* m) {
  glLoadMatrixx(m);
}
GL_API void GL_APIENTRY glMaterialxOES(GLenum face, GLenum pname, GLfixed param) {
  glMaterialx(face, pname, param);
}
GL_API void GL_APIENTRY glMaterialxvOES(GLenum face, GLenum pname, const GLfixed* param) {
  glMaterialxv(face, pname, param);
}
GL_API void GL_APIENTRY glMultMatrixxOES(const GLfixed* m) {
  glMultMatrixx(m);
}
GL_API void GL_APIENTRY glMultiTexCoord4xOES(GLenum texture, GLfixed s, GLfixed t, GLfixed r, GLfixed q) {
  glMultiTexCoord4x(texture, s, t, r, q);
}
GL_API void GL_APIENTRY glNormal3xOES(GLfixed nx, GLfixed ny, GLfixed nz) {
  glNormal3x(nx, ny, nz);
}
GL_API void GL_APIENTRY glOrthoxOES(GLfixed l, GLfixed r, GLfixed b, GLfixed t, GLfixed n, GLfixed f) {
  glOrthox(l, r, b, t, n, f);
}
GL_API void GL_APIENTRY glPointParameterxOES(GLenum pname, GLfixed param) {
  glPointParameterx(pname, param);
}
GL_API void GL_APIENTRY glPointParameterxvOES(GLenum pname, const GLfixed* params) {
  glPointParameterxv(pname, params);
}
GL_API void GL_APIENTRY glPointSizexOES(GLfixed size) {
  glPointSizex(size);
}
GL_API void GL_APIENTRY glPolygonOffsetxOES(GLfixed factor, GLfixed units) {
  glPolygonOffsetx(factor, units);
}
GL_API void GL_APIENTRY glRotatexOES(GLfixed angle, GLfixed x, GLfixed y, GLfixed z) {
  glRotatex(angle, x, y, z);
}
GL_API void GL_APIENTRY glSampleCoveragexOES(GLclampx value, GLboolean invert) {
  glSampleCoveragex(value, invert);
}
GL_API void GL_APIENTRY glScalexOES(GLfixed x, GLfixed y, GLfixed z) {
  glScalex(x, y, z);
}
GL_API void GL_APIENTRY glTexEnvxOES(GLenum target, GLenum pname, GLfixed param) {
  glTexEnvx(target, pname, param);
}
GL_API void GL_APIENTRY glTexEnvxvOES(GLenum target, GLenum pname, const GLfixed* params) {
  glTexEnvxv(target, pname, params);
}
GL_API void GL_APIENTRY glTexParameterxOES(GLenum target, GLenum pname, GLfixed param) {
  glTexParameterx(target, pname, param);
}
GL_API void GL_APIENTRY glTexParameterxvOES(GLenum target, GLenum pname, const GLfixed* params) {
  glTexParameterxv(target, pname, params);
}
GL_API void GL_APIENTRY glTranslatexOES(GLfixed x, GLfixed y, GLfixed z) {
  glTranslatex(x, y, z);
}

// ---- OES_single_precision -------------------------------------------------

GL_API void GL_APIENTRY glClearDepthfOES(GLclampf depth) {
  glClearDepthf(depth);
}
GL_API void GL_APIENTRY glClipPlanefOES(GLenum plane, const GLfloat* equation) {
  glClipPlanef(plane, equation);
}
GL_API void GL_APIENTRY glDepthRangefOES(GLclampf n, GLclampf f) {
  glDepthRangef(n, f);
}
GL_API void GL_APIENTRY glFrustumfOES(GLfloat l, GLfloat r, GLfloat b, GLfloat t, GLfloat n, GLfloat f) {
  glFrustumf(l, r, b, t, n, f);
}
GL_API void GL_APIENTRY glGetClipPlanefOES(GLenum plane, GLfloat* equation) {
  glGetClipPlanef(plane, equation);
}
GL_API void GL_APIENTRY glOrthofOES(GLfloat l, GLfloat r, GLfloat b, GLfloat t, GLfloat n, GLfloat f) {
  glOrthof(l, r, b, t, n, f);
}

}  // extern "C"
