/* A GL ES 1.1 application for the system tests: with the scissor test on
 * and a box of zero size (glScissor(50, 50, 0, 0)), a clear to red and a
 * white quad over the whole window must change no pixel (ES 1.1 section
 * 4.1.2: the test passes only inside the box, and the box is empty), so the
 * frames show nothing but the blue clear made before the test was on. A box
 * of zero width and one of zero height are both drawn through. */
#include <EGL/egl.h>
#include <GLES/gl.h>
#include <tessera/app.h>

#include <stdio.h>

/* Two triangles covering the window in clip space. */
static const GLfloat QUAD[] = {
    -1.0f, -1.0f, 0.0f, 1.0f, -1.0f, 0.0f, 1.0f, 1.0f, 0.0f, -1.0f, -1.0f, 0.0f, 1.0f, 1.0f, 0.0f, -1.0f, 1.0f, 0.0f,
};

int tessera_app_main(int argc, char** argv) {
  (void)argc;
  (void)argv;
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_NONE};
  EGLConfig config;
  EGLint configs = 0;
  if (!eglInitialize(display, NULL, NULL) || !eglChooseConfig(display, wanted, &config, 1, &configs) || configs != 1) {
    fprintf(stderr, "empty_scissor: no EGL configuration (0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  EGLSurface surface = eglCreateWindowSurface(display, config, (EGLNativeWindowType)0, NULL);
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, NULL);
  if (!eglMakeCurrent(display, surface, surface, context)) {
    fprintf(stderr, "empty_scissor: EGL set-up failed (0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, QUAD);
  glColor4f(1.0f, 1.0f, 1.0f, 1.0f);
  for (;;) {
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    glScissor(50, 50, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glScissor(50, 50, 0, 20);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glScissor(50, 50, 20, 0);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    eglSwapBuffers(display, surface);
  }
}
