// What the simulator hands an application when it starts: the host to run
// on (HostApi alone), how many frames to draw, where the frame buffers and
// the heap are (the boot loader's memory layout), the renderer back end the
// GL driver draws with, and where the driver's statistics and warnings go.
// Nothing of the simulator's own machinery travels here: an ARM executable's
// launcher takes the ISS core and the GDB server apart
// (tools/soc_sim/launch/iss_launcher.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/activity_counters.h"
#include "gl/renderer.h"
#include "host/host_api.h"

namespace tessera {
class Config;
struct AppEnvironment;

// Builds the renderer of the window surface (eglCreateWindowSurface). The
// launcher takes it from the back-end registry (sw_driver/renderers/
// backends.h) by driver.backend; the GL front end only calls it.
using RendererFactory = std::function<std::unique_ptr<gl::Renderer>(AppEnvironment& env)>;

struct AppEnvironment {
  HostApi* host = nullptr;
  unsigned frames = 1;
  uint32_t frame_buffers[2] = {0, 0};
  uint32_t memory_bytes = 0;  // system memory populated from address 0
  // System memory the driver may allocate (textures, depth buffers).
  uint32_t heap_base = 0;
  uint32_t heap_end = 0;
  // Empty for applications that do not use GL; EGL refuses to make a
  // surface without one.
  RendererFactory make_renderer;
  // What that back end's buffers hold, for EGL's configuration, which is
  // chosen before any surface (and so any renderer) exists.
  gl::RendererCapabilities capabilities;
  // The run's configuration, where the back end's make_renderer reads its
  // own keys (backend_entry_points.h, `parameters`). Null where a launcher
  // has none (native benchmarks, unit tests): the back end's defaults.
  const Config* config = nullptr;
  std::vector<std::string> args;
  // The driver's own statistics (vertex cache, ...), kept by the software
  // on the host; soc_sim writes them to stats.json as "driver". May be null.
  ActivityCounters* counters = nullptr;
  // Per-frame figures of the back end (passes, host time split, ...), one
  // call per frame presented, in order: soc_sim puts the i-th call's
  // figures in stats.json's i-th frame record as "driver". May be empty.
  std::function<void(const std::vector<std::pair<std::string, double>>& figures)> frame_statistics;
  // Warnings of the driver (state a back end does not support, ...): soc_sim
  // logs them as the blocks' warnings. Null: they go to standard error.
  std::function<void(const std::string& source, const std::string& message)> warn;
};

}  // namespace tessera
