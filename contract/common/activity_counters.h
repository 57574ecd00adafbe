// Typed activity counters: named event counts that a block (or the driver
// on the host) keeps while the simulation runs, and that statistics, the
// summary and the energy model read at the end. A counter is declared once,
// by name and description, and then only incremented on the hot path.
// Plain C++, no SystemC.
#pragma once

#include <cstdint>
#include <deque>
#include <string>

namespace tessera {

struct ActivityCounter {
  std::string name;  // dotted: "vertex_cache.hits" becomes {"vertex_cache": {"hits": n}} in JSON
  std::string description;
  uint64_t value = 0;

  ActivityCounter& operator+=(uint64_t count) {
    value += count;
    return *this;
  }
  ActivityCounter& operator++() {
    ++value;
    return *this;
  }
};

class ActivityCounters {
 public:
  // The counter called `name`, created at zero the first time it is asked
  // for. The reference stays valid as long as the set: counters live in a
  // deque, which never moves its elements when it grows.
  ActivityCounter& counter(const std::string& name, const std::string& description) {
    for (ActivityCounter& c : m_counters)
      if (c.name == name) return c;
    return m_counters.push_back({name, description, 0}), m_counters.back();
  }

  // The value of `name`, 0 when no such counter was declared.
  uint64_t value(const std::string& name) const {
    for (const ActivityCounter& c : m_counters)
      if (c.name == name) return c.value;
    return 0;
  }

  const std::deque<ActivityCounter>& all() const { return m_counters; }

 private:
  std::deque<ActivityCounter> m_counters;
};

}  // namespace tessera
