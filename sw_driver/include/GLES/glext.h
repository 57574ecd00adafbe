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
 * They are ES 1.1's required extensions, so <GLES/gl.h> defines them too,
 * where the Khronos gl.h does; the guards keep one copy. */
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

#ifdef __cplusplus
}
#endif

#endif
