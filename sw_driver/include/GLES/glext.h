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
 *
 * GL_OES_read_format is one of ES 1.1's required extensions, so <GLES/gl.h>
 * defines it too, where the Khronos gl.h does; the guard keeps one copy. */
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

#ifdef __cplusplus
}
#endif

#endif
