#include "timeline_writer.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tessera {

using sc_core::sc_time;

namespace {

constexpr size_t FLUSH_BYTES = 1 << 20;

void append_string(std::string& out, std::string_view text) {
  out += '"';
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
      out += escaped;
    } else {
      out += c;
    }
  }
  out += '"';
}

void append_number(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  out += text;
}

}  // namespace

TimelineDetail parse_timeline_detail(const std::string& text) {
  if (text == "frames") return TimelineDetail::frames;
  if (text == "blocks") return TimelineDetail::blocks;
  if (text == "all") return TimelineDetail::all;
  throw std::invalid_argument("unknown timeline detail '" + text + "': choose frames, blocks or all");
}

TimelineWriter::TimelineWriter(const std::string& path, TimelineDetail detail)
    : TimelineSink(detail),
      m_file(std::make_unique<OutputFile>(path)),
      m_picoseconds_per_unit(sc_core::sc_get_time_resolution().to_seconds() * 1e12) {
  m_buffer = "{\"displayTimeUnit\":\"ns\",\"traceEvents\":[\n";
}

TimelineWriter::~TimelineWriter() = default;

void TimelineWriter::open_event(char phase, unsigned track, std::string_view name) {
  if (m_events++ > 0) m_buffer += ",\n";
  m_buffer += "{\"ph\":\"";
  m_buffer += phase;
  m_buffer += "\",\"pid\":" + std::to_string(m_track_ids.at(track).first) +
              ",\"tid\":" + std::to_string(m_track_ids.at(track).second) + ",\"name\":";
  append_string(m_buffer, name);
}

// Microseconds with six decimals: every picosecond, no rounding.
void TimelineWriter::append_time(const char* key, const sc_time& time) {
  const auto picoseconds =
      static_cast<uint64_t>(std::llround(static_cast<double>(time.value()) * m_picoseconds_per_unit));
  char text[48];
  std::snprintf(text, sizeof text, ",\"%s\":%" PRIu64 ".%06" PRIu64, key, picoseconds / 1000000, picoseconds % 1000000);
  m_buffer += text;
}

void TimelineWriter::append_args(const TimelineArgs& args) {
  if (args.empty()) return;
  m_buffer += ",\"args\":{";
  for (size_t i = 0; i < args.size(); ++i) {
    if (i > 0) m_buffer += ',';
    append_string(m_buffer, args[i].first);
    m_buffer += ':';
    append_number(m_buffer, args[i].second);
  }
  m_buffer += '}';
}

void TimelineWriter::close_event() {
  m_buffer += '}';
  if (m_buffer.size() >= FLUSH_BYTES) flush();
}

void TimelineWriter::flush() {
  m_bytes += m_buffer.size();
  write_streamed(m_file.get(), m_buffer, m_error);
  m_buffer.clear();
}

unsigned TimelineWriter::track(const std::string& process, const std::string& thread) {
  const auto found = m_tracks.find({process, thread});
  if (found != m_tracks.end()) return found->second;
  const auto [entry, new_process] = m_processes.emplace(process, static_cast<unsigned>(m_processes.size() + 1));
  const unsigned pid = entry->second;
  const unsigned id = static_cast<unsigned>(m_track_ids.size());
  const unsigned tid = static_cast<unsigned>(id + 1);
  m_track_ids.emplace_back(pid, tid);
  m_tracks.emplace(std::make_pair(process, thread), id);
  // The names Perfetto shows for the group and the row.
  if (new_process) {
    open_event('M', id, "process_name");
    m_buffer += ",\"args\":{\"name\":";
    append_string(m_buffer, process);
    m_buffer += '}';
    close_event();
  }
  open_event('M', id, "thread_name");
  m_buffer += ",\"args\":{\"name\":";
  append_string(m_buffer, thread);
  m_buffer += '}';
  close_event();
  return id;
}

void TimelineWriter::slice(unsigned track, std::string_view name, const sc_time& begin, const sc_time& end,
                           const TimelineArgs& args) {
  open_event('X', track, name);
  append_time("ts", begin);
  append_time("dur", end > begin ? end - begin : sc_core::SC_ZERO_TIME);
  append_args(args);
  close_event();
}

void TimelineWriter::instant(unsigned track, std::string_view name, const sc_time& when) {
  open_event('i', track, name);
  m_buffer += ",\"s\":\"t\"";
  append_time("ts", when);
  close_event();
}

void TimelineWriter::counter(unsigned track, std::string_view name, const sc_time& when, const TimelineArgs& values) {
  open_event('C', track, name);
  append_time("ts", when);
  append_args(values);
  close_event();
}

void TimelineWriter::flow_from(const std::string& key, unsigned track, const sc_time& when) {
  if (!key.empty()) m_flows[key].push_back({m_next_flow++, track, when});
}

void TimelineWriter::flow_to(const std::string& key, unsigned track, const sc_time& when) {
  const auto found = m_flows.find(key);
  if (found == m_flows.end()) return;
  // A start binds to the slice around it, an end ("bp":"e") to the slice
  // that encloses it: the descriptor and the program.
  for (const FlowStart& start : found->second) {
    open_event('s', start.track, "cmem");
    m_buffer += ",\"cat\":\"flow\",\"id\":" + std::to_string(start.id);
    append_time("ts", start.when);
    close_event();
    open_event('f', track, "cmem");
    m_buffer += ",\"cat\":\"flow\",\"bp\":\"e\",\"id\":" + std::to_string(start.id);
    append_time("ts", when);
    close_event();
  }
  m_flows.erase(found);
}

std::string TimelineWriter::finish() {
  m_buffer += "\n]}\n";
  flush();
  m_error = commit_streamed(m_file, m_error);
  return m_error;
}

}  // namespace tessera
