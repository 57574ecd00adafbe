#include "progress_line.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace tessera {

namespace {

constexpr unsigned MIN_BAR_CELLS = 10;  // a shorter bar says nothing the frame count does not
constexpr unsigned MAX_BAR_CELLS = 30;
constexpr unsigned DEFAULT_COLUMNS = 80;
constexpr unsigned MAX_COLUMNS = 1000;  // $COLUMNS beyond this is a mistake, not a terminal

}  // namespace

std::string eta_text(const ProgressState& state) {
  if (state.frames_done == 0 || state.frames_total == 0) return "ETA --:--";
  const unsigned left = state.frames_total > state.frames_done ? state.frames_total - state.frames_done : 0;
  const double seconds = state.wall_seconds / state.frames_done * left;
  const auto whole = static_cast<unsigned long long>(std::llround(std::max(0.0, seconds)));
  char buffer[48];
  if (whole >= 3600)
    std::snprintf(buffer, sizeof buffer, "ETA %llu:%02llu:%02llu", whole / 3600, whole / 60 % 60, whole % 60);
  else
    std::snprintf(buffer, sizeof buffer, "ETA %llu:%02llu", whole / 60, whole % 60);
  return buffer;
}

std::string progress_line(const ProgressState& state, unsigned columns) {
  if (columns < 2) return "";
  const size_t width = columns - 1;

  const std::string frames = "frame " + std::to_string(state.frames_done) + "/" + std::to_string(state.frames_total);
  const std::string simulated = "simulated " + format_duration(state.simulated_seconds);
  const double rate = state.wall_seconds > 0 ? state.simulated_seconds / state.wall_seconds : 0;
  const std::string rate_text = format_duration(rate) + "/s";
  const std::string eta = eta_text(state);

  // Which parts fit, taken in order of importance.
  size_t length = frames.size();
  const auto fits = [&](const std::string& part) {
    if (length + 2 + part.size() > width) return false;
    length += 2 + part.size();
    return true;
  };
  const bool with_eta = fits(eta);
  const bool with_simulated = with_eta && fits(simulated);
  const bool with_rate = with_simulated && fits(rate_text);

  std::string text = frames;
  if (with_simulated) text += "  " + simulated;
  if (with_rate) text += "  " + rate_text;
  if (with_eta) text += "  " + eta;

  std::string line;
  if (text.size() + 1 + 2 + MIN_BAR_CELLS <= width) {
    const size_t cells = std::min<size_t>(MAX_BAR_CELLS, width - text.size() - 1 - 2);
    const size_t filled =
        state.frames_total ? std::min<size_t>(cells, size_t{state.frames_done} * cells / state.frames_total) : 0;
    line = "[" + std::string(filled, '#') + std::string(cells - filled, '.') + "] ";
  }
  line += text;
  line.resize(width, ' ');
  return line;
}

unsigned choose_columns(unsigned reported, const char* columns_variable) {
  if (reported > 0) return reported;
  if (columns_variable) {
    char* end = nullptr;
    const long value = std::strtol(columns_variable, &end, 10);
    if (end != columns_variable && *end == '\0' && value > 0 && value <= long{MAX_COLUMNS})
      return static_cast<unsigned>(value);
  }
  return DEFAULT_COLUMNS;
}

}  // namespace tessera
