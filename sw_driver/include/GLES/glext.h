/* The OpenGL ES 1.1 extensions tessera's driver implements.
 *
 * An application includes <GLES/glext.h> after <GLES/gl.h> and guards its
 * use of an extension with the extension's macro (#ifdef GL_OES_...), then
 * checks glGetString(GL_EXTENSIONS) at run time. This header declares
 * exactly the extensions that string lists, so code that uses one only
 * when its macro is defined compiles the paths that work here and leaves
 * out the others. (Shipping it also keeps the compiler from taking the
 * system's Khronos glext.h, which describes another implementation.)
 *
 *   GL_OES_read_format  the colour format and type glReadPixels prefers,
 *                       from glGetIntegerv(GL_IMPLEMENTATION_COLOR_READ_
 *                       FORMAT_OES / _TYPE_OES): RGBA, UNSIGNED_BYTE.
 *   GL_OES_point_size_array  a size per point from an array
 *                       (glPointSizePointerOES, GL_FIXED or GL_FLOAT).
 *   GL_OES_point_sprite  textured points whose texture coordinates run
 *                       across the point (GL_COORD_REPLACE_OES).
 *
 *   GL_OES_compressed_paletted_texture  glCompressedTexImage2D with the
 *                       ten GL_PALETTE4_* / GL_PALETTE8_* formats.
 *
 * Those four are ES 1.1's required extensions that the Khronos gl.h
 * carries, so <GLES/gl.h> defines them too; the guards keep one copy. The
 * other four ES 1.1 requires are here only:
 *
 *   GL_OES_byte_coordinates  GL_BYTE accepted by glVertexPointer and
 *                       glTexCoordPointer, the values taken as they are
 *                       (not normalised). No entry points in ES (the
 *                       extension's glVertex*bOES are desktop immediate mode).
 *   GL_OES_fixed_point  the fixed-point (S15.16) commands under OES names:
 *                       glTranslatexOES is glTranslatex, and so on. ES 1.1
 *                       has no texture coordinate generation, so the
 *                       extension's glTexGenx*OES (state of
 *                       OES_texture_cube_map) are not declared.
 *   GL_OES_single_precision  glFrustumfOES, glOrthofOES, glDepthRangefOES,
 *                       glClearDepthfOES, glClipPlanefOES, glGetClipPlanefOES:
 *                       the core ES 1.1 float commands under OES names.
 *   GL_OES_matrix_get   glGetIntegerv of GL_MODELVIEW_/PROJECTION_/TEXTURE_
 *                       MATRIX_FLOAT_AS_INT_BITS_OES: the 16 elements of the
 *                       current matrix of that stack (the texture matrix of
 *                       the active texture unit), column by column, each as
 *                       the bits of its IEEE 754 single (bit 31 the sign).
 *                       Only glGetIntegerv takes them, as the extension
 *                       says; the other glGet* report GL_INVALID_ENUM. */
#ifndef TESSERA_GLES_GLEXT_H
#define TESSERA_GLES_GLEXT_H

#include <GLES/gl.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Pointer-to-function types of extension entry points use it. */
#ifndef GL_APIENTRYP
#define GL_APIENTRYP GL_APIENTRY*
#endif

#ifndef GL_OES_read_format
#define GL_OES_read_format 1
#define GL_IMPLEMENTATION_COLOR_READ_TYPE_OES 0x8B9A
#define GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES 0x8B9B
#endif

#ifndef GL_OES_point_size_array
#define GL_OES_point_size_array 1
#define GL_POINT_SIZE_ARRAY_OES 0x8B9C
#define GL_POINT_SIZE_ARRAY_TYPE_OES 0x898A
#define GL_POINT_SIZE_ARRAY_STRIDE_OES 0x898B
#define GL_POINT_SIZE_ARRAY_POINTER_OES 0x898C
#define GL_POINT_SIZE_ARRAY_BUFFER_BINDING_OES 0x8B9F
GL_API void GL_APIENTRY glPointSizePointerOES(GLenum type, GLsizei stride, const void* pointer);
#endif

#ifndef GL_OES_point_sprite
#define GL_OES_point_sprite 1
#define GL_POINT_SPRITE_OES 0x8861
#define GL_COORD_REPLACE_OES 0x8862
#endif

#ifndef GL_OES_compressed_paletted_texture
#define GL_OES_compressed_paletted_texture 1
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

#ifndef GL_OES_byte_coordinates
#define GL_OES_byte_coordinates 1
#endif

