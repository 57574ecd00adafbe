/* es11_squares: an ordinary OpenGL ES 1.1 program, written the way such
 * programs are for any ES 1.1 implementation: a main, EGL set-up, and the
 * common profile's fixed-point commands. Two squares turn in opposite
 * directions on a dark blue background, a red one on the left and a green
 * one on the right, in a pixel-sized orthographic view.
 *
 * Nothing in it is particular to tessera: built against the tessera SDK
 * (see README.md) it runs on soc_sim, which calls main and ends the run
 * after --frames frames. */
#include <EGL/egl.h>
#include <GLES/gl.h>
#include <GLES/glext.h>

#include <stdio.h>
#include <stdlib.h>

/* 16.16 fixed point, the common profile's GLfixed. */
#define FIXED(x) ((GLfixed)((x)*65536))

#define FRAMES 600

/* A unit square around the origin, as a triangle strip. */
static const GLfixed square[] = {
    FIXED(-1), FIXED(-1), FIXED(1), FIXED(-1), FIXED(-1), FIXED(1), FIXED(1), FIXED(1),
};

/* Draws the unit square scaled to half-size `half` pixels, centred at
 * (x, y) and turned by `degrees`, in the colour (r, g, b). */
static void draw_square(GLfixed x, GLfixed y, GLfixed half, GLfixed degrees, GLfixed r, GLfixed g, GLfixed b) {
  glPushMatrix();
  glTranslatex(x, y, 0);
  glRotatex(degrees, 0, 0, FIXED(1));
  glScalex(half, half, FIXED(1));
  glColor4x(r, g, b, FIXED(1));
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glPopMatrix();
}

int main(int argc, char** argv) {
  EGLDisplay display;
  EGLConfig config;
  EGLSurface surface;
  EGLContext context;
  EGLint major, minor, configs = 0, width = 0, height = 0;
  static const EGLint attributes[] = {EGL_RED_SIZE,
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
  int frame;

  (void)argc;
  display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
    fprintf(stderr, "%s: cannot initialise EGL (0x%x)\n", argv[0], (unsigned)eglGetError());
    return EXIT_FAILURE;
  }
  if (!eglChooseConfig(display, attributes, &config, 1, &configs) || configs < 1) {
    fprintf(stderr, "%s: no RGB565 configuration with a depth buffer\n", argv[0]);
    return EXIT_FAILURE;
  }
  surface = eglCreateWindowSurface(display, config, (EGLNativeWindowType)0, NULL);
  context = eglCreateContext(display, config, EGL_NO_CONTEXT, NULL);
  if (surface == EGL_NO_SURFACE || context == EGL_NO_CONTEXT || !eglMakeCurrent(display, surface, surface, context)) {
    fprintf(stderr, "%s: cannot create the window and context (0x%x)\n", argv[0], (unsigned)eglGetError());
    return EXIT_FAILURE;
  }
  eglQuerySurface(display, surface, EGL_WIDTH, &width);
  eglQuerySurface(display, surface, EGL_HEIGHT, &height);

  printf("EGL %d.%d, %dx%d\n", major, minor, width, height);
  printf("GL_VENDOR     %s\n", (const char*)glGetString(GL_VENDOR));
  printf("GL_RENDERER   %s\n", (const char*)glGetString(GL_RENDERER));
  printf("GL_VERSION    %s\n", (const char*)glGetString(GL_VERSION));
  printf("GL_EXTENSIONS %s\n", (const char*)glGetString(GL_EXTENSIONS));
#ifdef GL_OES_read_format
  {
    GLint format = 0, type = 0;
    glGetIntegerv(GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES, &format);
    glGetIntegerv(GL_IMPLEMENTATION_COLOR_READ_TYPE_OES, &type);
    printf("read format   0x%04x, type 0x%04x\n", (unsigned)format, (unsigned)type);
  }
#endif

  /* One unit is one pixel, the origin at the bottom left. */
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrthox(0, FIXED(width), 0, FIXED(height), FIXED(-1), FIXED(1));
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColorx(0, 0, FIXED(0.5), FIXED(1));
  glShadeModel(GL_FLAT);
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(2, GL_FIXED, 0, square);

  for (frame = 0; frame < FRAMES; ++frame) {
    glClear(GL_COLOR_BUFFER_BIT);
    draw_square(FIXED(width) / 4, FIXED(height) / 2, FIXED(40), FIXED(15) * frame, FIXED(1), 0, 0);
    draw_square(FIXED(width) / 4 * 3, FIXED(height) / 2, FIXED(30), -FIXED(10) * frame, 0, FIXED(1), 0);
    if (glGetError() != GL_NO_ERROR) {
      fprintf(stderr, "%s: GL error in frame %d\n", argv[0], frame);
      return EXIT_FAILURE;
    }
    eglSwapBuffers(display, surface);
  }

  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, context);
  eglDestroySurface(display, surface);
  eglTerminate(display);
  return EXIT_SUCCESS;
}
