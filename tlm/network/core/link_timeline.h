// One directed link's reservations (README.md, "Timing"): disjoint
// [start, end) intervals in picoseconds, sorted. Calls come out of time
// order under temporal decoupling, so a reservation may fill a gap before
// intervals reserved earlier (first fit), as the SoC bus's timeline does
// (tlm/bus/ahb_bus.cpp). Requests come nearly in time order, so almost
// every reservation follows or extends the last interval, which is tried
// first; intervals that ended before the kernel's time are pruned. Plain C++.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera::network {

class LinkTimeline {
 public:
  // The earliest start >= `at` at which [start, start + length) is free.
  uint64_t earliest_free(uint64_t at, uint64_t length) const;
  // Reserves [start, start + length), which must be free (earliest_free).
  void reserve(uint64_t start, uint64_t length);
  // Drops the intervals that ended at or before `now`: nothing can be
  // reserved in the past.
  void prune(uint64_t now);

  uint64_t busy_ps() const { return m_busy_ps; }
  // The end of the last reservation (0 if none).
  uint64_t last_end() const { return m_last_end; }
  size_t intervals() const { return m_reserved.size(); }

 private:
  struct Interval {
    uint64_t start;
    uint64_t end;
  };
  std::vector<Interval> m_reserved;
  uint64_t m_busy_ps = 0;
  uint64_t m_last_end = 0;
};

}  // namespace tessera::network