#ifndef GL_OES_fixed_point
#define GL_OES_fixed_point 1
#define GL_FIXED_OES 0x140C
GL_API void GL_APIENTRY glAlphaFuncxOES(GLenum func, GLfixed ref);
GL_API void GL_APIENTRY glClearColorxOES(GLfixed red, GLfixed green, GLfixed blue, GLfixed alpha);
GL_API void GL_APIENTRY glClearDepthxOES(GLfixed depth);
GL_API void GL_APIENTRY glClipPlanexOES(GLenum plane, const GLfixed* equation);
GL_API void GL_APIENTRY glColor4xOES(GLfixed red, GLfixed green, GLfixed blue, GLfixed alpha);
GL_API void GL_APIENTRY glDepthRangexOES(GLfixed n, GLfixed f);
GL_API void GL_APIENTRY glFogxOES(GLenum pname, GLfixed param);
GL_API void GL_APIENTRY glFogxvOES(GLenum pname, const GLfixed* param);
GL_API void GL_APIENTRY glFrustumxOES(GLfixed l, GLfixed r, GLfixed b, GLfixed t, GLfixed n, GLfixed f);
GL_API void GL_APIENTRY glGetClipPlanexOES(GLenum plane, GLfixed* equation);
GL_API void GL_APIENTRY glGetFixedvOES(GLenum pname, GLfixed* params);
GL_API void GL_APIENTRY glGetLightxvOES(GLenum light, GLenum pname, GLfixed* params);
GL_API void GL_APIENTRY glGetMaterialxvOES(GLenum face, GLenum pname, GLfixed* params);
GL_API void GL_APIENTRY glGetTexEnvxvOES(GLenum target, GLenum pname, GLfixed* params);
GL_API void GL_APIENTRY glGetTexParameterxvOES(GLenum target, GLenum pname, GLfixed* params);
GL_API void GL_APIENTRY glLightModelxOES(GLenum pname, GLfixed param);
GL_API void GL_APIENTRY glLightModelxvOES(GLenum pname, const GLfixed* param);
GL_API void GL_APIENTRY glLightxOES(GLenum light, GLenum pname, GLfixed param);
GL_API void GL_APIENTRY glLightxvOES(GLenum light, GLenum pname, const GLfixed* params);
GL_API void GL_APIENTRY glLineWidthxOES(GLfixed width);
GL_API void GL_APIENTRY glLoadMatrixxOES(const GLfixed* m);
GL_API void GL_APIENTRY glMaterialxOES(GLenum face, GLenum pname, GLfixed param);
GL_API void GL_APIENTRY glMaterialxvOES(GLenum face, GLenum pname, const GLfixed* param);
GL_API void GL_APIENTRY glMultMatrixxOES(const GLfixed* m);
GL_API void GL_APIENTRY glMultiTexCoord4xOES(GLenum texture, GLfixed s, GLfixed t, GLfixed r, GLfixed q);
GL_API void GL_APIENTRY glNormal3xOES(GLfixed nx, GLfixed ny, GLfixed nz);
GL_API void GL_APIENTRY glOrthoxOES(GLfixed l, GLfixed r, GLfixed b, GLfixed t, GLfixed n, GLfixed f);
GL_API void GL_APIENTRY glPointParameterxOES(GLenum pname, GLfixed param);
GL_API void GL_APIENTRY glPointParameterxvOES(GLenum pname, const GLfixed* params);
GL_API void GL_APIENTRY glPointSizexOES(GLfixed size);
GL_API void GL_APIENTRY glPolygonOffsetxOES(GLfixed factor, GLfixed units);
GL_API void GL_APIENTRY glRotatexOES(GLfixed angle, GLfixed x, GLfixed y, GLfixed z);
GL_API void GL_APIENTRY glSampleCoveragexOES(GLclampx value, GLboolean invert);
GL_API void GL_APIENTRY glScalexOES(GLfixed x, GLfixed y, GLfixed z);
GL_API void GL_APIENTRY glTexEnvxOES(GLenum target, GLenum pname, GLfixed param);
GL_API void GL_APIENTRY glTexEnvxvOES(GLenum target, GLenum pname, const GLfixed* params);
GL_API void GL_APIENTRY glTexParameterxOES(GLenum target, GLenum pname, GLfixed param);
GL_API void GL_APIENTRY glTexParameterxvOES(GLenum target, GLenum pname, const GLfixed* params);
GL_API void GL_APIENTRY glTranslatexOES(GLfixed x, GLfixed y, GLfixed z);
#endif

#ifndef GL_OES_single_precision
#define GL_OES_single_precision 1
GL_API void GL_APIENTRY glClearDepthfOES(GLclampf depth);
GL_API void GL_APIENTRY glClipPlanefOES(GLenum plane, const GLfloat* equation);
GL_API void GL_APIENTRY glDepthRangefOES(GLclampf n, GLclampf f);
GL_API void GL_APIENTRY glFrustumfOES(GLfloat l, GLfloat r, GLfloat b, GLfloat t, GLfloat n, GLfloat f);
GL_API void GL_APIENTRY glGetClipPlanefOES(GLenum plane, GLfloat* equation);
GL_API void GL_APIENTRY glOrthofOES(GLfloat l, GLfloat r, GLfloat b, GLfloat t, GLfloat n, GLfloat f);
#endif

#ifndef GL_OES_matrix_get
#define GL_OES_matrix_get 1
#define GL_MODELVIEW_MATRIX_FLOAT_AS_INT_BITS_OES 0x898D
#define GL_PROJECTION_MATRIX_FLOAT_AS_INT_BITS_OES 0x898E
#define GL_TEXTURE_MATRIX_FLOAT_AS_INT_BITS_OES 0x898F
#endif

#ifdef __cplusplus
}
#endif

#endif
