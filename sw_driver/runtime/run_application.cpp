// tessera_runtime_run for an application of its own: entered at
// tessera_app_main (or, failing that, at main) with the arguments the
// launcher passed, in the standard EGL set-up of run_gl_app. ARM only.
#include <cstdio>

#include "apps/gl_apps.h"
#include "runtime/runtime.h"

extern "C" tessera::GlMain tessera_application_entry();

int tessera_runtime_run(tessera::AppEnvironment& env, const tessera::boot_info::BootInfo& boot) {
  const tessera::GlMain entry = tessera_application_entry();
  if (entry == nullptr) {
    std::fprintf(stderr, "%s: defines neither tessera_app_main nor main\n", boot.app.c_str());
    return 2;
  }
  return tessera::run_gl_app(env, entry, boot.app);
}
