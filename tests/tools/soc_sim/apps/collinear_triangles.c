/* A GL ES 1.1 application for the system tests: triangles whose three
 * vertices are collinear in float, drawn straight and through a rotated
 * perspective view, on a screen cleared to blue. They have no area, so the
 * frames must show nothing but the clear colour. */
#include <EGL/egl.h>
#include <GLES/gl.h>
#include <tessera/app.h>

#include <stdio.h>

/* On y = x / 2 and y = 4 x: halving and multiplying by four only move the
 * exponent, so the points are exactly on their lines in float. Snapping
 * to 1/16 pixel moves them off; with the zero-area test after snapping,
 * the second triangle drew a dotted line of 66 pixels on 320x240 (the
 * conformance run's case, 11 pixels, was of the same kind). */
static const GLfloat COLLINEAR[] = {
    -0.9f, -0.45f, 0.0f, 0.13f, 0.065f, 0.0f, 0.77f, 0.385f, 0.0f,
    -0.2f, -0.8f,  0.0f, 0.21f, 0.84f,  0.0f, 0.22f, 0.88f,  0.0f,
};

int tessera_app_main(int argc, char** argv) {
  (void)argc;
  (void)argv;
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_NONE};
  EGLConfig config;
  EGLint configs = 0;
  if (!eglInitialize(display, NULL, NULL) || !eglChooseConfig(display, wanted, &config, 1, &configs) || configs != 1) {
    fprintf(stderr, "collinear_triangles: no EGL configuration (0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  EGLSurface surface = eglCreateWindowSurface(display, config, (EGLNativeWindowType)0, NULL);
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, NULL);
  if (!eglMakeCurrent(display, surface, surface, context)) {
    fprintf(stderr, "collinear_triangles: EGL set-up failed (0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
  glColor4f(1.0f, 1.0f, 1.0f, 1.0f);
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, COLLINEAR);
  for (;;) {
    glClear(GL_COLOR_BUFFER_BIT);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glMatrixMode(GL_PROJECTION);
    glFrustumf(-1.0f, 1.0f, -0.75f, 0.75f, 1.0f, 10.0f);
    glMatrixMode(GL_MODELVIEW);
    glTranslatef(0.1f, -0.2f, -2.0f);
    glRotatef(37.0f, 0.3f, 1.0f, 0.2f);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    eglSwapBuffers(display, surface);
  }
}
