// What is recorded of a run of the SoC, apart from building it: each frame's
// record (its times and what was spent on it), the energy's power windows,
// the statistics document and the VCD trace, whose wall-clock date it blanks.
// Soc (soc.h) builds one over its blocks and feeds it the display's frame
// requests and frames; the recorder reads the blocks and builds nothing.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <systemc>

#include <nlohmann/json.hpp>

#include "array/array_processor.h"
#include "bus/ahb_bus.h"
#include "common/block.h"
#include "config/config.h"
#include "display/display_controller.h"
#include "host/host.h"
#include "power/energy_model.h"
#include "power/power_trace.h"

namespace tessera {

class SocRecorder {
 public:
  // The blocks whose figures the records take: every block (`blocks`, in
  // the order of the statistics, filled in by the SoC after this is built),
  // the host's busy time, the bus's bytes and the array's stages. `scope`
  // names the power signals in the VCD (<scope>.power.<unit>).
  struct Sources {
    const std::vector<Block*>& blocks;
    Host& host;
    const AhbBus& bus;
    const ArrayProcessor& array;
  };
  // Reads power.* of `config` (the energy model, the power trace's window,
  // power.sleep_unused).
  SocRecorder(const std::string& scope, const Config& config, Sources sources);
  SocRecorder(const SocRecorder&) = delete;
  SocRecorder& operator=(const SocRecorder&) = delete;

  // The display's hooks: a frame requested (SWAP or PRESENT) and a frame shown.
  void record_request(const sc_core::sc_time& when);
  void record_frame(const Frame& frame);

  // Opens a VCD file (path without ".vcd") and traces every block's
  // signals and, unless power.trace_window_us is 0, every energy unit's
  // average power per window (<scope>.power.<unit>, <scope>.power.total, in
  // mW). Call before sc_start.
  // The path may name a pipe (soc_sim copies the trace through one to check
  // every write); close_trace blanks the date (blank_vcd_date) only in a
  // regular file, and a reader of a pipe blanks it itself.
  void trace_to(const std::string& path_without_extension);
  void close_trace();

  // Records the run on a timeline (common/timeline.h): every block's
  // activity, and the counters "power" (each energy unit's average power
  // and the total, in mW) and "bus" (its utilisation, in %) over windows
  // that sample_timeline closes. Call before sc_start; `sink` outlives the
  // simulation. The run is the same as without it.
  void timeline_to(TimelineSink& sink);
  // Closes the counters' window at the kernel's time (soc_sim: after every
  // millisecond of simulated time); nothing without a timeline.
  void sample_timeline();
  // The end of the run on the timeline: what the blocks held back, and the
  // counters' last window.
  void finish_timeline();

  // The power trace's windows so far (null without a power trace).
  const PowerTrace* power_trace() const { return m_power_trace.get(); }
  // Closes the power trace's current window at the kernel's time, so that
  // the windows cover the run up to now; the SoC does so when the
  // simulation finishes. Nothing without a power trace.
  void close_power_window();
  // The power trace's process (the SoC's SC_THREAD trace_power): closes a
  // window every power.trace_window_us; returns at once without a power trace.
  void trace_power();

  // simulated_ns, each block's statistics under its name, `energy` (every
  // energy unit's energy and average power over the run, and the total) and
  // `frames`: for every frame shown, its time, when it was requested (SWAP or
  // PRESENT), its render time (from the previous frame's request to this one)
  // and the host's busy time, the bus bytes and the energy over that render
  // time.
  // With a region of interest marked, also `roi` (roi_json).
  nlohmann::json stats_json() const;
  // Describes every statistic stats_json gives (stats_schema.h).
  void describe_stats(StatsSchema& schema) const;

  // The region of interest (roi_register.h): software began (`begins`) or
  // ended one at `when`. Each region's statistics are the growth of the
  // run's accumulating statistics (stats_schema.h: accumulates) from its
  // begin to its end, summed over the regions; each end is read at the
  // access's time, every block but the host's as the kernel has it then (at
  // most a quantum, sim.quantum_ns, behind).
  void roi_edge(bool begins, const sc_core::sc_time& when);

  // Streams `frames` instead: from now on each frame shown goes to `sink`
  // as its stats.json record, in order, and is not kept, so a long run's
  // memory stays flat; stats_json()'s `frames` then holds only the frames
  // shown before. The records are those stats_json() would have listed.
  void stream_frames(std::function<void(const nlohmann::json& record)> sink) { m_frame_sink = std::move(sink); }

