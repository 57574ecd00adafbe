#include "gl/runtime.h"

#include "gl/frame_phases.h"

#include <stdexcept>
#include <string>

namespace tessera::gl {

namespace {
AppEnvironment* g_environment = nullptr;
uint32_t g_heap_next = 0;
}  // namespace

void set_environment(AppEnvironment* env) {
  g_environment = env;
  g_heap_next = env ? env->heap_base : 0;
  phase_clock().start(env != nullptr ? env->host : nullptr);
}

AppEnvironment& environment() {
  if (!g_environment) throw std::logic_error("GL driver used with no application environment");
  return *g_environment;
}

uint32_t allocate(uint32_t bytes, uint32_t alignment) {
  AppEnvironment& env = environment();
  const uint64_t start = (static_cast<uint64_t>(g_heap_next) + alignment - 1) / alignment * alignment;
  if (start + bytes > env.heap_end)
    throw std::runtime_error("GL driver: out of system memory allocating " + std::to_string(bytes) + " bytes (heap " +
                             std::to_string(env.heap_end - env.heap_base) + " bytes; raise mem.size_mib)");
  g_heap_next = static_cast<uint32_t>(start + bytes);
  return static_cast<uint32_t>(start);
}

}  // namespace tessera::gl
