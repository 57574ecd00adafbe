// The SoC assembled from one Config: host, bus, system memory, display and
// rasterizer, bound by the memory map (memory_map.def) and the interrupt map
// (irq_map.def). Owns the statistics and the VCD trace.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <string>

#include <systemc>

#include <nlohmann/json.hpp>

#include "array/array_processor.h"
#include "array/ciu.h"
#include "bus/ahb_bus.h"
#include "config/config.h"
#include "display/display_controller.h"
#include "display/display_dma.h"
#include "dma/dma.h"
#include "host/host.h"
#include "intc/interrupt_controller.h"
#include "mem/memory.h"
#include "power/energy_model.h"
#include "power/power_trace.h"
#include "raster/rasterizer.h"
#include "soc/irq_map.h"

namespace tessera {

// Bus priorities under fixed-priority arbitration (lower is served first):
// the display DMA has a deadline every line, the host has none; the
// rasterizer's tile traffic comes between: the host waits for it anyway.
struct BusPriority {
  static constexpr unsigned DISPLAY_DMA = 0;
  static constexpr unsigned RASTER = 1;
  // The system/array DMA feeds and drains the array for the host, which
  // waits for it; but the rasterizer's tile stream stalls a pipeline.
  static constexpr unsigned DMA = 2;
  static constexpr unsigned HOST = 3;
};

class Soc : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Soc);

  // The configuration must hold parameter_groups(); it is validated here.
  Soc(sc_core::sc_module_name name, const Config& config);

  // The SoC's parameters: its own (the simulation's timing) and every
  // block's, in the order of the configuration reference.
  static std::vector<ParamGroup> parameter_groups();
  ~Soc() override;

  AhbBus bus;
  Memory memory;
  Host host;
  DisplayController display;
  DisplayDma display_dma;
  Rasterizer raster;
  ArrayProcessor array;
  Ciu ciu;
  // The system/array DMA, built only when dma.enabled (otherwise the SoC is
  // exactly what it was without it: no bus initiator, no statistics).
  std::unique_ptr<Dma> dma;
  // The interrupt controller, built only when host.model=iss (the software
  // on the ISS needs it; host-compiled software waits on the lines).
  std::unique_ptr<InterruptController> intc;

  // Runs the host program; the simulation stops when it has finished and
  // the display has shown every frame handed to it.
  void set_program(Host::Program program) { host.set_program(std::move(program)); }
  bool done() const { return m_done; }

  // Every block, in the order of the statistics and the summary. The SoC
  // gathers statistics and traces over this list, and soc_sim prints the
  // summary from it, so neither names a block.
  const std::vector<Block*>& blocks() const { return m_blocks; }

  // Opens a VCD file (path without ".vcd") and traces every block's
  // signals and, unless power.trace_window_us is 0, every energy unit's
  // average power per window (soc.power.<unit>, soc.power.total, in mW).
  // Call before sc_start.
  // The path may name a pipe (soc_sim copies the trace through one to check
  // every write); close_trace blanks the date (blank_vcd_date) only in a
  // regular file, and a reader of a pipe blanks it itself.
  void trace_to(const std::string& path_without_extension);
  void close_trace();

  // The power trace's windows so far (null without a power trace).
  const PowerTrace* power_trace() const { return m_power_trace.get(); }
  // Closes the power trace's current window at the kernel's time, so that
  // the windows cover the run up to now; the SoC does so when the
  // simulation finishes. Nothing without a power trace.
  void close_power_window();

  // simulated_ns, each block's statistics under its name, `energy` (every
  // energy unit's energy and average power over the run, and the total) and
  // `frames`: for every frame shown, its time, when it was requested (SWAP or
  // PRESENT), its render time (from the previous frame's request to this one)
  // and the host's busy time, the bus bytes and the energy over that render
  // time.
  nlohmann::json stats_json() const;

  // Streams `frames` instead: from now on each frame shown goes to `sink`
  // as its stats.json record, in order, and is not kept, so a long run's
  // memory stays flat; stats_json()'s `frames` then holds only the frames
  // shown before. The records are those stats_json() would have listed.
  void stream_frames(std::function<void(const nlohmann::json& record)> sink) { m_frame_sink = std::move(sink); }

  // Every block's activity for the energy model, from the start to `now`.
  EnergyActivity energy_activity(const sc_core::sc_time& now) const;
  const EnergyModel& energy_model() const { return m_energy_model; }

 private:
  void finish();       // SC_THREAD
  void trace_power();  // SC_THREAD: ends at once without a power trace
  void record_request(const sc_core::sc_time& when);
  void record_frame(const Frame& frame);
  // stats.energy.array_stages: per stage of the array's programs, the
  // energy of the units the board measured as the array (array controller,
  // CIU, CUs) over the time of that stage's instructions alone.
  nlohmann::json array_stages_energy_json() const;
  nlohmann::json frames_json() const;
  struct FrameRecord;
  // Frame `index`'s record in stats.json; `previous_shown_seconds`: when the
  // frame before was shown (0 for the first).
  static nlohmann::json frame_json(const FrameRecord& frame, size_t index, double previous_shown_seconds);

  std::vector<Block*> m_blocks;
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
  std::vector<std::unique_ptr<sc_core::sc_signal<bool>>> m_irq_lines;
  std::unique_ptr<sc_core::sc_signal<bool>> m_core_irq, m_core_fiq;
  sc_core::sc_event m_host_finished;
  bool m_done = false;
  sc_core::sc_trace_file* m_trace = nullptr;
  std::string m_trace_path;
  sc_core::sc_time m_power_window;
  bool m_sleep_unused;  // power.sleep_unused
  std::unique_ptr<PowerTrace> m_power_trace;
  // The traced powers in mW: one per energy unit, in the order of
  // energy_activity(), then the total. Sized once: the VCD holds their addresses.
  std::vector<double> m_power_milliwatts;
};

// SystemC writes the wall-clock date into a VCD header; this replaces it in
// `head`, the first VCD_DATE_BYTES of the file or fewer, with dashes of the
// same length, so that identical runs give identical files.
constexpr size_t VCD_DATE_BYTES = 512;
void blank_vcd_date(std::string& head);

}  // namespace tessera
