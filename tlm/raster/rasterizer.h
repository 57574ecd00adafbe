// The tile-based fixed-function rasterizer as a bus peripheral: a register
// target (raster_regs.def), a bus initiator that fetches the driver's tile
// table, command lists, triangle records, state blocks and texels from system
// memory and writes the finished tiles back, and an interrupt line.
//
// The arithmetic is the functional core's (raster/core/tile_rasterizer.h,
// plain C++); this module gives it time. The core reports its work through
// RasterPort: every read and write becomes bus bursts issued at the
// rasterizer's local time (temporal decoupling through a quantum keeper),
// and every cycles(n) advances that local time by n periods of the
// rasterizer clock. The pipeline waits for each bus access to complete, so a
// run takes its compute cycles plus the bus time of its accesses, contention
// with the host and the display DMA included.
//
// Writes to the registers while a run is in progress (STATUS.busy) are
// rejected with a command error response, except IRQ_STATUS and IRQ_ENABLE,
// which the interrupt handler must be able to use at any time.
#pragma once

#include <cstdint>
#include <string>

#include <systemc>
#include <tlm>

#include <tlm_utils/tlm_quantumkeeper.h>

#include <nlohmann/json.hpp>

#include "common/bus_master.h"
#include "common/peripheral.h"
#include "common/timed_trace.h"
#include "config/config.h"
#include "raster/core/raster_port.h"
#include "raster/core/tile_rasterizer.h"

namespace tessera {

// Every field is read from raster.* (from_config) or, where marked, set by
// the SoC; none has a default of its own.
struct RasterizerParams {
  unsigned width = 0;   // set by the SoC: the display's (display.width)
  unsigned height = 0;  // set by the SoC: the display's (display.height)
  unsigned tile_width = 0;
  unsigned tile_height = 0;
  raster::RecipMethod recip_method{};
  unsigned texture_units = 0;  // texture units (sampler and combiner each), 1 .. raster::MAX_TEXTURE_UNITS
  raster::CycleCosts costs;
  sc_core::sc_time clock_period;
  // Longest burst on the bus, in beats (AHB's INCR16): a long tile write
  // must not hold the bus for hundreds of cycles while the display DMA has a
  // line due.
  unsigned burst_beats = 0;
  // Width of the pipeline's bus interface: bytes per beat.
  unsigned beat_bytes = 0;

  // The parameters this block owns (the one place their defaults live),
  // read back from a configuration that holds them; fields marked "set by the
  // SoC" are other blocks' values and stay zero here.
  static ParamGroup parameters();
  static RasterizerParams from_config(const Config& config);
  // from_config of the defaults alone.
  static RasterizerParams defaults();
};

class Rasterizer : public Peripheral {
 public:
  SC_HAS_PROCESS(Rasterizer);

  // Registers on `in` and the interrupt on `irq` (Peripheral).
  BusMaster mem_out;

  // The registers, one member each (raster_regs.def).
#define TESSERA_REGISTER_TABLE "raster/raster_regs.def"
#include "common/register_members.inc"

  Rasterizer(sc_core::sc_module_name name, const RasterizerParams& params);

  const RasterizerParams& params() const {
    return m_params;
  }
  bool busy() const {
    return m_busy;
  }
  // Notified when a run has ended (successfully or not) and the registers
  // hold its results.
  const sc_core::sc_event& run_finished_event() const {
    return m_run_finished;
  }
  const raster::RunResult& last_result() const {
    return m_last;
  }

  void trace_signals(sc_core::sc_trace_file* file) override;
  // Track "runs": each run, with its tiles, triangles and fragments; at
  // detail all, track "tiles": each tile the run drew, named by its place.
  void timeline_to(TimelineSink& sink) override;
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  // The core's view of memory and time: bus bursts over mem_out at the
  // local time of the quantum keeper.
  class BusPort : public raster::RasterPort {
   public:
    explicit BusPort(Rasterizer& owner) : m_owner(owner) {}
    bool read(uint32_t address, void* data, unsigned bytes) override;
    bool write(uint32_t address, const void* data, unsigned bytes) override;
    void cycles(uint64_t count) override;
    // Track "tiles" (timeline detail all): each tile from its table entry to
    // its write-back, at the quantum keeper's local time.
    void tile_begins(unsigned x, unsigned y) override;
    void tile_ends(unsigned x, unsigned y) override;

   private:
    Rasterizer& m_owner;
    sc_core::sc_time m_tile_begin;
  };

  uint32_t read_CTRL() const;
  void write_CTRL(uint32_t value);
  uint32_t read_STATUS() const;
  void write_START(uint32_t value);
  const char* write_refusal(const tlm::tlm_generic_payload& gp) const override;

  void run();  // SC_THREAD: one TileRasterizer::run per START
  bool transfer(tlm::tlm_command command, uint32_t address, uint8_t* data, unsigned bytes);
  void finish_run(const raster::RunResult& result, const sc_core::sc_time& start);

  RasterizerParams m_params;
  BusPort m_port;
  tlm_utils::tlm_quantumkeeper m_qk;
  sc_core::sc_event m_start;
  sc_core::sc_event m_run_finished;

  bool m_busy = false;
  bool m_done = false;
  bool m_error = false;
  raster::RunResult m_last;
  Log2Histogram m_span_pixels;  // every run's (histograms.span_pixels)

  // Totals over every run, for stats_json.
  ActivityCounter& m_runs;
  ActivityCounter& m_failed_runs;
  ActivityCounter& m_tiles;
  ActivityCounter& m_commands;
  ActivityCounter& m_triangles;
  ActivityCounter& m_triangles_skipped;
  ActivityCounter& m_fragments;
  ActivityCounter& m_fragments_written;
  ActivityCounter& m_texels;
  ActivityCounter& m_setup_cycles;
  ActivityCounter& m_tile_cycles;
  ActivityCounter& m_fragment_cycles;
  ActivityCounter& m_texel_cycles;
  ActivityCounter& m_compute_cycles;  // cycles(n) of the core
  sc_core::sc_time m_busy_time;

  TimedTrace m_busy_trace;
  bool m_tracing = false;
  TimelineSink* m_timeline = nullptr;  // timeline_to: null without a timeline
  unsigned m_timeline_track = 0;
  TimelineSink* m_tile_timeline = nullptr;  // at detail all only
  unsigned m_tile_track = 0;
};

}  // namespace tessera
