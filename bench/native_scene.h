// What the native runs of the benchmarks share (bench_arm_native,
// bench_ap_tile_native): the boot loader's memory layout on a NativeHost,
// and a scene run for 2N frames whose frames N..2N-1 are timed by the
// host's presents and reported as one JSON line. No SystemC.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "device/app_environment.h"
#include "host/native_host.h"
#include "scenes/scene.h"

namespace tessera::bench {

// The boot loader's layout on the SoC (Soc::frame_buffer and soc_sim): the
// two frame buffers, page-aligned, at the top of env.memory_bytes, and the
// driver's heap from 4 MiB up to them.
void lay_out_memory(AppEnvironment& env, const NativeDisplay& display);

// Runs `scene` on `env` (env.frames = 2 * frames), then prints one JSON
// line: scene, timed_frames, wall_per_frame_s (frames N..2N-1, from the
// host's presents), first_frame_s, max_rss_kib, and `extra`'s keys.
// Returns 1 with a message naming `program` if the scene fails or shows
// another number of frames.
int run_timed_scene(const char* program, AppEnvironment& env, const NativeHost& host, const scenes::Scene& scene,
                    const std::string& scene_name, unsigned frames, const nlohmann::json& extra = {});

}  // namespace tessera::bench
