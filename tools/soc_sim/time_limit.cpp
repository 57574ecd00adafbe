#include "time_limit.h"

#include <string>

#include "progress_line.h"

namespace tessera {

std::string TimeLimit::automatic_rule() {
  return std::to_string(AUTOMATIC_TIME_LIMIT_BASE_MS / 1000) + " s + " +
         std::to_string(AUTOMATIC_TIME_LIMIT_PER_FRAME_MS / 1000) + " s per frame requested";
}

std::string TimeLimit::describe() const {
  const std::string limit = format_duration(static_cast<double>(ms) * 1e-3);
  if (!automatic) return limit + " (sim.time_limit_ms)";
  return limit + " (automatic: " + std::to_string(AUTOMATIC_TIME_LIMIT_BASE_MS / 1000) + " s + " +
         std::to_string(AUTOMATIC_TIME_LIMIT_PER_FRAME_MS / 1000) + " s x " + std::to_string(frames) +
         (frames == 1 ? " frame)" : " frames)");
}

TimeLimit choose_time_limit(uint64_t frames, uint64_t given_ms) {
  if (given_ms > 0) return {given_ms, false, frames};
  return {AUTOMATIC_TIME_LIMIT_BASE_MS + AUTOMATIC_TIME_LIMIT_PER_FRAME_MS * frames, true, frames};
}

}  // namespace tessera
