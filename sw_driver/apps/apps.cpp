#include "apps/apps.h"

#include <stdexcept>

#include "apps/gl_apps.h"
#include "scenes/scene.h"

namespace tessera {

const std::map<std::string, AppInfo>& builtin_apps() {
  static const std::map<std::string, AppInfo> apps = {
      {"pattern", {pattern_app, "moving test pattern drawn by the host straight into the frame buffer (no GL)"}},
      {"calib_add", {calib_add_app, "host calibration: loop of 16-bit additions, memory operands (calibration.md)"}},
      {"calib_mul", {calib_mul_app, "host calibration: loop of 16x8-bit multiplications, memory operands"}},
      {"calib_display_port",
       {calib_display_port_app,
        "display port calibration: the host copies one 192x144 16-bit frame to the display port "
        "(--set display.width=192 --set display.height=144)"}},
      {"calib_operations",
       {calib_operations_app,
        "host calibration: cycles per operation class of the cost model (soft-float add, multiply, divide, "
        "square root, compare, conversion; a function call and return); on the ISS, the measurement behind "
        "host.cycles.f* and host.cycles.call (docs/calibration.md)"}},
      {"calib_array_add",
       {calib_array_add_app, "array calibration: 16-bit addition at register level (calibration.md)"}},
      {"calib_array_mul",
       {calib_array_mul_app, "array calibration: signed 16 x 8-bit multiplication at register level"}},
      {"calib_array_add_cmem",
       {calib_array_add_cmem_app, "array calibration: 16-bit addition of CMEM operands stored back, one pass"}},
      {"calib_array_mul_cmem",
       {calib_array_mul_cmem_app,
        "array calibration: 16 x 8-bit multiplication of CMEM operands stored back, one pass"}},
      {"calib_ciu", {calib_ciu_app, "CIU calibration: the host's 32-bit CMEM writes and reads through the CIU"}},
      {"study_shading",
       {study_shading_app,
        "the study's pixel shading: single-pixel shades, each its own attribute set, on the host (--backend arm) "
        "or the array (--backend ap-pixel, ap.pixel.program); -- --shades N (default 192000), --attributes N "
        "(1 to 7; default 7, 6 with ap.pixel.program=study as the study measured; tuned takes 7 only)"}},
      {"study_patches",
       {study_patches_app,
        "the study's patch sizes: square and line patches of 1 to 40 pixels sharing an attribute set, on the host "
        "(--backend arm) or the array (--backend ap-pixel, ap.pixel.block, ap.pixel.program); -- --max-pixels N"}},
      {"study_forward_texture",
       {study_forward_texture_app,
        "van Sinten's two-pass forward texture mapping on the host (--backend arm): a checkerboard warped onto the "
        "display under a perspective matrix with Eq. 6's prefiltered resampling, shown grey; -- --texture-size N, "
        "--filter box|tent, --filter-width F (1 to 8), --matrix A,B,C,D,E,F,G,H,I, --array-factors computed|table "
        "(on ap-tile or ap-pixel: the lookup table, array.features.lut)"}},
      {"unmapped_access", {unmapped_access_app, "diagnostic: reads an unmapped address to show the bus error path"}},
      {"stuck_loop",
       {stuck_loop_app,
        "diagnostic: shows one frame, then computes forever without calling the host model (sim.stall_limit_s "
        "ends it)"}},
      {"crash",
       {crash_app, "diagnostic: shows one frame, then writes through a null pointer (a crashing application)"}},
  };
  static const std::map<std::string, AppInfo> with_scenes = [] {
    std::map<std::string, AppInfo> all = apps;
    for (const scenes::Scene& scene : scenes::all_scenes())
      all[scene.name] = {[&scene](AppEnvironment& env) { return run_scene_app(env, scene); },
                         std::string(scene.description) + " (GL ES 1.1 scene)"};
    return all;
  }();
  return with_scenes;
}

std::string builtin_app_names() {
  std::string names;
  for (const auto& [name, info] : builtin_apps()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

}  // namespace tessera
