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

// A figure in `unit` (J, W) with the largest prefix that keeps it at 1 or
// more, down to micro: "2.345 mJ", "57.500 mW".
inline std::string format_scaled(double value, const char* unit) {
  char buffer[32];
  if (value >= 1)
    std::snprintf(buffer, sizeof buffer, "%.3f %s", value, unit);
  else if (value >= 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.3f m%s", value * 1e3, unit);
  else
    std::snprintf(buffer, sizeof buffer, "%.3f u%s", value * 1e6, unit);
  return buffer;
}

inline std::string format_energy(double joules) {
  return format_scaled(joules, "J");
}

inline std::string format_power(double watts) {
  return format_scaled(watts, "W");
}

}  // namespace tessera
