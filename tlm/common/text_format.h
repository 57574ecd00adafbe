#pragma once

#include <cstdio>
#include <string>

namespace tessera {

// How tessera's reports word a duration ("13.874 ms", "5.208 us", "1.250 s")
// and a fraction ("4.6%"): the summary, the progress line and the messages.
// Plain C++, header-only, so tools without a simulation can use it.
inline std::string format_duration(double seconds) {
  char buffer[32];
  if (seconds >= 1)
    std::snprintf(buffer, sizeof buffer, "%.3f s", seconds);
  else if (seconds >= 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.3f ms", seconds * 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%.3f us", seconds * 1e6);
  return buffer;
}

inline std::string format_percent(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f%%", fraction * 100);
  return buffer;
}

}  // namespace tessera
