#include "display/display_controller.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "common/log.h"
#include "common/loosely_timed.h"
#include "common/ticks_time.h"
#include "display/display_regs.h"

namespace tessera {

using sc_core::sc_time;
namespace regs = display_regs;

DisplayController::DisplayController(sc_core::sc_module_name name, const DisplayParams& params)
    : Peripheral(name, params.clock_period),
      port_in("port_in"),
      m_params(params),
      m_frames(counter("frames_shown", "distinct frames shown")),
      m_refreshes(counter("refreshes", "refresh periods completed (DMA mode)")),
      m_port_bytes(counter("port_bytes", "bytes written to the display port (port mode)")),
      m_vblank("vblank") {
  if (params.width == 0 || params.height == 0) throw std::invalid_argument(std::string(this->name()) + ": empty frame");
  if (params.refresh_hz <= 0)
    throw std::invalid_argument(std::string(this->name()) + ": refresh rate must be positive");
  port_in.bind(m_port);

  STATUS.on_read(this, &DisplayController::read_STATUS);
  SWAP.on_write(this, &DisplayController::write_SWAP);
  bind_irq_registers(IRQ_STATUS, IRQ_ENABLE);
  PRESENT.on_write(this, &DisplayController::write_PRESENT);
  FRAMES.on_read(this, &DisplayController::read_FRAMES);
  REFRESHES.on_read(this, &DisplayController::read_REFRESHES);
  UNDERRUNS.on_read(this, &DisplayController::read_UNDERRUNS);
  WIDTH.set_reset(m_params.width);
  HEIGHT.set_reset(m_params.height);
  FORMAT.set_reset(static_cast<uint32_t>(m_params.format));
  MODE.set_reset(m_params.dma ? 1u : 0u);

  m_port_frame.assign(frame_bytes(), 0);

  if (m_params.dma) SC_THREAD(refresh);
}

uint32_t DisplayController::read_STATUS() const {
  return (in_vblank() ? regs::STATUS_VBLANK : 0u) | (m_swap_pending ? regs::STATUS_SWAP_PENDING : 0u);
}

void DisplayController::write_SWAP(uint32_t value) {
  if (!(value & 1)) return;
  if (!m_params.dma) {
    log::warning(name(), "SWAP written in port mode (display.dma=false); ignored, use PRESENT");
    return;
  }
  m_swap_pending = true;
  m_swap_requested = sc_core::sc_time_stamp() + m_regs.access_delay();
  requested(m_swap_requested);
}

void DisplayController::write_PRESENT(uint32_t value) {
  if (!(value & 1)) return;
  if (m_params.dma) {
    log::warning(name(), "PRESENT written in DMA mode (display.dma=true); ignored, use SWAP");
    return;
  }
  requested(sc_core::sc_time_stamp() + m_regs.access_delay());
  show(m_port_frame, sc_core::sc_time_stamp() + m_regs.access_delay(), m_regs.access_delay());
  raise_irq(regs::IRQ_FRAME_PRESENTED, m_regs.access_delay());
}

uint32_t DisplayController::read_FRAMES() const {
  return static_cast<uint32_t>(m_frames.value);
}

uint32_t DisplayController::read_REFRESHES() const {
  return static_cast<uint32_t>(m_refreshes.value);
}

uint32_t DisplayController::read_UNDERRUNS() const {
  return static_cast<uint32_t>(underruns());
}

void DisplayController::trace_signals(sc_core::sc_trace_file* file) {
  sc_core::sc_trace(file, m_vblank.signal, std::string(name()) + ".vblank");
}

bool DisplayController::in_vblank() const {
  const sc_time now = sc_core::sc_time_stamp();
  return m_params.dma && now >= m_frame_start && now < m_active_start;
}

bool DisplayController::frame_pending() const {
  return m_params.dma && (m_swap_pending || m_frame_in_scan);
}

bool DisplayController::port_b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) {
  const uint64_t address = gp.get_address();
  const uint64_t length = gp.get_data_length();
  if (address >= m_port_frame.size() || length > m_port_frame.size() - address) {
    gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    log::warning(name(), "display port access outside the " + std::to_string(m_port_frame.size()) +
                             "-byte frame at offset " + log::hex(address));
    return false;
  }
  if (gp.get_byte_enable_ptr() || gp.get_streaming_width() < length) {
    gp.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    return false;
  }
  if (gp.is_write()) {
    std::memcpy(&m_port_frame[address], gp.get_data_ptr(), length);
    m_port_bytes += length;
  } else if (gp.is_read()) {
    std::memcpy(gp.get_data_ptr(), &m_port_frame[address], length);
  }
  delay += ticks_time(port_ticks(length));
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
  return true;
}

