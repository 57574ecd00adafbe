// Where the host's time goes in the array back ends (ap-tile, ap-pixel):
// computing (set-up, scan conversion, packing, texturing), writing to the
// array, reading from it, waiting for its programs, and writing the frame
// out; and a guard that charges the host time of a scope to one of them.
// Header-only: the back end that uses it links the host.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "device/app_environment.h"

#include "common/activity_counters.h"
#include "host/host_api.h"

namespace tessera::renderers {

// Seconds of host time.
struct HostTime {
  double compute = 0, array_write = 0, array_read = 0, array_wait = 0, frame_out = 0;
};

// Adds the host time between its construction and its end to `total`.
class TimedScope {
 public:
  TimedScope(HostApi& host, double& total) : m_host(host), m_total(total), m_start(host.now_seconds()) {}
  ~TimedScope() { m_total += m_host.now_seconds() - m_start; }
  TimedScope(const TimedScope&) = delete;
  TimedScope& operator=(const TimedScope&) = delete;

 private:
  HostApi& m_host;
  double& m_total;
  double m_start;
};

// The split as counters <prefix>.host_compute_ns ... host_frame_out_ns.
inline void publish_host_time(ActivityCounters& counters, const std::string& prefix, const HostTime& time,
                              const char* compute_description) {
  auto set = [&](const char* name, const char* description, double seconds) {
    counters.counter(prefix + "." + name, description).value = static_cast<uint64_t>(std::llround(seconds * 1e9));
  };
  set("host_compute_ns", compute_description, time.compute);
  set("host_write_ns", "host time writing the array (CIU accesses, or building DMA descriptors and waiting for them)",
      time.array_write);
  set("host_read_ns", "host time reading results back from the array (CIU accesses, or waiting for the DMA)",
      time.array_read);
  set("host_wait_ns", "host time waiting for the array's programs", time.array_wait);
  set("host_frame_out_ns", "host time showing the frame (the copy to the display port, or the swap)", time.frame_out);
}

// A back end's figures per frame (AppEnvironment::frame_statistics): at each
// present, the change of each running total since the previous present,
// and figures that are already per frame as they are.
class FrameFigures {
 public:
  using Figures = std::vector<std::pair<std::string, double>>;

  // The change of the running total `name` since the last emit.
  double change(const std::string& name, double total) const {
    const auto it = m_previous.find(name);
    return it == m_previous.end() ? total : total - it->second;
  }

  void emit(AppEnvironment& env, const Figures& totals, Figures per_frame) {
    for (const auto& [name, total] : totals) {
      double& previous = m_previous[name];
      per_frame.emplace_back(name, total - previous);
      previous = total;
    }
    if (env.frame_statistics) env.frame_statistics(per_frame);
  }

 private:
  std::map<std::string, double> m_previous;
};

// The host-time split as running totals in nanoseconds, for FrameFigures.
inline void add_host_time(FrameFigures::Figures& totals, const HostTime& time) {
  totals.emplace_back("host_compute_ns", time.compute * 1e9);
  totals.emplace_back("host_write_ns", time.array_write * 1e9);
  totals.emplace_back("host_read_ns", time.array_read * 1e9);
  totals.emplace_back("host_wait_ns", time.array_wait * 1e9);
  totals.emplace_back("host_frame_out_ns", time.frame_out * 1e9);
}

}  // namespace tessera::renderers
