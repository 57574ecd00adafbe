// The progress line soc_sim draws on a terminal, as plain functions so that
// tests can check it without a terminal or a simulation: the text for a
// state and a width, the ETA, and which width to use.
#pragma once

#include <string>

#include "common/text_format.h"

namespace tessera {

struct ProgressState {
  unsigned frames_done = 0;
  unsigned frames_total = 0;
  double simulated_seconds = 0;
  double wall_seconds = 0;
};

// soc_sim redraws the line at most once per this many wall seconds (4 times
// a second): often enough to look alive, rarely enough that a terminal that
// keeps the "\r" redraws in its scrollback is not flooded.
constexpr double PROGRESS_REDRAW_SECONDS = 0.25;

// "ETA 1:05" (or "ETA 1:02:05" from an hour): the wall time left if the
// frames still to draw take as long as those drawn so far took on average;
// "ETA --:--" before the first frame.
std::string eta_text(const ProgressState& state);

// The line for a terminal `columns` wide, e.g.
//   [#########...........] frame 12/40  simulated 2.016 s  12.282 s/s  ETA 0:35
// It is exactly columns - 1 characters, padded with spaces: never the last
// column, so the terminal never wraps it, and always the same length, so a
// redraw after "\r" covers all of the previous one. What does not fit goes,
// in this order: the bar, the rate (simulated seconds per wall second), the
// simulated time, the ETA; the frame count is cut as a last resort. Empty
// below 2 columns.
std::string progress_line(const ProgressState& state, unsigned columns);

// The width to draw for: what the terminal reports (TIOCGWINSZ), unless 0;
// else $COLUMNS (`columns_variable`, may be null) if it is a positive
// number; else 80.
unsigned choose_columns(unsigned reported, const char* columns_variable);

}  // namespace tessera