bool DisplayController::port_quote(tlm::tlm_command command, uint64_t address, unsigned bytes, size_t count,
                                   uint64_t& latency_ticks, bool& untouched) const {
  if (command != tlm::TLM_WRITE_COMMAND || bytes == 0 || count == 0 || address >= m_port_frame.size() ||
      count > (m_port_frame.size() - address) / bytes)
    return false;
  latency_ticks = port_ticks(bytes);
  untouched = true;  // a port write schedules nothing (ScheduleUntouched)
  return true;
}

void DisplayController::port_write_accesses(uint64_t address, const uint8_t* data, unsigned bytes, size_t count) {
  const uint64_t length = uint64_t{bytes} * count;
  std::memcpy(&m_port_frame[address], data, length);
  m_port_bytes += length;
}

tlm::tlm_sync_enum DisplayController::Port::nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& /*phase*/,
                                                            sc_time& /*delay*/) {
  return refuse_non_blocking(m_display.name(), gp);
}

unsigned DisplayController::port_transport_dbg(tlm::tlm_generic_payload& gp) {
  const uint64_t address = gp.get_address();
  if (address >= m_port_frame.size()) return 0;
  const uint64_t length = std::min<uint64_t>(gp.get_data_length(), m_port_frame.size() - address);
  if (gp.is_write())
    std::memcpy(&m_port_frame[address], gp.get_data_ptr(), length);
  else if (gp.is_read())
    std::memcpy(gp.get_data_ptr(), &m_port_frame[address], length);
  return static_cast<unsigned>(length);
}

void DisplayController::requested(const sc_time& when) {
  for (const auto& receiver : m_request_receivers) receiver(when);
}

void DisplayController::show(const std::vector<uint8_t>& pixels, const sc_time& requested, const sc_time& delay) {
  const sc_time when = sc_core::sc_time_stamp() + delay;
  Frame frame{static_cast<unsigned>(m_frames.value),
              when.to_seconds(),
              requested.to_seconds(),
              m_params.width,
              m_params.height,
              {}};
  if (m_keep_pixels) {
    const size_t count = size_t{m_params.width} * m_params.height;
    const unsigned bpp = bytes_per_pixel();
    frame.rgba.resize(count * 4);
    for (size_t i = 0; i < count; ++i) {
      const uint32_t rgba = unpack_pixel(m_params.format, load_pixel(m_params.format, &pixels[i * bpp]));
      for (unsigned c = 0; c < 4; ++c) frame.rgba[4 * i + c] = static_cast<uint8_t>(rgba >> (8 * c));
    }
  }
  if (m_timeline)
    m_timeline->slice(m_frame_track, "frame " + std::to_string(frame.index),
                      m_frames.value == 0 ? sc_core::SC_ZERO_TIME : m_last_frame_time, when,
                      {{"requested_ns", requested.to_seconds() * 1e9}});
  if (m_frames.value == 0) m_first_frame_time = when;
  m_last_frame_time = when;
  ++m_frames;
  log::info(name(), "frame " + std::to_string(frame.index) + " shown");
  for (const auto& receiver : m_receivers) receiver(frame);
  m_frame_shown.notify(delay);
}

void DisplayController::connect_dma(DisplayDma& dma) {
  if (dma.params().line_bytes != m_params.width * bytes_per_pixel() || dma.params().lines != m_params.height)
    throw std::invalid_argument(std::string(name()) + ": the display DMA " + dma.name() +
                                " fetches frames of another size than this display's");
  m_dma = &dma;
}

