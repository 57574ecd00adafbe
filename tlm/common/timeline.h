// What a block did when, for a timeline (soc_sim --timeline: Chrome
// trace-event JSON that Perfetto and chrome://tracing open). A block that
// records is handed a TimelineSink before the simulation starts
// (Block::timeline_to) and keeps a pointer to it; without a timeline the
// pointer stays null and recording costs the test of it, where the block
// already tests whether its VCD signals are traced or folds the two tests
// into one (the host's hot path). The sink knows nothing of the blocks; soc_sim's
// writer (tools/soc_sim/timeline_writer.*) streams what it is given to the
// file, so a long run's timeline is never held in memory.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <systemc>

namespace tessera {

// How much a timeline holds, each level everything of the one before:
// frames (the display's frames and vertical blanks, the power and bus
// counters), blocks (every block's runs: the host's activity, array
// programs, DMA chains and descriptors, rasterizer runs, CIU bursts) and all
// (the array's stages, the host's busy and stalled time apart, the CIU's
// single accesses, counters every power window).
enum class TimelineDetail : uint8_t { frames, blocks, all };

// Figures attached to an event (its args) or a counter's values, by name.
using TimelineArgs = std::vector<std::pair<std::string_view, double>>;

class TimelineSink {
 public:
  explicit TimelineSink(TimelineDetail detail) : m_detail(detail) {}
  virtual ~TimelineSink() = default;
  TimelineSink(const TimelineSink&) = delete;
  TimelineSink& operator=(const TimelineSink&) = delete;

  TimelineDetail detail() const { return m_detail; }
  // Whether events of `level` are recorded.
  bool records(TimelineDetail level) const { return level <= m_detail; }

  // A track: the row `thread` of the group `process` (a block's full name,
  // so that the cluster's nodes each have their own). The same names give
  // the same track.
  virtual unsigned track(const std::string& process, const std::string& thread) = 0;
  // Something that lasted from `begin` to `end`. A track's slices follow
  // each other or nest; they may be given out of time order (a loosely
  // timed block knows an interval before the kernel gets there).
  virtual void slice(unsigned track, std::string_view name, const sc_core::sc_time& begin, const sc_core::sc_time& end,
                     const TimelineArgs& args = {}) = 0;
  virtual void instant(unsigned track, std::string_view name, const sc_core::sc_time& when) = 0;
  // Counter values from `when` until the counter's next values.
  virtual void counter(unsigned track, std::string_view name, const sc_core::sc_time& when,
                       const TimelineArgs& values) = 0;
  // A flow arrow from the slice of `track` around `when` to the slice that
  // next calls flow_to with the same key (several flow_from before one
  // flow_to all point at it; a flow_to without one before draws nothing).
  // The key names what is handed over (cmem_flow_key below).
  virtual void flow_from(const std::string& key, unsigned track, const sc_core::sc_time& when) = 0;
  virtual void flow_to(const std::string& key, unsigned track, const sc_core::sc_time& when) = 0;

 private:
  TimelineDetail m_detail;
};

// The flow key of an array's CMEM (TimelineSink::flow_from): what the DMA
// writes there, the array's next program reads.
inline std::string cmem_flow_key(const sc_core::sc_object& array) {
  return std::string(array.name()) + ".cmem";
}

}  // namespace tessera
