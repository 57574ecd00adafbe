#include "soc/soc_recorder.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "common/log.h"

namespace tessera {

using sc_core::sc_time;

namespace {

// Energy in joules and average power in watts over `seconds`: one unit's
// (adding its event classes' energies under "events" is the caller's), and
// the total of all units with each unit's.
nlohmann::json unit_energy_json(double static_joules, double dynamic_joules, double seconds) {
  const double total = dynamic_joules + static_joules;
  return {{"total_j", total},
          {"static_j", static_joules},
          {"dynamic_j", dynamic_joules},
          {"average_w", seconds > 0 ? total / seconds : 0.0}};
}
nlohmann::json energy_json(nlohmann::json units, double total_joules, double seconds) {
  return {{"total_j", total_joules}, {"average_w", seconds > 0 ? total_joules / seconds : 0.0}, {"units", units}};
}

// energy_json's statistics under `prefix` (with its dot), over `what`
// (the run, a frame, a stage).
void describe_energy(StatsSchema& schema, const std::string& prefix, const std::string& what) {
  schema.add(prefix + "total_j", "J", "energy of every unit over " + what);
  schema.add(prefix + "average_w", "W", "average power of every unit over " + what);
  schema.add(prefix + "units.*.total_j", "J", "the unit's energy over " + what + " (static_j + dynamic_j)");
  schema.add(prefix + "units.*.static_j", "J", "the unit's static (leakage) energy over " + what);
  schema.add(prefix + "units.*.dynamic_j", "J", "the unit's dynamic energy over " + what + " (its events')");
  schema.add(prefix + "units.*.average_w", "W", "the unit's average power over " + what);
}

}  // namespace

SocRecorder::SocRecorder(const std::string& scope, const Config& config, Sources sources)
    : m_scope(scope),
      m_sources(sources),
      m_energy_model(EnergyModel::from_config(config)),
      m_power_window(config.get_real("power.trace_window_us"), sc_core::SC_US),
      m_sleep_unused(config.get_bool("power.sleep_unused")) {}

void SocRecorder::trace_to(const std::string& path_without_extension) {
  m_trace_path = path_without_extension + ".vcd";
  m_trace = sc_core::sc_create_vcd_trace_file(path_without_extension.c_str());
  if (!m_trace) throw std::runtime_error("cannot create VCD file " + m_trace_path);
  m_trace->set_time_unit(1, sc_core::SC_PS);
  for (Block* block : m_sources.blocks) block->trace_signals(m_trace);
  // A window below the time resolution would never advance.
  if (m_power_window == sc_core::SC_ZERO_TIME) return;
  m_power_trace = std::make_unique<PowerTrace>(m_energy_model);
  m_sources.host.attribute_activity_in_time();
  const EnergyActivity units = energy_activity(sc_core::SC_ZERO_TIME);
  m_power_milliwatts.assign(units.size() + 1, 0.0);
  const std::string scope = m_scope + ".power.";
  for (size_t i = 0; i < units.size(); ++i) sc_core::sc_trace(m_trace, m_power_milliwatts[i], scope + units[i].unit);
  sc_core::sc_trace(m_trace, m_power_milliwatts.back(), scope + "total");
}

void SocRecorder::timeline_to(TimelineSink& sink) {
  m_timeline = &sink;
  for (Block* block : m_sources.blocks) block->timeline_to(sink);
  // The counters' windows are closed from outside the simulation
  // (sample_timeline), not by a process of their own: a process would add
  // events to the kernel, at which the host synchronises, and the run would
  // differ from a run without the timeline.
  m_sources.host.attribute_activity_in_time();
  m_counter_trace = std::make_unique<PowerTrace>(m_energy_model);
  m_power_track = sink.track(m_scope, "power");
  m_bus_track = sink.track(m_scope, "bus");
}

void SocRecorder::sample_timeline() {
  const sc_time now = sc_core::sc_time_stamp();
  if (m_counter_trace) record_counters(energy_activity(now), now);
}

void SocRecorder::finish_timeline() {
  if (!m_timeline) return;
  for (Block* block : m_sources.blocks) block->finish_timeline();
  sample_timeline();
}

void SocRecorder::record_counters(const EnergyActivity& activity, const sc_time& now) {
  if (now.to_seconds() <= m_counter_trace->last_window().end_seconds) return;
  const PowerWindow& window = m_counter_trace->close_window(activity, now.to_seconds());
  const sc_time begin(window.start_seconds, sc_core::SC_SEC);
  TimelineArgs milliwatts;
  for (const UnitEnergy& unit : window.units)
    milliwatts.emplace_back(unit.unit, window.milliwatts(unit.total_joules()));
  milliwatts.emplace_back("total", window.milliwatts(window.total_joules()));
  m_timeline->counter(m_power_track, "power (mW)", begin, milliwatts);
  const uint64_t cycles = m_sources.bus.busy_cycles();
  const double bus_seconds =
      static_cast<double>(cycles - m_counter_bus_cycles) * m_sources.bus.params().clock_period.to_seconds();
  m_counter_bus_cycles = cycles;
  m_timeline->counter(m_bus_track, "bus utilisation (%)", begin, {{"busy", 100 * bus_seconds / window.seconds()}});
}

void SocRecorder::trace_power() {
  if (!m_power_trace) return;
  for (;;) {
    sc_core::wait(m_power_window);
    close_power_window();
  }
}

void SocRecorder::close_power_window() {
  if (!m_power_trace) return;
  const sc_time now = sc_core::sc_time_stamp();
  // The simulation may finish exactly at a window's end: no empty window.
  if (now.to_seconds() <= m_power_trace->last_window().end_seconds) return;
  // A window's power is known at its end: the trace shows it from there to
  // the next window's end, one window after the activity.
  // Traced to the nanowatt: rounding noise would otherwise change a steady
  // power in every window.
  const auto traced = [](double milliwatts) { return std::round(milliwatts * 1e6) / 1e6; };
  const PowerWindow& window = m_power_trace->close_window(energy_activity(now), now.to_seconds());
  for (size_t i = 0; i < window.units.size(); ++i)
    m_power_milliwatts[i] = traced(window.milliwatts(window.units[i].total_joules()));
  m_power_milliwatts.back() = traced(window.milliwatts(window.total_joules()));
}

void SocRecorder::close_trace() {
  if (!m_trace) return;
  sc_core::sc_close_vcd_trace_file(m_trace);
  m_trace = nullptr;
  std::error_code error;
  if (!std::filesystem::is_regular_file(m_trace_path, error)) return;
  std::fstream file(m_trace_path, std::ios::in | std::ios::out | std::ios::binary);
  std::string head(VCD_DATE_BYTES, '\0');
  file.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(file.gcount()));
  const std::string original = head;
  blank_vcd_date(head);
  if (head == original) return;
  file.clear();
  file.seekp(0);
  file.write(head.data(), static_cast<std::streamsize>(head.size()));
}