void DisplayController::end_of_elaboration() {
  if (m_params.dma && !m_dma)
    throw std::logic_error(std::string(name()) + ": DMA mode without a display DMA (connect_dma)");
}

void DisplayController::refresh() {
  const sc_time period(1.0 / m_params.refresh_hz, sc_core::SC_SEC);
  const sc_time line_time = period / static_cast<double>(m_params.height + m_params.vblank_lines);
  for (;;) {
    // A refresh period: vertical blank, then the visible lines. A requested
    // swap takes effect at the start of the blank.
    m_frame_start = sc_core::sc_time_stamp();
    m_active_start = m_frame_start + line_time * static_cast<double>(m_params.vblank_lines);
    const sc_time frame_end = m_frame_start + period;
    m_vblank.set_at(true, m_frame_start);
    m_vblank.set_at(false, m_active_start);
    if (m_timeline) m_timeline->slice(m_vblank_track, "vblank", m_frame_start, m_active_start);
    bool new_frame = false;
    if (m_swap_pending) {
      FRONT_BASE.set(BACK_BASE.get());
      m_swap_pending = false;
      m_scan_requested = m_swap_requested;
      m_front_valid = true;
      new_frame = true;
      raise_irq(regs::IRQ_SWAP_DONE);
    }
    raise_irq(regs::IRQ_VBLANK);
    const bool scanning = m_front_valid && (CTRL.get() & regs::CTRL_ENABLE);
    m_frame_in_scan = scanning && new_frame;
    if (scanning) {
      m_dma->start_frame(FRONT_BASE.get(), m_active_start, line_time);
      wait(m_dma->frame_fetched_event());
    }
    if (sc_core::sc_time_stamp() < frame_end) wait(frame_end - sc_core::sc_time_stamp());
    ++m_refreshes;
    if (m_frame_in_scan) show(m_dma->frame(), m_scan_requested);
    m_frame_in_scan = false;
  }
}

void DisplayController::timeline_to(TimelineSink& sink) {
  m_timeline = &sink;
  m_frame_track = sink.track(name(), "frames");
  if (m_params.dma) m_vblank_track = sink.track(name(), "vblank");
}

nlohmann::json DisplayController::stats_json(const sc_time& elapsed) const {
  double rate = 0;
  if (m_frames.value > 1) {
    const double span = (m_last_frame_time - m_first_frame_time).to_seconds();
    if (span > 0) rate = (m_frames.value - 1) / span;
  }
  nlohmann::json stats = Peripheral::stats_json(elapsed);
  stats["mode"] = m_params.dma ? "dma" : "port";
  stats["width"] = m_params.width;
  stats["height"] = m_params.height;
  stats["format"] = pixel_format_name(m_params.format);
  stats["achieved_fps"] = rate;
  stats["refresh_hz"] = m_params.dma ? m_params.refresh_hz : 0.0;
  stats["elapsed_ns"] = elapsed.to_seconds() * 1e9;
  return stats;
}

void DisplayController::describe_stats(StatsSchema& schema) const {
  Peripheral::describe_stats(schema);
  schema.add("width", "pixels", "width of the screen");
  schema.add("height", "pixels", "height of the screen");
  schema.add("achieved_fps", "Hz",
             "frames shown per second, between the first and the last frame shown (0 below two frames)");
  schema.add("refresh_hz", "Hz", "the panel's refresh rate in DMA mode (display.refresh_hz); 0 in port mode");
  schema.add("elapsed_ns", "ns", "simulated time of the run");
}

SummaryRow DisplayController::summary_row(const sc_time& elapsed) const {
  const nlohmann::json stats = stats_json(elapsed);
  char notes[128];
  std::snprintf(notes, sizeof notes, "%llu frames shown, %.1f frames/s achieved, %llu underrun lines",
                static_cast<unsigned long long>(m_frames.value), stats["achieved_fps"].get<double>(),
                static_cast<unsigned long long>(underruns()));
  return {std::nullopt, std::nullopt, notes};
}

EnergyActivity DisplayController::energy_activity(const sc_time& now) const {
  (void)now;
  return {{"display", {{"port_bytes", static_cast<double>(m_port_bytes.value)}}}};
}

}  // namespace tessera
