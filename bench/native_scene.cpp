#include "native_scene.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "apps/gl_apps.h"

namespace tessera::bench {

void lay_out_memory(AppEnvironment& env, const NativeDisplay& display) {
  const uint64_t frame_bytes = uint64_t{display.width} * display.height * bytes_per_pixel(display.format);
  const uint64_t frame = (frame_bytes + 4095) / 4096 * 4096;
  env.frame_buffers[0] = static_cast<uint32_t>(env.memory_bytes - 2 * frame);
  env.frame_buffers[1] = static_cast<uint32_t>(env.memory_bytes - frame);
  env.heap_base = std::min<uint32_t>(4u << 20, env.frame_buffers[0]);
  env.heap_end = env.frame_buffers[0];
}

int run_timed_scene(const char* program, AppEnvironment& env, const NativeHost& host, const scenes::Scene& scene,
                    const std::string& scene_name, unsigned frames, const nlohmann::json& extra) {
  env.frames = 2 * frames;
  const auto start = NativeHost::Clock::now();
  const int status = run_scene_app(env, scene);
  const auto& presents = host.present_times();
  if (status != 0 || presents.size() != 2 * frames) {
    std::cerr << program << ": scene '" << scene_name << "' ended with status " << status << " after "
              << presents.size() << " of " << 2 * frames << " frames\n";
    return 1;
  }
  auto seconds = [](auto from, auto to) { return std::chrono::duration<double>(to - from).count(); };
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  nlohmann::json result = {
      {"scene", scene_name},
      {"timed_frames", frames},
      {"wall_per_frame_s", seconds(presents[frames - 1], presents.back()) / frames},
      {"cpu_per_frame_s", (host.present_cpu_seconds().back() - host.present_cpu_seconds()[frames - 1]) / frames},
      {"first_frame_s", seconds(start, presents.front())},
      {"max_rss_kib", usage.ru_maxrss}};
  for (const auto& [key, value] : extra.items()) result[key] = value;
  std::printf("%s\n", result.dump().c_str());
  return 0;
}

}  // namespace tessera::bench
