#include "soc/soc.h"

#include "common/log.h"
#include "soc/memory_map.h"
#include "soc/platform_params.h"
#include "zbuf/zbuf_regs.h"

namespace tessera {

using sc_core::sc_time;

namespace {

BusParams bus_params(const Config& config) {
  return BusParams::from_config(config);
}

MemoryParams memory_params(const Config& config) {
  return platform_memory_params(config, MemoryParams::from_config(config).size_bytes);
}

HostParams host_params(const Config& config) {
  return platform_host_params(config, memory_map::sysmem.base, MemoryParams::from_config(config).size_bytes);
}

DisplayParams display_params(const Config& config) {
  DisplayParams p = DisplayParams::from_config(config);
  p.clock_period = BusParams::from_config(config).clock_period;
  return p;
}

DisplayDmaParams display_dma_params(const Config& config) {
  DisplayDmaParams p = DisplayDmaParams::from_config(config);
  const DisplayParams display = DisplayParams::from_config(config);
  p.burst_bytes = p.burst_beats * BusParams::from_config(config).width_bytes;
  p.line_bytes = display.width * bytes_per_pixel(display.format);
  p.lines = display.height;
  return p;
}

// The rasterizer covers the display's screen.
RasterizerParams raster_params(const Config& config) {
  RasterizerParams p = RasterizerParams::from_config(config);
  const DisplayParams display = DisplayParams::from_config(config);
  p.width = display.width;
  p.height = display.height;
  return p;
}

CiuParams ciu_params(const Config& config) {
  CiuParams p = CiuParams::from_config(config);
  p.clock_period = ArrayParams::from_config(config).clock_period;
  return p;
}

DmaParams dma_params(const Config& config) {
  DmaParams p = DmaParams::from_config(config);
  const BusParams bus = BusParams::from_config(config);
  p.burst_bytes = p.burst_beats * bus.width_bytes;
  p.clock_period = bus.clock_period;
  p.cmem_clock_period = ArrayParams::from_config(config).clock_period;
  p.memory_base = memory_map::sysmem.base;
  p.memory_bytes = MemoryParams::from_config(config).size_bytes;
  if (config.get_bool("zbuf.enabled")) {
    p.readable_base = memory_map::zbuf_colour.base;
    p.readable_bytes = uint64_t{ZbufParams::from_config(config).core.entries} * zbuf_regs::COLOUR_ENTRY_BYTES;
  }
  return p;
}

}  // namespace

std::vector<ParamGroup> Soc::parameter_groups() {
  ParamGroup soc{
      "soc",
      {
          param::integer("sim.quantum_ns", 1000, 0, 1000000, "ns",
                         "temporal-decoupling quantum of the loosely-timed initiators (0: synchronise on every "
                         "access)"),
          param::integer("sim.run_ahead_us", 1000, 0, 1000000, "us",
                         "how far ahead of the kernel the host may run past its quantum while no other process has "
                         "anything scheduled that soon (0: always synchronise at the end of the quantum)"),
      },
      [](const Config& config) {
        const DisplayParams display = display_params(config);
        const uint64_t frame_bytes = uint64_t{display.width} * display.height * bytes_per_pixel(display.format);
        const uint64_t memory_bytes = MemoryParams::from_config(config).size_bytes;
        // Two frame buffers must fit in system memory, with room for everything else.
        if (2 * frame_bytes > memory_bytes / 2)
          throw ConfigError("configuration: impossible combination: two frame buffers of display.width=" +
                            std::to_string(display.width) + " x display.height=" + std::to_string(display.height) +
                            " display.format=" + pixel_format_name(display.format) + " pixels need " +
                            std::to_string(2 * frame_bytes) +
                            " bytes, more than half of mem.size_mib=" + std::to_string(memory_bytes >> 20));
        const DisplayDmaParams dma = display_dma_params(config);
        if (display.dma && dma.line_bytes % std::min(dma.burst_bytes, dma.line_bytes) != 0)
          throw ConfigError("configuration: impossible combination: a display line of " +
                            std::to_string(dma.line_bytes) +
                            " bytes is not a whole number of display_dma.burst_beats bursts (" +
                            std::to_string(dma.burst_bytes) + " bytes)");
      }};
  return {soc,
          HostParams::parameters(),
          BusParams::parameters(),
          MemoryParams::parameters(),
          DisplayParams::parameters(),
          DisplayDmaParams::parameters(),
          RasterizerParams::parameters(),
          ArrayParams::parameters(),
          CiuParams::parameters(),
          DmaParams::parameters(),
          ZbufParams::parameters(),
          EnergyModel::parameters()};
}

Soc::Soc(sc_core::sc_module_name name, const Config& config)
    : sc_core::sc_module(name),
      bus("bus", bus_params(config)),
      memory("memory", memory_params(config)),
      host("host", host_params(config)),
      display("display", display_params(config)),
      display_dma("display_dma", display_dma_params(config)),
      raster("raster", raster_params(config)),
      array("array", ArrayParams::from_config(config)),
      ciu("ciu", ciu_params(config), array),
      m_recorder(this->name(), config, {m_blocks, host, bus, array}),
      m_roi("roi", bus.params().clock_period,
            [this](bool begins, const sc_time& when) { m_recorder.roi_edge(begins, when); }) {
  config.validate();
  tlm_utils::tlm_quantumkeeper::set_global_quantum(
      sc_time(static_cast<double>(config.get_uint("sim.quantum_ns")), sc_core::SC_NS));

  // Initiators, in round-robin visiting order.
  bus.attach(host.out, "host", BusPriority::HOST);
  bus.attach(display_dma.out, "display_dma", BusPriority::DISPLAY_DMA);
  bus.attach(raster.mem_out, "raster", BusPriority::RASTER);

  // Targets, by the memory map.
  bus.map(memory.in, memory_map::sysmem.base, memory_map::sysmem.size, memory_map::sysmem.name);
  bus.map(display.in, memory_map::display_regs.base, memory_map::display_regs.size, memory_map::display_regs.name);
  bus.map(display.port_in, memory_map::display_port.base, memory_map::display_port.size, memory_map::display_port.name);
  bus.map(raster.in, memory_map::raster_regs.base, memory_map::raster_regs.size, memory_map::raster_regs.name);
  bus.map(array.in, memory_map::array_regs.base, memory_map::array_regs.size, memory_map::array_regs.name);
  bus.map(array.program_in, memory_map::array_program.base, memory_map::array_program.size,
          memory_map::array_program.name);
  bus.map(ciu.in, memory_map::array_cmem.base, memory_map::array_cmem.size, memory_map::array_cmem.name);
  bus.map(m_roi.in, memory_map::sim_control.base, memory_map::sim_control.size, memory_map::sim_control.name);

  for (const auto& region : memory_map::ALL_REGIONS) {
    if (region.base == memory_map::dma_regs.base && !config.get_bool("dma.enabled")) continue;
    if ((region.base == memory_map::zbuf_regs.base || region.base == memory_map::zbuf_colour.base) &&
        !config.get_bool("zbuf.enabled"))
      continue;
    if (region.base == memory_map::intc.base && !host.params().iss) continue;
    log::info(basename(), std::string("memory map: ") + region.name + " at " + log::hex(region.base) + ", " +
                              std::to_string(region.size) + " bytes");
  }

  // Interrupts: every host line gets a signal; sources drive theirs.
  for (unsigned i = 0; i < host.irq.size(); ++i) {
    m_irq_lines.push_back(std::make_unique<sc_core::sc_signal<bool>>(("irq_line_" + std::to_string(i)).c_str(), false));
    host.irq[i].bind(*m_irq_lines.back());
  }
  // Every source in irq_map.def has its line: host.irq_lines is at least
  // irq_map::MIN_HOST_LINES, which irq_map.h checks each line against.
  display.irq.bind(*m_irq_lines[irq_map::display]);
  raster.irq.bind(*m_irq_lines[irq_map::raster]);
  array.irq.bind(*m_irq_lines[irq_map::array]);

  display.connect_dma(display_dma);
  display.on_request([this](const sc_time& when) { m_recorder.record_request(when); });
  display.on_frame([this](const Frame& frame) { m_recorder.record_frame(frame); });

  m_blocks = {&host, &bus, &memory, &display, &display_dma, &raster, &array, &ciu};

  if (config.get_bool("dma.enabled")) {
    dma = std::make_unique<Dma>("dma", dma_params(config));
    bus.attach(dma->out, "dma", BusPriority::DMA);
    bus.map(dma->in, memory_map::dma_regs.base, memory_map::dma_regs.size, memory_map::dma_regs.name);
    dma->irq.bind(*m_irq_lines[irq_map::dma]);
    dma->connect_cmem(array);
    const size_t initiator = bus.initiator_stats().size() - 1;
    dma->set_bus_wait_probe([this, initiator] { return bus.initiator_stats()[initiator].wait_cycles; });
    m_blocks.push_back(dma.get());
  }

  if (config.get_bool("zbuf.enabled")) {
    zbuf = std::make_unique<ZbufUnit>("zbuf", ZbufParams::from_config(config), array);
    bus.map(zbuf->in, memory_map::zbuf_regs.base, memory_map::zbuf_regs.size, memory_map::zbuf_regs.name);
    bus.map(zbuf->colour_in, memory_map::zbuf_colour.base, memory_map::zbuf_colour.size, memory_map::zbuf_colour.name);
    array.core().set_pixel_port(zbuf.get());
    m_blocks.push_back(zbuf.get());
  }

  if (host.params().iss) {
    // The ISS's software reads the lines and waits for them through the
    // interrupt controller, on the bus clock.
    intc = std::make_unique<InterruptController>("intc", bus.params().clock_period, host.irq.size());
    bus.map(intc->in, memory_map::intc.base, memory_map::intc.size, memory_map::intc.name);
    for (unsigned i = 0; i < host.irq.size(); ++i) intc->lines[i].bind(*m_irq_lines[i]);
    m_core_irq = std::make_unique<sc_core::sc_signal<bool>>("core_irq", false);
    m_core_fiq = std::make_unique<sc_core::sc_signal<bool>>("core_fiq", false);
    intc->irq.bind(*m_core_irq);
    intc->fiq.bind(*m_core_fiq);
    host.core_irq.bind(*m_core_irq);
    host.core_fiq.bind(*m_core_fiq);
    m_blocks.push_back(intc.get());
  }

  host.on_finish([this] { m_host_finished.notify(sc_core::SC_ZERO_TIME); });
  SC_THREAD(finish);
  SC_THREAD(trace_power);
}

Soc::~Soc() {
  m_recorder.close_trace();
}

void Soc::finish() {
  wait(m_host_finished);
  while (host.exit_code() == 0 && display.frame_pending()) wait(display.frame_shown_event());
  m_done = true;
  m_recorder.close_power_window();
  sc_core::sc_stop();
}

void Soc::trace_power() {
  m_recorder.trace_power();
}

}  // namespace tessera
