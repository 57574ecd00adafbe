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
// (soc_sim finds an application by name, built-in or not, and runs it:
// tools/soc_sim/launch/app_loading.h.)

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
int study_forward_texture_app(AppEnvironment& env);

}  // namespace tessera