void blank_vcd_date(std::string& head) {
  const auto date = head.find("$date");
  const auto end = date == std::string::npos ? std::string::npos : head.find("$end", date);
  if (end == std::string::npos) return;
  for (size_t i = date + 5; i < end; ++i)
    if (head[i] != '\n' && head[i] != ' ') head[i] = '-';
}

void SocRecorder::record_request(const sc_time& when) {
  // The host's busy time is exact here: the request is the host's own
  // write. The bus has counted the host's transfers up to its time and the
  // DMAs' up to the kernel's, at most a quantum (sim.quantum_ns) behind.
  m_requests.push_back({when.to_seconds(), m_sources.host.busy_time(), m_sources.bus.bytes(), energy_activity(when)});
}

void SocRecorder::record_frame(const Frame& frame) {
  // A frame comes from the last request before the vertical blank that took
  // it (DMA mode) or from its PRESENT (port mode); requests it replaced are
  // dropped.
  while (m_requests.size() > 1 && m_requests.front().seconds < frame.requested_seconds) m_requests.pop_front();
  Request request;
  if (m_requests.empty() || m_requests.front().seconds != frame.requested_seconds) {
    // Only software that bypasses the display's registers gets here.
    request = {frame.requested_seconds, m_sources.host.busy_time(), m_sources.bus.bytes(),
               energy_activity(sc_core::sc_time_stamp())};
  } else {
    request = std::move(m_requests.front());
    m_requests.pop_front();
  }
  // What stats.json lists of the frame, as differences to the frame before,
  // taken now: a long run keeps a few numbers per frame, not every unit's
  // event counts (docs/robustness.md, soak).
  FrameRecord record;
  record.shown_seconds = frame.time_seconds;
  record.requested_seconds = request.seconds;
  record.render_seconds = request.seconds - m_last_shown.seconds;
  record.host_busy = request.host_busy - m_last_shown.host_busy;
  record.bus_bytes = request.bus_bytes - m_last_shown.bus_bytes;
  std::vector<std::string> units;
  for (const UnitEnergy& unit : m_energy_model.unit_energies(
           activity_difference(request.activity, m_last_shown.activity), record.render_seconds)) {
    units.push_back(unit.unit);
    record.energy.push_back({unit.static_joules, unit.dynamic_joules()});
  }
  if (m_frames.empty() || *m_frames.back().units != units)
    record.units = std::make_shared<const std::vector<std::string>>(std::move(units));
  else
    record.units = m_frames.back().units;
  m_last_shown = std::move(request);
  for (const RoiRegion& region : m_roi_regions)
    if (region.begin_seconds <= record.requested_seconds && record.requested_seconds <= region.end_seconds)
      m_roi_frames.push_back(m_frames.size() + m_frames_streamed);
  if (m_frame_sink) {
    const double previous = m_last_shown_seconds;
    m_last_shown_seconds = record.shown_seconds;
    m_frame_sink(frame_json(record, m_frames.size() + m_frames_streamed++, previous));
    return;
  }
  m_last_shown_seconds = record.shown_seconds;
  m_frames.push_back(std::move(record));
}

