#include "apps/apps.h"

#include <stdexcept>

namespace tessera {

const std::map<std::string, AppInfo>& builtin_apps() {
  static const std::map<std::string, AppInfo> apps = {
      {"pattern", {pattern_app, "moving test pattern drawn by the host into the frame buffer (default demo)"}},
      {"calib_add", {calib_add_app, "host calibration: loop of 16-bit additions, memory operands (calibration.md)"}},
      {"calib_mul", {calib_mul_app, "host calibration: loop of 16x8-bit multiplications, memory operands"}},
      {"unmapped_access", {unmapped_access_app, "diagnostic: reads an unmapped address to show the bus error path"}},
  };
  return apps;
}

const AppInfo& find_app(const std::string& name) {
  const auto& apps = builtin_apps();
  auto it = apps.find(name);
  if (it != apps.end()) return it->second;
  std::string known;
  for (const auto& [app_name, info] : apps) known += (known.empty() ? "" : ", ") + app_name;
  throw std::invalid_argument("unknown application '" + name + "' (built-in: " + known + ")");
}

}  // namespace tessera
