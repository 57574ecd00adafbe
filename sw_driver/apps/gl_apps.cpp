#include "apps/gl_apps.h"

#include <EGL/egl.h>
#include <GLES/gl.h>

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "costs/host_cost.h"
#include "gl/runtime.h"

namespace tessera {

namespace {

const scenes::Scene* g_scene = nullptr;
HostApi* g_host = nullptr;

// The scene's own code: the rows scene_<name>_init and scene_<name>_frame
// of the measured cost table, where it has them (looked up once).
std::optional<costs::HostCost> scene_row(const scenes::Scene& scene, const char* part) {
  return costs::find_host_cost(std::string("scene_") + scene.name + "_" + part);
}

void charge_scene(const std::optional<costs::HostCost>& row) {
  if (g_host != nullptr && row) costs::charge(*g_host, *row);
}

// A scene's program: EGL set-up, the scene's own set-up, then frames until
// the simulator has seen enough of them.
int scene_main(int argc, char** argv) {
  const scenes::Scene& scene = *g_scene;
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) {
    std::fprintf(stderr, "%s: eglInitialize failed (0x%x)\n", scene.name, static_cast<unsigned>(eglGetError()));
    return 1;
  }
  const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES_BIT, EGL_DEPTH_SIZE, 16,
                           EGL_NONE};
  EGLConfig config;
  EGLint configs = 0;
  if (!eglChooseConfig(display, wanted, &config, 1, &configs) || configs != 1) {
    std::fprintf(stderr, "%s: no EGL configuration with a depth buffer\n", scene.name);
    return 1;
  }
  EGLSurface surface = eglCreateWindowSurface(display, config, static_cast<EGLNativeWindowType>(0), nullptr);
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (surface == EGL_NO_SURFACE || context == EGL_NO_CONTEXT || !eglMakeCurrent(display, surface, surface, context)) {
    std::fprintf(stderr, "%s: EGL set-up failed (0x%x)\n", scene.name, static_cast<unsigned>(eglGetError()));
    return 1;
  }
  EGLint width = 0, height = 0;
  eglQuerySurface(display, surface, EGL_WIDTH, &width);
  eglQuerySurface(display, surface, EGL_HEIGHT, &height);
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string error;
  if (!scene.init(width, height, args, &error)) {
    std::fprintf(stderr, "%s: %s\n", scene.name, error.c_str());
    return 2;
  }
  charge_scene(scene_row(scene, "init"));
  const std::optional<costs::HostCost> frame_row = scene_row(scene, "frame");
  for (int frame = 0;; ++frame) {
    scene.draw(frame);
    charge_scene(frame_row);
    eglSwapBuffers(display, surface);
  }
}

}  // namespace

int run_gl_app(AppEnvironment& env, GlMain main, const std::string& name) {
  gl::set_environment(&env);
  std::vector<std::string> strings;
  strings.push_back(name);
  strings.insert(strings.end(), env.args.begin(), env.args.end());
  std::vector<char*> argv;
  argv.reserve(strings.size() + 1);
  for (auto& s : strings) argv.push_back(s.data());
  argv.push_back(nullptr);
  try {
    return main(static_cast<int>(strings.size()), argv.data());
  } catch (const gl::FramesComplete&) {
    return 0;
  }
}

int run_scene_app(AppEnvironment& env, const scenes::Scene& scene) {
  g_scene = &scene;
  g_host = env.host;
  return run_gl_app(env, scene_main, scene.name);
}

}  // namespace tessera