nlohmann::json SocRecorder::frame_json(const FrameRecord& f, size_t index, double previous_shown_seconds) {
  nlohmann::json units = nlohmann::json::object();
  double total_joules = 0;
  for (size_t u = 0; u < f.energy.size(); ++u) {
    units[(*f.units)[u]] = unit_energy_json(f.energy[u].static_joules, f.energy[u].dynamic_joules, f.render_seconds);
    total_joules += f.energy[u].dynamic_joules + f.energy[u].static_joules;
  }
  return {{"index", index},
          {"time_ns", f.shown_seconds * 1e9},
          {"interval_ns", (f.shown_seconds - previous_shown_seconds) * 1e9},
          {"requested_ns", f.requested_seconds * 1e9},
          {"render_ns", f.render_seconds * 1e9},
          {"host_busy_ns", f.host_busy.to_seconds() * 1e9},
          {"bus_bytes", f.bus_bytes},
          {"energy", energy_json(std::move(units), total_joules, f.render_seconds)}};
}

nlohmann::json SocRecorder::frames_json() const {
  nlohmann::json frames = nlohmann::json::array();
  double previous_shown_seconds = 0;
  for (size_t i = 0; i < m_frames.size(); ++i) {
    frames.push_back(frame_json(m_frames[i], i, previous_shown_seconds));
    previous_shown_seconds = m_frames[i].shown_seconds;
  }
  return frames;
}

nlohmann::json SocRecorder::array_stages_energy_json() const {
  nlohmann::json stages = nlohmann::json::object();
  for (ArrayProcessor::StageActivity& stage : m_sources.array.stage_activity()) {
    // The CIU belongs to the array as the board measured it; its words are
    // the host's, between programs, so within a stage it has its static
    // power only. Each unit is clocked for the stage's time.
    stage.units.push_back({"ciu", {{"words", 0.0}}});
    nlohmann::json units = nlohmann::json::object();
    double total_joules = 0;
    for (UnitActivity& unit : stage.units) {
      unit.clocked_seconds = stage.seconds;
      const UnitEnergy energy = m_energy_model.energy(unit, stage.seconds);
      units[unit.unit] = unit_energy_json(energy.static_joules, energy.dynamic_joules(), stage.seconds);
      total_joules += energy.total_joules();
    }
    stages[stage.stage] = energy_json(std::move(units), total_joules, stage.seconds);
    stages[stage.stage]["seconds"] = stage.seconds;
  }
  return stages;
}

void SocRecorder::describe_run_stats(StatsSchema& schema) const {
  schema.add("simulated_ns", "ns", "simulated time of the run");
  for (const Block* block : m_sources.blocks) {
    StatsSchema own;
    block->describe_stats(own);
    schema.add_all(std::string(block->basename()) + ".", own);
  }
  describe_energy(schema, "energy.", "the run");
  schema.add("energy.units.*.events.*.count", "count",
             "events of the class that the unit's block counted (energy_params.def; host cycles may be fractional)");
  schema.add("energy.units.*.events.*.j", "J", "dynamic energy of the unit's events of the class");
  describe_energy(schema, "energy.array_stages.*.", "the array programs' instructions of the stage");
  schema.add("energy.array_stages.*.seconds", "s", "time the array spent in instructions of the stage");
  schema.add("frames[].index", "index", "the frame's number, from 0");
  schema.add("frames[].time_ns", "ns", "when the frame was shown");
  schema.add("frames[].interval_ns", "ns", "time since the frame before was shown (since the start for the first)");
  schema.add("frames[].requested_ns", "ns", "when the software asked for the frame to be shown");
  schema.add("frames[].render_ns", "ns", "time from the frame before's request to this one's: the frame's render time");
  schema.add("frames[].host_busy_ns", "ns", "host busy time over the frame's render time");
  schema.add("frames[].bus_bytes", "bytes", "bytes every initiator moved on the bus over the frame's render time");
  describe_energy(schema, "frames[].energy.", "the frame's render time");
}

