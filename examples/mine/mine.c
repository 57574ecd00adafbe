/* mine: a tessera application in C. A fan of triangles (a hexagon unless
 * --sides says otherwise) with a colour per vertex turns a few degrees each
 * frame. soc_sim decides how many frames are drawn, so the loop never ends.
 *
 * With --roi FIRST:LAST, frames FIRST to LAST - 1 are its region of
 * interest (tessera/roi.h): stats.json's "roi" reports them apart.
 *
 *   soc_sim --app ./libmine.so --frames 10 [-- --sides N] [--roi FIRST:LAST] */
#include <EGL/egl.h>
#include <GLES/gl.h>
#include <tessera/app.h>
#include <tessera/roi.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MIN_SIDES = 3, MAX_SIDES = 64 };

static const float DEGREES_PER_FRAME = 7.5f;
static const float PI = 3.14159265f;

/* What the arguments after "--" ask for. */
struct options {
  int sides;
  /* The region of interest: frames roi_first to roi_last - 1 (none when equal). */
  long roi_first, roi_last;
};

static int usage(const char* problem, const char* argument) {
  fprintf(stderr, "mine: %s%s%s (usage: [--sides N] [--roi FIRST:LAST])\n", problem, argument ? " " : "",
          argument ? argument : "");
  return 0;
}

/* "--sides N" and "--roi FIRST:LAST". */
static int parse_arguments(int argc, char** argv, struct options* options) {
  options->sides = 6;
  options->roi_first = options->roi_last = 0;
  for (int i = 1; i < argc; ++i) {
    const int sides = strcmp(argv[i], "--sides") == 0, roi = strcmp(argv[i], "--roi") == 0;
    if (!sides && !roi) return usage("unknown argument", argv[i]);
    if (i + 1 == argc) {
      if (sides) {
        fprintf(stderr, "mine: --sides needs a number from %d to %d\n", MIN_SIDES, MAX_SIDES);
        return 0;
      }
      return usage("--roi needs two frame numbers", NULL);
    }
    char* end = NULL;
    const char* value = argv[++i];
    if (sides) {
      const long n = strtol(value, &end, 10);
      if (*value == '\0' || *end != '\0' || n < MIN_SIDES || n > MAX_SIDES) {
        fprintf(stderr, "mine: --sides must be a number from %d to %d, not '%s'\n", MIN_SIDES, MAX_SIDES, value);
        return 0;
      }
      options->sides = (int)n;
      continue;
    }
    options->roi_first = strtol(value, &end, 10);
    if (end == value || *end != ':') return usage("--roi takes FIRST:LAST, not", value);
    const char* last = end + 1;
    options->roi_last = strtol(last, &end, 10);
    if (*last == '\0' || *end != '\0' || options->roi_first < 0 || options->roi_last < options->roi_first)
      return usage("--roi takes frame numbers FIRST:LAST with 0 <= FIRST <= LAST, not", value);
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
  struct options options;
  if (!parse_arguments(argc, argv, &options)) return 2;
  const int sides = options.sides;

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

  for (long frame = 0;; ++frame) {
    /* The region of interest holds frames roi_first to roi_last - 1: from
     * before the first's drawing to after the last's eglSwapBuffers. */
    if (options.roi_first != options.roi_last) {
      if (frame == options.roi_first) tessera_roi_begin();
      if (frame == options.roi_last) tessera_roi_end();
    }
    glClear(GL_COLOR_BUFFER_BIT);
    glLoadIdentity();
    glRotatef(DEGREES_PER_FRAME * (float)frame, 0.0f, 0.0f, 1.0f);
    glDrawArrays(GL_TRIANGLE_FAN, 0, sides + 2);
    eglSwapBuffers(display, surface);
  }
}
