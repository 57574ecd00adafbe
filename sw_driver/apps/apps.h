// The built-in applications, by name.
#pragma once

#include <functional>
#include <map>
#include <string>

#include "device/app_environment.h"

namespace tessera {

using AppMain = std::function<int(AppEnvironment&)>;

struct AppInfo {
  AppMain main;
  std::string description;
};

const std::map<std::string, AppInfo>& builtin_apps();
// Their names, ", "-separated, for messages.
std::string builtin_app_names();

// The application `name`: a built-in one, an ARM executable (*.elf, on the
// ISS) or a shared library given by its path. With `on_iss`
// (host.model=iss) a built-in one runs cross-compiled on the ISS, from the
// image builtin_iss_image() names, and a shared library is refused. Throws
// std::invalid_argument listing the built-in ones, or naming what is wrong.
// Native only (app_loading.cpp): the driver cross-compiled for the ISS runs
// built-in applications alone.
AppInfo find_app(const std::string& name, bool on_iss = false);
// The ARM executable of every built-in application, beside the running
// program (<its folder>/arm922t/tessera_apps.elf); std::invalid_argument if
// it is missing.
std::string builtin_iss_image();

int pattern_app(AppEnvironment& env);
int calib_add_app(AppEnvironment& env);
int calib_mul_app(AppEnvironment& env);
int calib_display_port_app(AppEnvironment& env);
int calib_operations_app(AppEnvironment& env);
int calib_array_add_app(AppEnvironment& env);
int calib_array_mul_app(AppEnvironment& env);
int calib_array_add_cmem_app(AppEnvironment& env);
int calib_array_mul_cmem_app(AppEnvironment& env);
int calib_ciu_app(AppEnvironment& env);
int unmapped_access_app(AppEnvironment& env);
int stuck_loop_app(AppEnvironment& env);
int crash_app(AppEnvironment& env);
int study_shading_app(AppEnvironment& env);
int study_patches_app(AppEnvironment& env);

}  // namespace tessera
