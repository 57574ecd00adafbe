#include "raster/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "common/log.h"
#include "raster/raster_regs.h"

namespace tessera {

using sc_core::sc_time;
namespace regs = raster_regs;

namespace {

uint32_t recip_method_number(raster::RecipMethod method) {
  switch (method) {
    case raster::RecipMethod::method1: return 1;
    case raster::RecipMethod::method2: return 2;
    case raster::RecipMethod::method3: return 3;
  }
  return 3;
}

raster::RecipMethod recip_method_of(uint32_t number) {
  if (number == 1) return raster::RecipMethod::method1;
  if (number == 2) return raster::RecipMethod::method2;
  return raster::RecipMethod::method3;
}

// A triangle skipped for a bad reciprocal operand is counted, not fatal
// (command_format.h): the run still completes.
bool fatal(raster::RasterError error) {
  return error != raster::RasterError::none && error != raster::RasterError::bad_reciprocal;
}

}  // namespace

Rasterizer::Rasterizer(sc_core::sc_module_name name, const RasterizerParams& params)
    : Peripheral(name, params.clock_period),
      mem_out("mem_out", activity()),
      m_params(params),
      m_port(*this),
      m_runs(counter("runs", "runs started (one per START)")),
      m_failed_runs(counter("failed_runs", "runs that stopped with an error")),
      m_tiles(counter("tiles", "tiles rasterized")),
      m_commands(counter("commands", "commands decoded")),
      m_triangles(counter("triangles", "triangles set up")),
      m_triangles_skipped(counter("triangles_skipped", "triangles skipped (zero area, bad reciprocal operand)")),
      m_fragments(counter("fragments", "fragments generated")),
      m_fragments_written(counter("fragments_written", "fragments that passed the tests and were written")),
      m_texels(counter("texels", "texels fetched")),
      m_setup_cycles(counter("cycles.setup", "cycles of triangle setup")),
      m_tile_cycles(counter("cycles.tile", "cycles of tile starts, clears and write-back")),
      m_fragment_cycles(counter("cycles.fragment", "cycles of the fragment pipeline")),
      m_texel_cycles(counter("cycles.texel", "cycles of texel fetches")),
      m_compute_cycles(counter("cycles.compute", "compute cycles the core charged, all stages")),
      m_busy_trace("busy") {
  sleeps_until_used();
  if (params.width == 0 || params.height == 0 || params.tile_width == 0 || params.tile_height == 0)
    throw std::invalid_argument(std::string(this->name()) + ": empty screen or tile");
  if (params.burst_beats == 0 || params.beat_bytes == 0)
    throw std::invalid_argument(std::string(this->name()) + ": burst_beats and beat_bytes must be positive");
  mem_out.configure(params.burst_beats * params.beat_bytes, BusMaster::OnError::stop);

  CTRL.on_read(this, &Rasterizer::read_CTRL);
  CTRL.on_write(this, &Rasterizer::write_CTRL);
  STATUS.on_read(this, &Rasterizer::read_STATUS);
  START.on_write(this, &Rasterizer::write_START);
  bind_irq_registers(IRQ_STATUS, IRQ_ENABLE);
  WIDTH.set_reset(m_params.width);
  HEIGHT.set_reset(m_params.height);
  TILE_WIDTH.set_reset(m_params.tile_width);
  TILE_HEIGHT.set_reset(m_params.tile_height);
  TEXTURE_UNITS.set_reset(m_params.texture_units);
  RECIP_METHOD.set_reset(recip_method_number(m_params.recip_method));

  SC_THREAD(run);
}

void Rasterizer::trace_signals(sc_core::sc_trace_file* file) {
  m_tracing = true;
  sc_core::sc_trace(file, m_busy_trace.signal, std::string(name()) + ".busy");
}

// Reserved: reads 0, ignores what is written.
uint32_t Rasterizer::read_CTRL() const {
  return 0;
}

void Rasterizer::write_CTRL(uint32_t /*value*/) {}

uint32_t Rasterizer::read_STATUS() const {
  return (m_busy ? regs::STATUS_BUSY : 0u) | (m_done ? regs::STATUS_DONE : 0u) | (m_error ? regs::STATUS_ERROR : 0u);
}

void Rasterizer::write_START(uint32_t value) {
  if (!(value & 1)) return;
  m_busy = true;
  m_done = false;
  m_error = false;
  // The run starts one clock after the write reaches the register, at the
  // access's annotated time (the bus forwards the initiator's).
  m_start.notify(m_regs.access_delay() + m_params.clock_period);
}

const char* Rasterizer::write_refusal(const tlm::tlm_generic_payload& gp) const {
  if (!gp.is_write() || gp.get_data_length() != 4 || !gp.get_data_ptr()) return nullptr;
  const uint64_t offset = gp.get_address();
  if (m_busy && offset != regs::IRQ_STATUS && offset != regs::IRQ_ENABLE) return "written while busy";
  uint32_t value = 0;
  std::memcpy(&value, gp.get_data_ptr(), 4);
  if (offset == regs::RECIP_METHOD && (value < 1 || value > 3)) return "RECIP_METHOD accepts 1, 2 or 3";
  if (offset == regs::FORMAT && !pixel_format_from_code(value))
    return "FORMAT accepts a pixel format code (0 RGB565, 1 RGBA8888)";
  return nullptr;
}

bool Rasterizer::BusPort::read(uint32_t address, void* data, unsigned bytes) {
  return m_owner.transfer(tlm::TLM_READ_COMMAND, address, static_cast<uint8_t*>(data), bytes);
}

bool Rasterizer::BusPort::write(uint32_t address, const void* data, unsigned bytes) {
  return m_owner.transfer(tlm::TLM_WRITE_COMMAND, address, static_cast<uint8_t*>(const_cast<void*>(data)), bytes);
}

void Rasterizer::BusPort::cycles(uint64_t count) {
  m_owner.m_compute_cycles += count;
  m_owner.m_qk.inc(m_owner.m_params.clock_period * static_cast<double>(count));
  if (m_owner.m_qk.need_sync()) m_owner.m_qk.sync();
}

// One access of the core: bursts of at most burst_beats beats of beat_bytes, each issued
// when the previous one has completed (the pipeline waits for its data).
bool Rasterizer::transfer(tlm::tlm_command command, uint32_t address, uint8_t* data, unsigned bytes) {
  sc_time local = m_qk.get_local_time();
  return mem_out.transfer(command, address, data, bytes, local, &m_qk);
}

void Rasterizer::run() {
  for (;;) {
    wait(m_start);
    const sc_time start = sc_core::sc_time_stamp();
    if (m_tracing) m_busy_trace.set_at(true, start);
    raster::RunConfig config;
    config.width = m_params.width;
    config.height = m_params.height;
    config.tile_width = m_params.tile_width;
    config.tile_height = m_params.tile_height;
    config.texture_units = m_params.texture_units;
    config.tile_table = TILE_TABLE.get();
    config.color_base = COLOR_BASE.get();
    config.depth_base = DEPTH_BASE.get();
    config.color_format = *pixel_format_from_code(FORMAT.get());
    config.recip_method = recip_method_of(RECIP_METHOD.get());
    log::info(name(), "run started: tile table at " + log::hex(config.tile_table) + ", colour buffer at " +
                          log::hex(config.color_base));

    m_qk.reset();
    raster::TileRasterizer core(m_port, m_params.costs);
    const raster::RunResult result = core.run(config);
    m_qk.sync();
    finish_run(result, start);
  }
}

void Rasterizer::finish_run(const raster::RunResult& result, const sc_time& start) {
  const sc_time elapsed = sc_core::sc_time_stamp() - start;
  m_last = result;
  ++m_runs;
  m_busy_time += elapsed;
  m_tiles += result.tiles;
  m_commands += result.commands;
  m_triangles += result.triangles;
  m_triangles_skipped += result.triangles_skipped;
  m_fragments += result.fragments;
  m_fragments_written += result.fragments_written;
  m_texels += result.texels;
  m_setup_cycles += result.setup_cycles;
  m_tile_cycles += result.tile_cycles;
  m_fragment_cycles += result.fragment_cycles;
  m_texel_cycles += result.texel_cycles;
  m_span_pixels.merge(result.span_pixels);

  const uint64_t cycles = static_cast<uint64_t>(std::llround(elapsed / m_params.clock_period));
  ERROR_STATUS.set(static_cast<uint32_t>(result.error));
  ERROR_ADDRESS.set(result.error == raster::RasterError::none ? 0 : result.error_address);
  TRIANGLES.set(static_cast<uint32_t>(result.triangles));
  FRAGMENTS.set(static_cast<uint32_t>(result.fragments));
  CYCLES.set(static_cast<uint32_t>(std::min<uint64_t>(cycles, UINT32_MAX)));
  m_busy = false;
  if (fatal(result.error)) {
    ++m_failed_runs;
    m_error = true;
    log::warning(name(), std::string("run failed: ") + raster::error_name(result.error) + " at " +
                             log::hex(result.error_address));
    raise_irq(regs::IRQ_ERROR);
  } else {
    m_done = true;
    log::info(name(), "run done: " + std::to_string(result.triangles) + " triangles, " +
                          std::to_string(result.fragments) + " fragments, " + std::to_string(cycles) + " cycles");
    raise_irq(regs::IRQ_DONE);
  }
  if (m_tracing) m_busy_trace.set_at(false, sc_core::sc_time_stamp());
  if (m_timeline)
    m_timeline->slice(m_timeline_track, fatal(result.error) ? "run (failed)" : "run", start, sc_core::sc_time_stamp(),
                      {{"tiles", static_cast<double>(result.tiles)},
                       {"triangles", static_cast<double>(result.triangles)},
                       {"fragments", static_cast<double>(result.fragments)}});
  m_run_finished.notify(sc_core::SC_ZERO_TIME);
}

void Rasterizer::timeline_to(TimelineSink& sink) {
  if (!sink.records(TimelineDetail::blocks)) return;
  m_timeline = &sink;
  m_timeline_track = sink.track(name(), "runs");
  if (!sink.records(TimelineDetail::all)) return;
  m_tile_timeline = &sink;
  m_tile_track = sink.track(name(), "tiles");
}

void Rasterizer::BusPort::tile_begins(unsigned /*x*/, unsigned /*y*/) {
  if (m_owner.m_tile_timeline) m_tile_begin = sc_core::sc_time_stamp() + m_owner.m_qk.get_local_time();
}

void Rasterizer::BusPort::tile_ends(unsigned x, unsigned y) {
  if (!m_owner.m_tile_timeline) return;
  const std::string name = "tile " + std::to_string(x) + "," + std::to_string(y);
  m_owner.m_tile_timeline->slice(m_owner.m_tile_track, name, m_tile_begin,
                                 sc_core::sc_time_stamp() + m_owner.m_qk.get_local_time(),
                                 {{"x", static_cast<double>(x)}, {"y", static_cast<double>(y)}});
}

nlohmann::json Rasterizer::stats_json(const sc_time& elapsed) const {
  nlohmann::json stats = Peripheral::stats_json(elapsed);
  stats["clock_mhz"] = 1e-6 / m_params.clock_period.to_seconds();
  stats["width"] = m_params.width;
  stats["height"] = m_params.height;
  stats["tile_width"] = m_params.tile_width;
  stats["tile_height"] = m_params.tile_height;
  stats["cycles"]["busy"] = static_cast<uint64_t>(std::llround(m_busy_time / m_params.clock_period));
  add_busy_stats(stats, m_busy_time, elapsed);
  stats["waiting_for_bus_ns"] = mem_out.bus_time().to_seconds() * 1e9;
  stats["histograms"]["span_pixels"] = histogram_json(m_span_pixels);
  return stats;
}

void Rasterizer::describe_stats(StatsSchema& schema) const {
  Peripheral::describe_stats(schema);
  schema.add("clock_mhz", "MHz", "the rasterizer's clock frequency");
  schema.add("width", "pixels", "width of the render target");
  schema.add("height", "pixels", "height of the render target");
  schema.add("tile_width", "pixels", "width of a tile");
  schema.add("tile_height", "pixels", "height of a tile");
  schema.add("cycles.busy", "cycles", "rasterizer cycles of every run, busy_ns in cycles");
  describe_busy_stats(schema, "time the rasterizer ran tile tables");
  schema.add("waiting_for_bus_ns", "ns", "time the rasterizer's memory port spent on the bus");
  schema.add_histogram(
      "histograms.span_pixels", "pixels",
      "the pixels of each span (a run of one row's pixels of a triangle in a tile, handed to the shader)");
}

SummaryRow Rasterizer::summary_row(const sc_time& elapsed) const {
  return busy_row(m_busy_time, elapsed,
                  std::to_string(m_runs.value) + " runs, " + std::to_string(m_triangles.value) + " triangles, " +
                      std::to_string(m_tiles.value) + " tiles, " + std::to_string(m_fragments.value) + " fragments (" +
                      std::to_string(m_fragments_written.value) + " written)");
}

EnergyActivity Rasterizer::energy_activity(const sc_time& now) const {
  (void)now;
  return {{"raster",
           {{"compute_cycles", static_cast<double>(m_compute_cycles.value)},
            {"fragments", static_cast<double>(m_fragments.value)},
            {"texels", static_cast<double>(m_texels.value)},
            {"tiles", static_cast<double>(m_tiles.value)}}}};
}

}  // namespace tessera
