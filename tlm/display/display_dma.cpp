#include "display/display_dma.h"

#include <stdexcept>
#include <string>

namespace tessera {

using sc_core::sc_time;

DisplayDma::DisplayDma(sc_core::sc_module_name name, const DisplayDmaParams& params)
    : Block(name),
      out("out", activity()),
      m_params(params),
      m_frames_fetched(counter("frames_fetched", "frames scanned out (one per refresh period while enabled)")),
      m_lines_fetched(counter("lines_fetched", "lines fetched")),
      m_underrun_lines(counter("underrun_lines", "lines that arrived after they were due on screen")),
      m_underrun_frames(counter("underrun_frames", "frames with at least one underrun line")) {
  sleeps_until_used();
  if (params.line_bytes == 0 || params.lines == 0)
    throw std::invalid_argument(std::string(this->name()) + ": empty frame");
  if (params.fifo_lines == 0) throw std::invalid_argument(std::string(this->name()) + ": fifo_lines must be positive");
  out.configure(params.burst_bytes, BusMaster::OnError::zeros_and_continue);
  m_frame.assign(size_t{params.line_bytes} * params.lines, 0);
  SC_THREAD(scan_out);
  sensitive << m_start;
  dont_initialize();
}

void DisplayDma::start_frame(uint32_t base, sc_time first_line_due, sc_time line_time) {
  if (m_fetching) throw std::logic_error(std::string(name()) + ": a frame was started before the last one was fetched");
  m_fetching = true;
  mark_used();
  m_base = base;
  m_first_line_due = first_line_due;
  m_line_time = line_time;
  m_start.notify();
}

bool DisplayDma::fetch_line(uint32_t address, uint8_t* line, const sc_time& due) {
  sc_time delay = sc_core::SC_ZERO_TIME;
  out.transfer(tlm::TLM_READ_COMMAND, address, line, m_params.line_bytes, delay);
  const sc_time done = sc_core::sc_time_stamp() + delay;
  wait(delay);
  ++m_lines_fetched;
  return done <= due;
}

void DisplayDma::scan_out() {
  for (;;) {
    const sc_time lead = m_line_time * static_cast<double>(m_params.fifo_lines);
    bool underrun = false;
    for (unsigned y = 0; y < m_params.lines; ++y) {
      // The line buffer holds fifo_lines lines: line y may be fetched once
      // line y - fifo_lines has gone to the screen.
      const sc_time due = m_first_line_due + m_line_time * static_cast<double>(y);
      const sc_time earliest = due > lead ? due - lead : sc_core::SC_ZERO_TIME;
      if (earliest > sc_core::sc_time_stamp()) wait(earliest - sc_core::sc_time_stamp());
      if (!fetch_line(m_base + y * m_params.line_bytes, &m_frame[size_t{y} * m_params.line_bytes], due)) {
        ++m_underrun_lines;
        underrun = true;
      }
    }
    if (underrun) ++m_underrun_frames;
    ++m_frames_fetched;
    m_fetching = false;
    m_fetched.notify();
    wait();
  }
}

nlohmann::json DisplayDma::stats_json(const sc_time& elapsed) const {
  nlohmann::json stats = Block::stats_json(elapsed);
  stats["burst_bytes"] = m_params.burst_bytes;
  stats["fifo_lines"] = m_params.fifo_lines;
  add_busy_stats(stats, out.bus_time(), elapsed);
  return stats;
}

void DisplayDma::describe_stats(StatsSchema& schema) const {
  Block::describe_stats(schema);
  schema.add_setting("burst_bytes", "bytes", "length of the DMA's bus bursts (display_dma.burst_bytes)");
  schema.add_setting("fifo_lines", "count", "lines the line FIFO holds (display_dma.fifo_lines)");
  describe_busy_stats(schema, "time the DMA's bus transfers took");
}

SummaryRow DisplayDma::summary_row(const sc_time& elapsed) const {
  return busy_row(out.bus_time(), elapsed,
                  std::to_string(m_frames_fetched.value) + " frames fetched, " + std::to_string(m_lines_fetched.value) +
                      " lines, " + std::to_string(m_underrun_lines.value) + " underrun lines");
}

EnergyActivity DisplayDma::energy_activity(const sc_time& now) const {
  (void)now;
  return {{"display_dma", {{"bytes", static_cast<double>(counters().value("bus.bytes_read"))}}}};
}

}  // namespace tessera
