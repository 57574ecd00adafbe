/* Platform types and linkage of tessera's EGL 1.4.
 *
 * Tessera is its own window system: a "window" is the display controller's
 * scan-out buffer chosen by the driver, so the native handles are opaque
 * pointers that applications pass through unchanged (normally 0, as with
 * EGL_DEFAULT_DISPLAY). The macros can be predefined by a build that needs
 * different linkage, as with the Khronos headers. */
#ifndef TESSERA_EGL_EGLPLATFORM_H
#define TESSERA_EGL_EGLPLATFORM_H

#include <stdint.h>

#ifndef EGLAPI
#if defined(__GNUC__)
#define EGLAPI __attribute__((visibility("default")))
#else
#define EGLAPI
#endif
#endif

#ifndef EGLAPIENTRY
#define EGLAPIENTRY
#endif
#define EGLAPIENTRYP EGLAPIENTRY*

typedef void* EGLNativeDisplayType;
typedef void* EGLNativeWindowType;
typedef void* EGLNativePixmapType;

/* The EGL 1.0 names of the same handles. */
typedef EGLNativeDisplayType NativeDisplayType;
typedef EGLNativeWindowType NativeWindowType;
typedef EGLNativePixmapType NativePixmapType;

typedef int32_t EGLint;

/* C++ code should not see old-style casts in the handle constants. */
#if defined(__cplusplus)
#define EGL_CAST(type, value) (static_cast<type>(value))
#else
#define EGL_CAST(type, value) ((type)(value))
#endif

#endif
