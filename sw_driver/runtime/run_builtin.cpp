// tessera_runtime_run for the build of every built-in application
// (tessera_apps.elf): the one the launcher named. ARM only.
#include <cstdio>

#include "apps/apps.h"
#include "runtime/runtime.h"

int tessera_runtime_run(tessera::AppEnvironment& env, const tessera::boot_info::BootInfo& boot) {
  const auto& apps = tessera::builtin_apps();
  const auto it = apps.find(boot.app);
  if (it == apps.end()) {
    std::fprintf(stderr, "unknown application '%s' (built-in: %s)\n", boot.app.c_str(),
                 tessera::builtin_app_names().c_str());
    return 2;
  }
  return it->second.main(env);
}