void SocRecorder::describe_stats(StatsSchema& schema) const {
  StatsSchema run;
  describe_run_stats(run);
  schema.add_all("", run);
  for (const StatDescription& d : run.entries())
    if (accumulates(d)) schema.add("roi." + d.key, d.unit, d.description + ", over the regions of interest");
  schema.add("roi.regions", "count", "regions of interest the software marked (tessera_roi_begin/end)");
  schema.add("roi.begin_ns", "ns", "when the first region of interest began");
  schema.add("roi.end_ns", "ns", "when the last region of interest ended (the run's end if still open)");
  schema.add("roi.frames[]", "index", "a frame whose request (SWAP or PRESENT) fell in a region of interest");
}

EnergyActivity SocRecorder::energy_activity(const sc_time& now) const {
  EnergyActivity activity;
  for (const Block* block : m_sources.blocks) {
    for (UnitActivity& unit : block->energy_activity(now)) {
      if (m_sleep_unused && block->sleeps()) unit.clocked_seconds = block->clocked_seconds(now);
      activity.push_back(std::move(unit));
    }
  }
  return activity;
}

nlohmann::json SocRecorder::stats_json() const {
  nlohmann::json stats = totals_json(sc_core::sc_time_stamp());
  stats["frames"] = frames_json();
  if (!m_roi_regions.empty()) stats["roi"] = roi_json();
  return stats;
}

void SocRecorder::roi_edge(bool begins, const sc_time& when) {
  const bool open = !m_roi_regions.empty() && std::isinf(m_roi_regions.back().end_seconds);
  if (begins == open) return;  // the register ignores a write that changes nothing
  if (begins) {
    m_roi_regions.push_back({when.to_seconds(), std::numeric_limits<double>::infinity()});
    m_roi_open_begin = totals_json(when);
    return;
  }
  m_roi_regions.back().end_seconds = when.to_seconds();
  StatsSchema schema;
  describe_run_stats(schema);
  add_growth(schema, m_roi_open_begin, totals_json(when), m_roi_growth);
  m_roi_open_begin = nullptr;
}

nlohmann::json SocRecorder::roi_json() const {
  nlohmann::json growth = m_roi_growth;
  double end_seconds = m_roi_regions.back().end_seconds;
  if (std::isinf(end_seconds)) {
    const sc_time now = sc_core::sc_time_stamp();
    log::warning("roi", "the region of interest begun at " + std::to_string(m_roi_regions.back().begin_seconds * 1e9) +
                            " ns was still open when the run ended: it ends with the run");
    StatsSchema schema;
    describe_run_stats(schema);
    add_growth(schema, m_roi_open_begin, totals_json(now), growth);
    end_seconds = now.to_seconds();
  }
  growth["regions"] = m_roi_regions.size();
  growth["begin_ns"] = m_roi_regions.front().begin_seconds * 1e9;
  growth["end_ns"] = end_seconds * 1e9;
  growth["frames"] = m_roi_frames;
  return growth;
}

nlohmann::json SocRecorder::totals_json(const sc_time& elapsed) const {
  nlohmann::json stats = {{"simulated_ns", elapsed.to_seconds() * 1e9}};
  for (const Block* block : m_sources.blocks) stats[block->basename()] = block->stats_json(elapsed);
  const EnergyActivity activity = energy_activity(elapsed);
  nlohmann::json units = nlohmann::json::object();
  double total_joules = 0;
  for (const UnitEnergy& unit : m_energy_model.unit_energies(activity, elapsed.to_seconds())) {
    nlohmann::json& u = units[unit.unit];
    u = unit_energy_json(unit.static_joules, unit.dynamic_joules(), elapsed.to_seconds());
    for (const auto& [event, joules] : unit.event_joules) u["events"][event]["j"] = joules;
    total_joules += unit.total_joules();
  }
  stats["energy"] = energy_json(std::move(units), total_joules, elapsed.to_seconds());
  for (const UnitActivity& unit : activity)
    for (const auto& [event, count] : unit.counts)
      stats["energy"]["units"][unit.unit]["events"][event]["count"] = count;
  stats["energy"]["array_stages"] = array_stages_energy_json();
  return stats;
}

}  // namespace tessera
