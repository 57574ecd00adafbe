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
#include "costs/host_cost.h"
#include "host/host_api.h"

namespace tessera::renderers {

// Where a scope's host time goes; each is also a bucket of the measured
// cost table's meter (costs/host_cost.h), so that the units charged in it
// can be fitted to its time.
enum class HostSplit : unsigned { compute, array_write, array_read, array_wait, frame_out, count_ };
static_assert(static_cast<unsigned>(HostSplit::count_) == costs::SPLIT_BUCKETS);

// Host time in whole host cycles (HostApi::now_cycles): integers, as the
// ARM922T driver keeps it.
struct HostTime {
  uint64_t compute = 0, array_write = 0, array_read = 0, array_wait = 0, frame_out = 0;
  uint64_t& at(HostSplit split) {
    switch (split) {
      case HostSplit::array_write: return array_write;
      case HostSplit::array_read: return array_read;
      case HostSplit::array_wait: return array_wait;
      case HostSplit::frame_out: return frame_out;
      default: return compute;
    }
  }
};

// Counts the measured cost table's charges in `split` while it lasts (and
// in the split open before it again afterwards).
class CostSplit {
 public:
  explicit CostSplit(HostSplit split)
      : m_previous(costs::set_split_bucket(costs::PHASE_BUCKETS + static_cast<unsigned>(split))) {}
  ~CostSplit() { costs::set_split_bucket(m_previous); }
  CostSplit(const CostSplit&) = delete;
  CostSplit& operator=(const CostSplit&) = delete;

 private:
  unsigned m_previous;
};

// Adds the host time between its construction and its end to `split` of
// `time`, and counts the charges made meanwhile in that split.
class TimedScope {
 public:
  TimedScope(HostApi& host, HostTime& time, HostSplit split)
      : m_host(host), m_total(time.at(split)), m_split(split), m_start(host.now_cycles()) {}
  // On the ISS reading the clock is the program's own work, about one read's
  // worth inside the scope: natively a row of the measured cost table.
  ~TimedScope() {
    costs::charge(m_host, costs::HostCost::host_clock_read);
    m_total += m_host.now_cycles() - m_start;
  }
  TimedScope(const TimedScope&) = delete;
  TimedScope& operator=(const TimedScope&) = delete;

 private:
  HostApi& m_host;
  uint64_t& m_total;
  CostSplit m_split;
  uint64_t m_start;
};

// Host cycles in nanoseconds, at the host's clock.
inline double host_ns(HostApi& host, uint64_t cycles) {
  return static_cast<double>(cycles) * 1e9 / host.clock_hz();
}

// The split as counters <prefix>.host_compute_ns ... host_frame_out_ns.
inline void publish_host_time(ActivityCounters& counters, const std::string& prefix, HostApi& host,
                              const HostTime& time, const char* compute_description) {
  auto set = [&](const char* name, const char* description, uint64_t cycles) {
    counters.counter(prefix + "." + name, description).value =
        static_cast<uint64_t>(std::llround(host_ns(host, cycles)));
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
inline void add_host_time(FrameFigures::Figures& totals, HostApi& host, const HostTime& time) {
  totals.emplace_back("host_compute_ns", host_ns(host, time.compute));
  totals.emplace_back("host_write_ns", host_ns(host, time.array_write));
  totals.emplace_back("host_read_ns", host_ns(host, time.array_read));
  totals.emplace_back("host_wait_ns", host_ns(host, time.array_wait));
  totals.emplace_back("host_frame_out_ns", host_ns(host, time.frame_out));
}

}  // namespace tessera::renderers
