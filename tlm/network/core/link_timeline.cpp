#include "network/core/link_timeline.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace tessera::network {

uint64_t LinkTimeline::earliest_free(uint64_t at, uint64_t length) const {
  if (m_reserved.empty() || m_reserved.back().end <= at) return at;
  uint64_t start = at;
  const auto by_start = [](uint64_t t, const Interval& i) { return t < i.start; };
  // The first interval starting after `at`; the one before it may still
  // run at `at`.
  auto it = std::upper_bound(m_reserved.begin(), m_reserved.end(), start, by_start);
  if (it != m_reserved.begin() && std::prev(it)->end > start) start = std::prev(it)->end;
  while (it != m_reserved.end() && it->start < start + length) {
    start = std::max(start, it->end);
    ++it;
  }
  return start;
}

void LinkTimeline::reserve(uint64_t start, uint64_t length) {
  if (length == 0) return;
  const uint64_t end = start + length;
  m_busy_ps += length;
  m_last_end = std::max(m_last_end, end);
  if (m_reserved.empty() || m_reserved.back().end <= start) {
    if (!m_reserved.empty() && m_reserved.back().end == start)
      m_reserved.back().end = end;
    else
      m_reserved.push_back({start, end});
    return;
  }
  const auto by_start = [](uint64_t t, const Interval& i) { return t < i.start; };
  auto it = std::upper_bound(m_reserved.begin(), m_reserved.end(), start, by_start);
  if ((it != m_reserved.begin() && std::prev(it)->end > start) || (it != m_reserved.end() && it->start < end))
    throw std::logic_error("network: a link reservation overlaps another");
  // Joins its neighbours where they touch, to keep the timeline short.
  const bool joins_before = it != m_reserved.begin() && std::prev(it)->end == start;
  const bool joins_after = it != m_reserved.end() && it->start == end;
  if (joins_before && joins_after) {
    std::prev(it)->end = it->end;
    m_reserved.erase(it);
  } else if (joins_before) {
    std::prev(it)->end = end;
  } else if (joins_after) {
    it->start = start;
  } else {
    m_reserved.insert(it, {start, end});
  }
}

void LinkTimeline::prune(uint64_t now) {
  const auto ended = std::find_if(m_reserved.begin(), m_reserved.end(), [&](const Interval& i) { return i.end > now; });
  m_reserved.erase(m_reserved.begin(), ended);
}

}  // namespace tessera::network
