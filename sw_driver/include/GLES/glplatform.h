/* Calling convention and linkage of tessera's OpenGL ES 1.1 entry points.
 *
 * Applications include <GLES/gl.h>; this file exists because portable code
 * sometimes includes it directly. The macros can be predefined by a build
 * that needs different linkage (as with the Khronos headers). Like the
 * Khronos glplatform.h it brings in <KHR/khrplatform.h>, the SDK's own copy,
 * for code that expects the khronos_* types after including the GL. */
#ifndef TESSERA_GLES_GLPLATFORM_H
#define TESSERA_GLES_GLPLATFORM_H

#include <KHR/khrplatform.h>

#ifndef GL_API
#if defined(__GNUC__)
#define GL_API __attribute__((visibility("default")))
#else
#define GL_API
#endif
#endif

/* Only 32-bit Windows has a non-default calling convention for GL. */
#ifndef GL_APIENTRY
#define GL_APIENTRY
#endif

#endif
