/* Compiles a typical ES 1.1 + EGL start-up and draw in C against tessera's
 * headers only (no Khronos header is on the include path), and checks the
 * type sizes the specifications fix. Built as an object library: it is
 * never linked, so the entry points need not exist yet. */
#include <EGL/egl.h>
#include <GLES/gl.h>
#include <GLES/glext.h>
#include <KHR/khrplatform.h>
#include <stddef.h>

#if !defined(TESSERA_GLES_GL_H) || !defined(TESSERA_EGL_EGL_H) || !defined(TESSERA_GLES_GLEXT_H) || \
    !defined(TESSERA_KHR_KHRPLATFORM_H)
#error "the Khronos headers shadowed ours: check the include path"
#endif
#ifndef GL_OES_read_format
#error "<GLES/glext.h> must declare the extensions the driver implements"
#endif

_Static_assert(sizeof(GLfloat) == 4, "GLfloat is IEEE single precision");
_Static_assert(sizeof(GLfixed) == 4 && sizeof(GLclampx) == 4, "GLfixed is S15.16");
_Static_assert(sizeof(GLbyte) == 1 && sizeof(GLubyte) == 1 && sizeof(GLboolean) == 1, "8-bit types");
_Static_assert(sizeof(GLshort) == 2 && sizeof(GLushort) == 2, "16-bit types");
_Static_assert(sizeof(GLint) == 4 && sizeof(GLuint) == 4 && sizeof(GLsizei) == 4, "32-bit types");
_Static_assert(sizeof(GLenum) == 4 && sizeof(GLbitfield) == 4, "32-bit enums");
_Static_assert(sizeof(GLintptr) == sizeof(void*) && sizeof(GLsizeiptr) == sizeof(void*), "pointer-sized");
_Static_assert(sizeof(EGLint) == 4 && sizeof(EGLBoolean) == 4 && sizeof(EGLenum) == 4, "EGL 32-bit types");
_Static_assert(sizeof(khronos_uint64_t) == 8 && sizeof(khronos_int64_t) == 8, "64-bit Khronos types");
_Static_assert(sizeof(khronos_intptr_t) == sizeof(void*) && sizeof(khronos_usize_t) == sizeof(size_t),
               "pointer-sized Khronos types");
_Static_assert(sizeof(khronos_boolean_enum_t) == 4, "Khronos enums are 32 bits");

int tessera_header_check_draw(void);

int tessera_header_check_draw(void) {
  static const EGLint config_attributes[] = {EGL_RED_SIZE,
                                             5,
                                             EGL_GREEN_SIZE,
                                             6,
                                             EGL_BLUE_SIZE,
                                             5,
                                             EGL_DEPTH_SIZE,
                                             16,
                                             EGL_SURFACE_TYPE,
                                             EGL_WINDOW_BIT,
                                             EGL_RENDERABLE_TYPE,
                                             EGL_OPENGL_ES_BIT,
                                             EGL_NONE};
  static const GLfloat triangle[] = {-1.0f, -1.0f, 0.0f, 1.0f, -1.0f, 0.0f, 0.0f, 1.0f, 0.0f};
  static const GLubyte colours[] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255};
  static const GLfloat light_position[] = {0.0f, 0.0f, 1.0f, 0.0f};
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  EGLint major = 0, minor = 0, count = 0, width = 0;
  EGLConfig config;
  EGLSurface surface;
  EGLContext context;
  GLuint texture = 0;
  int frame;

  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) return eglGetError();
  eglBindAPI(EGL_OPENGL_ES_API);
  if (!eglChooseConfig(display, config_attributes, &config, 1, &count) || count == 0) return EGL_BAD_CONFIG;
  eglGetConfigAttrib(display, config, EGL_BUFFER_SIZE, &width);
  surface = eglCreateWindowSurface(display, config, (EGLNativeWindowType)0, NULL);
  context = eglCreateContext(display, config, EGL_NO_CONTEXT, NULL);
  if (surface == EGL_NO_SURFACE || context == EGL_NO_CONTEXT) return eglGetError();
  eglMakeCurrent(display, surface, surface, context);
  eglSwapInterval(display, 1);
  (void)eglQueryString(display, EGL_VENDOR);
  (void)glGetString(GL_RENDERER);
#ifdef GL_OES_read_format
  {
    GLint read_format = 0;
    glGetIntegerv(GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES, &read_format);
  }
#endif

  glViewport(0, 0, 320, 240);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustumf(-1.0f, 1.0f, -0.75f, 0.75f, 1.0f, 10.0f);
  glMatrixMode(GL_MODELVIEW);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glLightfv(GL_LIGHT0, GL_POSITION, light_position);
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  for (frame = 0; frame < 2; ++frame) {
    glClearColor(0.0f, 0.0f, 0.2f, 1.0f);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glLoadIdentity();
    glTranslatef(0.0f, 0.0f, -3.0f);
    glRotatef(10.0f * (GLfloat)frame, 0.0f, 1.0f, 0.0f);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, triangle);
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, colours);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    eglSwapBuffers(display, surface);
  }
  glDeleteTextures(1, &texture);
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, context);
  eglDestroySurface(display, surface);
  eglTerminate(display);
  return (int)glGetError();
}
