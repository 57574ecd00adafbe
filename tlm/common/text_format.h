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

// Energy ("2.345 mJ") and power ("57.500 mW"), in the largest unit that
// keeps the figure at 1 or more (down to micro- and nano-).
inline std::string format_energy(double joules) {
  char buffer[32];
  if (joules >= 1)
    std::snprintf(buffer, sizeof buffer, "%.3f J", joules);
  else if (joules >= 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.3f mJ", joules * 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%.3f uJ", joules * 1e6);
  return buffer;
}

inline std::string format_power(double watts) {
  char buffer[32];
  if (watts >= 1)
    std::snprintf(buffer, sizeof buffer, "%.3f W", watts);
  else if (watts >= 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.3f mW", watts * 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%.3f uW", watts * 1e6);
  return buffer;
}

}  // namespace tessera
