// Applications written against GL ES 1.1 / EGL: the built-in scenes (each
// runs in the standard EGL loop of scene_main in gl_apps.cpp) and shared
// libraries that export tessera_app_main or, as an ordinary program, main.
#pragma once

#include <string>

#include "device/app_environment.h"
#include "scenes/scene.h"

namespace tessera {

using GlMain = int (*)(int argc, char** argv);

// Runs a GL application on the host: installs the environment for the
// driver, calls `main` with `name` and env.args, and ends normally when
// eglSwapBuffers has shown env.frames frames.
int run_gl_app(AppEnvironment& env, GlMain main, const std::string& name);

// The EGL loop around a built-in scene.
int run_scene_app(AppEnvironment& env, const scenes::Scene& scene);

}  // namespace tessera
