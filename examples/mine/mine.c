/* mine: a tessera application in C. A fan of triangles (a hexagon unless
 * --sides says otherwise) with a colour per vertex turns a few degrees each
 * frame. soc_sim decides how many frames are drawn, so the loop never ends.
 *
 *   soc_sim --app ./libmine.so --frames 10 [-- --sides N] */
#include <EGL/egl.h>
#include <GLES/gl.h>
#include <tessera/app.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MIN_SIDES = 3, MAX_SIDES = 64 };

static const float DEGREES_PER_FRAME = 7.5f;
static const float PI = 3.14159265f;

/* Reads the arguments after "--": only "--sides N". */
static int parse_sides(int argc, char** argv, int* sides) {
  *sides = 6;
  for (int i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--sides") != 0) {
      fprintf(stderr, "mine: unknown argument '%s' (usage: --sides N)\n", argv[i]);
      return 0;
    }
    if (i + 1 == argc) {
      fprintf(stderr, "mine: --sides needs a number from %d to %d\n", MIN_SIDES, MAX_SIDES);
      return 0;
    }
    char* end = NULL;
    const long value = strtol(argv[++i], &end, 10);
    if (*argv[i] == '\0' || *end != '\0' || value < MIN_SIDES || value > MAX_SIDES) {
      fprintf(stderr, "mine: --sides must be a number from %d to %d, not '%s'\n", MIN_SIDES, MAX_SIDES, argv[i]);
      return 0;
    }
    *sides = (int)value;
  }
  return 1;
}

/* A hue wheel: red, green and blue a third of a turn apart. */
static void hue_to_rgb(float turns, GLubyte* rgba) {
  for (int channel = 0; channel < 3; ++channel) {
    const float c = 0.5f + 0.5f * cosf(2.0f * PI * (turns - channel / 3.0f));
    rgba[channel] = (GLubyte)(255.0f * c + 0.5f);
  }
  rgba[3] = 255;
}

int tessera_app_main(int argc, char** argv) {
  int sides;
  if (!parse_sides(argc, argv, &sides)) return 2;

  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, NULL, NULL)) {
    fprintf(stderr, "mine: eglInitialize failed (0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES_BIT, EGL_NONE};
  EGLConfig config;
  EGLint configs = 0;
  if (!eglChooseConfig(display, wanted, &config, 1, &configs) || configs != 1) {
    fprintf(stderr, "mine: no EGL configuration for GL ES 1.x window surfaces\n");
    return 1;
  }
  EGLSurface surface = eglCreateWindowSurface(display, config, (EGLNativeWindowType)0, NULL);
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, NULL);
  if (surface == EGL_NO_SURFACE || context == EGL_NO_CONTEXT || !eglMakeCurrent(display, surface, surface, context)) {
    fprintf(stderr, "mine: EGL set-up failed (0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  EGLint width = 0, height = 0;
  eglQuerySurface(display, surface, EGL_WIDTH, &width);
  eglQuerySurface(display, surface, EGL_HEIGHT, &height);

  /* The centre, then the rim, whose first vertex is repeated to close it. */
  GLfloat positions[(MAX_SIDES + 2) * 2];
  GLubyte colours[(MAX_SIDES + 2) * 4];
  positions[0] = positions[1] = 0.0f;
  colours[0] = colours[1] = colours[2] = colours[3] = 255;
  for (int i = 0; i <= sides; ++i) {
    const float turns = (float)(i % sides) / (float)sides;
    positions[2 * (i + 1)] = 0.8f * cosf(2.0f * PI * turns);
    positions[2 * (i + 1) + 1] = 0.8f * sinf(2.0f * PI * turns);
    hue_to_rgb(turns, &colours[4 * (i + 1)]);
  }

  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  const float aspect = height > 0 ? (float)width / (float)height : 1.0f;
  glOrthof(-aspect, aspect, -1.0f, 1.0f, -1.0f, 1.0f);
  glMatrixMode(GL_MODELVIEW);
  glClearColor(0.1f, 0.1f, 0.15f, 1.0f);
  glShadeModel(GL_SMOOTH);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, positions);
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, colours);

  for (int frame = 0;; ++frame) {
    glClear(GL_COLOR_BUFFER_BIT);
    glLoadIdentity();
    glRotatef(DEGREES_PER_FRAME * (float)frame, 0.0f, 0.0f, 1.0f);
    glDrawArrays(GL_TRIANGLE_FAN, 0, sides + 2);
    eglSwapBuffers(display, surface);
  }
}
