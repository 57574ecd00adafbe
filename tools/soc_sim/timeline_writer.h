// soc_sim --timeline: the TimelineSink (tlm/common/timeline.h) that streams
// every event to a Chrome trace-event JSON file as it is given (Perfetto and
// chrome://tracing open it): `{"traceEvents":[...]}`, one event a line,
// times in microseconds to the picosecond, each track a thread of a process
// named after its block. Nothing is kept but the tracks' names and the flows
// waiting for their end, so a long run's timeline costs no memory. The file
// is written whole or not at all (tools/common/output_file.h).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/timeline.h"
#include "output_file.h"

namespace tessera {

// Reads a --timeline-detail value ("frames", "blocks" or "all"); throws
// std::invalid_argument naming the value and the choices.
TimelineDetail parse_timeline_detail(const std::string& text);

class TimelineWriter : public TimelineSink {
 public:
  // Opens `path`; throws naming the file.
  TimelineWriter(const std::string& path, TimelineDetail detail);
  ~TimelineWriter() override;

  unsigned track(const std::string& process, const std::string& thread) override;
  void slice(unsigned track, std::string_view name, const sc_core::sc_time& begin, const sc_core::sc_time& end,
             const TimelineArgs& args) override;
  void instant(unsigned track, std::string_view name, const sc_core::sc_time& when) override;
  void counter(unsigned track, std::string_view name, const sc_core::sc_time& when,
               const TimelineArgs& values) override;
  void flow_from(const std::string& key, unsigned track, const sc_core::sc_time& when) override;
  void flow_to(const std::string& key, unsigned track, const sc_core::sc_time& when) override;

  // Ends the document and puts the file in place; the error that lost it
  // ("" if none): a failed write during the run is kept until here, the
  // simulation is not stopped for it.
  std::string finish();
  uint64_t events() const { return m_events; }
  uint64_t bytes() const { return m_bytes; }

 private:
  // Starts an event of phase `phase` on `track`: `{"ph":"X","pid":..,"tid":..`.
  void open_event(char phase, unsigned track, std::string_view name);
  void append_time(const char* key, const sc_core::sc_time& time);
  void append_args(const TimelineArgs& args);
  void close_event();
  void flush();

  std::unique_ptr<OutputFile> m_file;
  std::string m_error;
  std::string m_buffer;
  uint64_t m_events = 0, m_bytes = 0;
  double m_picoseconds_per_unit;  // of sc_time's resolution
  std::map<std::string, unsigned> m_processes;
  std::map<std::pair<std::string, std::string>, unsigned> m_tracks;
  std::vector<std::pair<unsigned, unsigned>> m_track_ids;  // pid, tid per track
  struct FlowStart {
    uint64_t id;
    unsigned track;
    sc_core::sc_time when;
  };
  std::map<std::string, std::vector<FlowStart>> m_flows;
  uint64_t m_next_flow = 1;
};

}  // namespace tessera