  // Every block's activity for the energy model, from the start to `now`.
  EnergyActivity energy_activity(const sc_core::sc_time& now) const;
  const EnergyModel& energy_model() const { return m_energy_model; }

 private:
  // stats.energy.array_stages: per stage of the array's programs, the
  // energy of the units the board measured as the array (array controller,
  // CIU, CUs) over the time of that stage's instructions alone.
  nlohmann::json array_stages_energy_json() const;
  nlohmann::json frames_json() const;
  // stats_json's statistics at `elapsed` but for frames and roi.
  nlohmann::json totals_json(const sc_core::sc_time& elapsed) const;
  // describe_stats but for roi: what totals_json and frames give.
  void describe_run_stats(StatsSchema& schema) const;
  // stats.json's roi: the regions' count, the first begin and the last end,
  // the frames whose request fell in a region, and the growth of every
  // accumulating statistic summed over the regions; one still open ends now.
  nlohmann::json roi_json() const;
  struct RoiRegion {
    double begin_seconds, end_seconds;  // end: infinite while open
  };
  std::vector<RoiRegion> m_roi_regions;
  nlohmann::json m_roi_open_begin;  // totals_json at the open region's begin
  nlohmann::json m_roi_growth;      // summed over the closed regions
  std::vector<size_t> m_roi_frames;
  struct FrameRecord;
  // Frame `index`'s record in stats.json; `previous_shown_seconds`: when the
  // frame before was shown (0 for the first).
  static nlohmann::json frame_json(const FrameRecord& frame, size_t index, double previous_shown_seconds);

  std::string m_scope;
  Sources m_sources;
  EnergyModel m_energy_model;
  // Totals since the start when a frame was requested (sampled from within
  // the request, a write the host makes: at the host's own time).
  struct Request {
    double seconds;
    sc_core::sc_time host_busy;
    uint64_t bus_bytes;
    EnergyActivity activity;
  };
  std::deque<Request> m_requests;                         // not yet shown
  Request m_last_shown{0, sc_core::SC_ZERO_TIME, 0, {}};  // of the last frame shown (zero before the first)
  // A frame shown: its times, and what was spent on it (since the frame
  // before), as stats.json lists them.
  struct UnitJoules {
    double static_joules, dynamic_joules;
  };
  struct FrameRecord {
    double shown_seconds = 0, requested_seconds = 0, render_seconds = 0;
    sc_core::sc_time host_busy;
    uint64_t bus_bytes = 0;
    std::shared_ptr<const std::vector<std::string>> units;  // energy's units, shared with the frame before if the same
    std::vector<UnitJoules> energy;                         // per unit of `units`
  };
  std::vector<FrameRecord> m_frames;
  std::function<void(const nlohmann::json&)> m_frame_sink;  // stream_frames
  size_t m_frames_streamed = 0;
  double m_last_shown_seconds = 0;  // the last frame's, streamed or kept
  sc_core::sc_trace_file* m_trace = nullptr;
  std::string m_trace_path;
  sc_core::sc_time m_power_window;
  bool m_sleep_unused;  // power.sleep_unused
  std::unique_ptr<PowerTrace> m_power_trace;
  // The traced powers in mW: one per energy unit, in the order of
  // energy_activity(), then the total. Sized once: the VCD holds their addresses.
  std::vector<double> m_power_milliwatts;
  // The timeline's counters: a power trace of their own over the same
  // activity, its windows closed by sample_timeline.
  TimelineSink* m_timeline = nullptr;
  unsigned m_power_track = 0, m_bus_track = 0;
  std::unique_ptr<PowerTrace> m_counter_trace;
  uint64_t m_counter_bus_cycles = 0;  // the bus's busy cycles at the last counter window's end
  // Closes a counter window at `now`, unless it would be empty.
  void record_counters(const EnergyActivity& activity, const sc_core::sc_time& now);
};

// SystemC writes the wall-clock date into a VCD header; this replaces it in
// `head`, the first VCD_DATE_BYTES of the file or fewer, with dashes of the
// same length, so that identical runs give identical files.
constexpr size_t VCD_DATE_BYTES = 512;
void blank_vcd_date(std::string& head);

}  // namespace tessera
