// soc_sim's simulated-time limit. A limit the user gives (sim.time_limit_ms
// in a --config file or a --set) is taken as it is; without one the limit
// follows the run, generous per frame requested, so that a long run is not
// cut short by a fixed default (60 s stopped `--frames 400` of the teapot
// after 355 frames) while a run that hangs still ends.
#pragma once

#include <cstdint>
#include <string>

namespace tessera {

// The automatic limit: 60 s, plus 10 s per frame requested. The slowest
// built-in frame is the teapot's on the arm back end, 168 ms at 320x240;
// a fill-bound scene at the largest display (2048x2048) takes about 1 s.
constexpr uint64_t AUTOMATIC_TIME_LIMIT_BASE_MS = 60000;
constexpr uint64_t AUTOMATIC_TIME_LIMIT_PER_FRAME_MS = 10000;

struct TimeLimit {
  uint64_t ms = 0;
  bool automatic = false;
  uint64_t frames = 0;  // requested; what the automatic limit was computed for

  // "90.000 s (automatic: 60 s + 10 s x 3 frames)" or "20.000 ms (sim.time_limit_ms)".
  std::string describe() const;
  // The rule, for --help and messages: "60 s + 10 s per frame requested".
  static std::string automatic_rule();
};

// `given_ms` is the value of sim.time_limit_ms when the user gave one, else 0.
TimeLimit choose_time_limit(uint64_t frames, uint64_t given_ms);

}  // namespace tessera
