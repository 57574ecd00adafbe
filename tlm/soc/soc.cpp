#include "soc/soc.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/log.h"
#include "soc/memory_map.h"

namespace tessera {

using sc_core::sc_time;

namespace {

BusParams bus_params(const Config& config) {
  return BusParams::from_config(config);
}

MemoryParams memory_params(const Config& config) {
  MemoryParams p = MemoryParams::from_config(config);
  const BusParams bus = BusParams::from_config(config);
  p.clock_period = bus.clock_period;
  p.width_bytes = bus.width_bytes;
  return p;
}

HostParams host_params(const Config& config) {
  HostParams p = HostParams::from_config(config);
  p.cacheable_base = memory_map::sysmem.base;
  p.cacheable_size = static_cast<uint32_t>(MemoryParams::from_config(config).size_bytes);
  // A quantum of zero asks for synchronisation on every access: no run-ahead.
  if (config.get_uint("sim.quantum_ns") != 0)
    p.run_ahead = sc_core::sc_time(static_cast<double>(config.get_uint("sim.run_ahead_us")), sc_core::SC_US);
  return p;
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
  return p;
}

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
          EnergyModel::parameters()};
}

Soc::Soc(sc_core::sc_module_name name, const Config& config)
    : sc_core::sc_module(name),
      bus("bus", bus_params(config)),
      memory("memory", memory_params(config)),
      host("host", host_params(config)),
      display("display", display_params(config)),
      display_dma("display_dma", display_dma_params(config)),
      raster("raster", RasterizerParams::from_config(config)),
      array("array", ArrayParams::from_config(config)),
      ciu("ciu", ciu_params(config), array),
      m_energy_model(EnergyModel::from_config(config)),
      m_power_window(config.get_real("power.trace_window_us"), sc_core::SC_US),
      m_sleep_unused(config.get_bool("power.sleep_unused")) {
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

  for (const auto& region : memory_map::ALL_REGIONS) {
    if (region.base == memory_map::dma_regs.base && !config.get_bool("dma.enabled")) continue;
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
  display.on_request([this](const sc_time& when) { record_request(when); });
  display.on_frame([this](const Frame& frame) { record_frame(frame); });

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
  close_trace();
}

void Soc::finish() {
  wait(m_host_finished);
  while (host.exit_code() == 0 && display.frame_pending()) wait(display.frame_shown_event());
  m_done = true;
  close_power_window();
  sc_core::sc_stop();
}

void Soc::trace_to(const std::string& path_without_extension) {
  m_trace_path = path_without_extension + ".vcd";
  m_trace = sc_core::sc_create_vcd_trace_file(path_without_extension.c_str());
  if (!m_trace) throw std::runtime_error("cannot create VCD file " + m_trace_path);
  m_trace->set_time_unit(1, sc_core::SC_PS);
  for (Block* block : m_blocks) block->trace_signals(m_trace);
  // A window below the time resolution would never advance.
  if (m_power_window == sc_core::SC_ZERO_TIME) return;
  m_power_trace = std::make_unique<PowerTrace>(m_energy_model);
  host.attribute_activity_in_time();
  const EnergyActivity units = energy_activity(sc_core::SC_ZERO_TIME);
  m_power_milliwatts.assign(units.size() + 1, 0.0);
  const std::string scope = std::string(name()) + ".power.";
  for (size_t i = 0; i < units.size(); ++i) sc_core::sc_trace(m_trace, m_power_milliwatts[i], scope + units[i].unit);
  sc_core::sc_trace(m_trace, m_power_milliwatts.back(), scope + "total");
}

void Soc::trace_power() {
  if (!m_power_trace) return;
  for (;;) {
    wait(m_power_window);
    close_power_window();
  }
}

void Soc::close_power_window() {
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

void Soc::close_trace() {
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

void Soc::record_request(const sc_time& when) {
  // The host's busy time is exact here: the request is the host's own
  // write. The bus has counted the host's transfers up to its time and the
  // DMAs' up to the kernel's, at most a quantum (sim.quantum_ns) behind.
  m_requests.push_back({when.to_seconds(), host.busy_time(), bus.bytes(), energy_activity(when)});
}

void Soc::record_frame(const Frame& frame) {
  // A frame comes from the last request before the vertical blank that took
  // it (DMA mode) or from its PRESENT (port mode); requests it replaced are
  // dropped.
  while (m_requests.size() > 1 && m_requests.front().seconds < frame.requested_seconds) m_requests.pop_front();
  Request request;
  if (m_requests.empty() || m_requests.front().seconds != frame.requested_seconds) {
    // Only software that bypasses the display's registers gets here.
    request = {frame.requested_seconds, host.busy_time(), bus.bytes(), energy_activity(sc_core::sc_time_stamp())};
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
  if (m_frame_sink) {
    const double previous = m_last_shown_seconds;
    m_last_shown_seconds = record.shown_seconds;
    m_frame_sink(frame_json(record, m_frames.size() + m_frames_streamed++, previous));
    return;
  }
  m_last_shown_seconds = record.shown_seconds;
  m_frames.push_back(std::move(record));
}

nlohmann::json Soc::frame_json(const FrameRecord& f, size_t index, double previous_shown_seconds) {
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

nlohmann::json Soc::frames_json() const {
  nlohmann::json frames = nlohmann::json::array();
  double previous_shown_seconds = 0;
  for (size_t i = 0; i < m_frames.size(); ++i) {
    frames.push_back(frame_json(m_frames[i], i, previous_shown_seconds));
    previous_shown_seconds = m_frames[i].shown_seconds;
  }
  return frames;
}

nlohmann::json Soc::array_stages_energy_json() const {
  nlohmann::json stages = nlohmann::json::object();
  for (ArrayProcessor::StageActivity& stage : array.stage_activity()) {
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

EnergyActivity Soc::energy_activity(const sc_time& now) const {
  EnergyActivity activity;
  for (const Block* block : m_blocks) {
    for (UnitActivity& unit : block->energy_activity(now)) {
      if (m_sleep_unused && block->sleeps()) unit.clocked_seconds = block->clocked_seconds(now);
      activity.push_back(std::move(unit));
    }
  }
  return activity;
}

nlohmann::json Soc::stats_json() const {
  const sc_time elapsed = sc_core::sc_time_stamp();
  nlohmann::json stats = {{"simulated_ns", elapsed.to_seconds() * 1e9}};
  for (const Block* block : m_blocks) stats[block->basename()] = block->stats_json(elapsed);
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
  stats["frames"] = frames_json();
  return stats;
}

}  // namespace tessera
