#include "soc/soc.h"

#include <cstdio>
#include <fstream>

#include "common/log.h"
#include "soc/memory_map.h"

namespace tessera {

using sc_core::sc_time;

namespace {
sc_time period_of_mhz(double mhz) {
  return sc_time(1e3 / mhz, sc_core::SC_NS);
}
}  // namespace

BusParams bus_params(const Config& config) {
  BusParams p;
  p.clock_period = period_of_mhz(config.get_real("bus.clock_mhz"));
  p.arbitration = parse_arbitration(config.get_string("bus.arbitration"));
  p.width_bytes = static_cast<unsigned>(config.get_uint("bus.width_bits") / 8);
  p.address_cycles = static_cast<unsigned>(config.get_uint("bus.address_cycles"));
  p.error_cycles = static_cast<unsigned>(config.get_uint("bus.error_cycles"));
  return p;
}

MemoryParams memory_params(const Config& config) {
  MemoryParams p;
  p.size_bytes = config.get_uint("mem.size_mib") << 20;
  p.clock_period = period_of_mhz(config.get_real("bus.clock_mhz"));
  p.width_bytes = static_cast<unsigned>(config.get_uint("bus.width_bits") / 8);
  p.first_access_cycles = static_cast<unsigned>(config.get_uint("mem.first_access_cycles"));
  p.beat_cycles = static_cast<unsigned>(config.get_uint("mem.beat_cycles"));
  return p;
}

HostParams host_params(const Config& config) {
  HostParams p;
  p.clock_period = period_of_mhz(config.get_real("host.clock_mhz"));
  auto cycles = [&](Op op, const char* key) {
    p.op_cycles[static_cast<size_t>(op)] = static_cast<unsigned>(config.get_uint(std::string("host.cycles.") + key));
  };
  cycles(Op::alu, "alu");
  cycles(Op::load_use, "load_use");
  cycles(Op::mul, "mul");
  cycles(Op::branch, "branch");
  cycles(Op::call, "call");
  cycles(Op::fadd, "fadd");
  cycles(Op::fmul, "fmul");
  cycles(Op::fdiv, "fdiv");
  cycles(Op::fsqrt, "fsqrt");
  cycles(Op::fcmp, "fcmp");
  cycles(Op::fconv, "fconv");
  p.load_cycles = static_cast<unsigned>(config.get_uint("host.cycles.load"));
  p.store_cycles = static_cast<unsigned>(config.get_uint("host.cycles.store"));
  p.dcache_bytes = static_cast<unsigned>(config.get_uint("host.dcache.size_bytes"));
  p.dcache_line_bytes = static_cast<unsigned>(config.get_uint("host.dcache.line_bytes"));
  p.dcache_ways = static_cast<unsigned>(config.get_uint("host.dcache.ways"));
  p.write_buffer_words = static_cast<unsigned>(config.get_uint("host.write_buffer.entries"));
  p.irq_lines = static_cast<unsigned>(config.get_uint("host.irq_lines"));
  p.cacheable_base = memory_map::sysmem.base;
  p.cacheable_size = static_cast<uint32_t>(config.get_uint("mem.size_mib") << 20);
  // A quantum of zero asks for synchronisation on every access: no run-ahead.
  if (config.get_uint("sim.quantum_ns") != 0)
    p.run_ahead = sc_core::sc_time(static_cast<double>(config.get_uint("sim.run_ahead_us")), sc_core::SC_US);
  return p;
}

DisplayParams display_params(const Config& config) {
  DisplayParams p;
  p.width = static_cast<unsigned>(config.get_uint("display.width"));
  p.height = static_cast<unsigned>(config.get_uint("display.height"));
  p.format = *pixel_format_from_name(config.get_string("display.format"));
  p.dma = config.get_bool("display.dma");
  p.refresh_hz = config.get_real("display.refresh_hz");
  p.vblank_lines = static_cast<unsigned>(config.get_uint("display.vblank_lines"));
  p.burst_bytes = static_cast<unsigned>(config.get_uint("display.burst_beats") * config.get_uint("bus.width_bits") / 8);
  p.fifo_lines = static_cast<unsigned>(config.get_uint("display.fifo_lines"));
  p.clock_period = period_of_mhz(config.get_real("bus.clock_mhz"));
  return p;
}

RasterizerParams rasterizer_params(const Config& config) {
  RasterizerParams p;
  p.width = static_cast<unsigned>(config.get_uint("raster.width"));
  p.height = static_cast<unsigned>(config.get_uint("raster.height"));
  p.tile_width = static_cast<unsigned>(config.get_uint("raster.tile_width"));
  p.tile_height = static_cast<unsigned>(config.get_uint("raster.tile_height"));
  const uint64_t method = config.get_uint("raster.recip_method");
  p.recip_method = method == 1   ? raster::RecipMethod::method1
                   : method == 2 ? raster::RecipMethod::method2
                                 : raster::RecipMethod::method3;
  p.burst_beats = static_cast<unsigned>(config.get_uint("raster.burst_beats"));
  auto cycles = [&](const char* key) {
    return static_cast<unsigned>(config.get_uint(std::string("raster.cycles.") + key));
  };
  p.costs.command = cycles("command");
  p.costs.setup = cycles("setup");
  p.costs.tile_start = cycles("tile_start");
  p.costs.tile_pixel_clear = cycles("tile_pixel_clear");
  p.costs.fragment = cycles("fragment");
  p.costs.texel = cycles("texel");
  p.costs.tile_write_word = cycles("tile_write_word");
  p.clock_period = period_of_mhz(config.get_real("raster.clock_mhz"));
  return p;
}

Soc::Soc(sc_core::sc_module_name name, const Config& config)
    : sc_core::sc_module(name),
      bus("bus", bus_params(config)),
      memory("memory", memory_params(config)),
      host("host", host_params(config)),
      display("display", display_params(config)),
      raster("raster", rasterizer_params(config)) {
  config.validate();
  tlm_utils::tlm_quantumkeeper::set_global_quantum(
      sc_time(static_cast<double>(config.get_uint("sim.quantum_ns")), sc_core::SC_NS));

  // Initiators, in round-robin visiting order.
  bus.attach(host.out, "host", BusPriority::HOST);
  bus.attach(display.dma_out, "display_dma", BusPriority::DISPLAY_DMA);
  bus.attach(raster.mem_out, "raster", BusPriority::RASTER);

  // Targets, by the memory map.
  bus.map(memory.in, memory_map::sysmem.base, memory_map::sysmem.size, memory_map::sysmem.name);
  bus.map(display.in, memory_map::display_regs.base, memory_map::display_regs.size, memory_map::display_regs.name);
  bus.map(display.port_in, memory_map::display_port.base, memory_map::display_port.size, memory_map::display_port.name);
  bus.map(raster.in, memory_map::raster_regs.base, memory_map::raster_regs.size, memory_map::raster_regs.name);

  for (const auto& region : memory_map::ALL_REGIONS)
    log::info(basename(), std::string("memory map: ") + region.name + " at " + log::hex(region.base) + ", " +
                              std::to_string(region.size) + " bytes");

  // Interrupts: every host line gets a signal; sources drive theirs.
  for (unsigned i = 0; i < host.irq.size(); ++i) {
    m_irq_lines.push_back(std::make_unique<sc_core::sc_signal<bool>>(("irq_line_" + std::to_string(i)).c_str(), false));
    host.irq[i].bind(*m_irq_lines.back());
  }
  // host.irq_lines is at least 4 (parameters.cpp), so every source in irq_map.def has its line.
  static_assert(irq_map::display < 4 && irq_map::raster < 4,
                "interrupt sources must use lines below host.irq_lines' minimum");
  display.irq.bind(*m_irq_lines[irq_map::display]);
  raster.irq.bind(*m_irq_lines[irq_map::raster]);

  host.on_finish([this] { m_host_finished.notify(sc_core::SC_ZERO_TIME); });
  SC_THREAD(finish);
}

Soc::~Soc() {
  close_trace();
}

uint32_t Soc::frame_buffer(unsigned index) const {
  const uint64_t memory_bytes = memory.size();
  const uint64_t frame = (display.frame_bytes() + 4095) / 4096 * 4096;
  return static_cast<uint32_t>(memory_map::sysmem.base + memory_bytes - frame * (2 - index));
}

void Soc::finish() {
  wait(m_host_finished);
  while (host.exit_code() == 0 && display.frame_pending()) wait(display.frame_shown_event());
  m_done = true;
  sc_core::sc_stop();
}

void Soc::trace_to(const std::string& path_without_extension) {
  m_trace_path = path_without_extension + ".vcd";
  m_trace = sc_core::sc_create_vcd_trace_file(path_without_extension.c_str());
  if (!m_trace) throw std::runtime_error("cannot create VCD file " + m_trace_path);
  m_trace->set_time_unit(1, sc_core::SC_PS);
  bus.trace_signals(m_trace);
  host.trace_signals(m_trace);
  display.trace_signals(m_trace);
  raster.trace_signals(m_trace);
}

void Soc::close_trace() {
  if (!m_trace) return;
  sc_core::sc_close_vcd_trace_file(m_trace);
  m_trace = nullptr;
  // SystemC writes the wall-clock date into the header; replace it with a
  // fixed text of the same length so that identical runs give identical files.
  std::fstream file(m_trace_path, std::ios::in | std::ios::out | std::ios::binary);
  std::string head(512, '\0');
  file.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(file.gcount()));
  const auto date = head.find("$date");
  const auto end = date == std::string::npos ? std::string::npos : head.find("$end", date);
  if (end != std::string::npos) {
    std::string replacement = head.substr(date, end - date);
    for (size_t i = 5; i < replacement.size(); ++i)
      if (replacement[i] != '\n' && replacement[i] != ' ') replacement[i] = '-';
    file.clear();
    file.seekp(static_cast<std::streamoff>(date));
    file.write(replacement.data(), static_cast<std::streamsize>(replacement.size()));
  }
}

nlohmann::json Soc::stats_json() const {
  const sc_time elapsed = sc_core::sc_time_stamp();
  return {{"simulated_ns", elapsed.to_seconds() * 1e9},
          {"host", host.stats_json(elapsed)},
          {"bus", bus.stats_json(elapsed)},
          {"memory", memory.stats_json(elapsed)},
          {"display", display.stats_json(elapsed)},
          {"raster", raster.stats_json(elapsed)}};
}

}  // namespace tessera
