// The display DMA: the display's scan-out engine in DMA mode
// (display.dma=true, the proposed hardware). Once per refresh period the
// display controller hands it the front buffer and the time its first
// visible line is due on screen; the DMA fetches the frame over the bus,
// line by line, each line no earlier than fifo_lines line times before it
// is due (its line buffer holds fifo_lines lines), as bursts of burst_bytes
// through its own bus-master socket. A line that arrives after it is due is
// an underrun. The frame it fetched is what the controller shows at the end
// of the period.
#pragma once

#include <cstdint>
#include <vector>

#include <systemc>

#include <nlohmann/json.hpp>

#include "common/block.h"
#include "common/bus_master.h"
#include "config/config.h"

namespace tessera {

struct DisplayDmaParams {
  unsigned burst_beats = 0;
  unsigned fifo_lines = 0;
  unsigned burst_bytes = 0;  // set by the SoC: burst_beats words of the bus
  unsigned line_bytes = 0;   // set by the SoC: display.width pixels of display.format
  unsigned lines = 0;        // set by the SoC: display.height

  // The parameters this block owns (the one place their defaults live),
  // read back from a configuration that holds them; fields marked "set by the
  // SoC" are other blocks' values and stay zero here.
  static ParamGroup parameters();
  static DisplayDmaParams from_config(const Config& config);
  // from_config of the defaults alone.
  static DisplayDmaParams defaults();
};

class DisplayDma : public Block {
 public:
  SC_HAS_PROCESS(DisplayDma);

  BusMaster out;  // bus initiator display_dma

  DisplayDma(sc_core::sc_module_name name, const DisplayDmaParams& params);

  const DisplayDmaParams& params() const { return m_params; }

  // Fetches the frame at `base`: line y is due at first_line_due + y x
  // line_time (absolute times). frame_fetched_event() is notified when the
  // last line has arrived; a frame must not be started before the previous
  // one is fetched (std::logic_error).
  void start_frame(uint32_t base, sc_core::sc_time first_line_due, sc_core::sc_time line_time);
  const sc_core::sc_event& frame_fetched_event() const { return m_fetched; }
  // The last frame fetched, lines top to bottom, in the display's format.
  const std::vector<uint8_t>& frame() const { return m_frame; }
  uint64_t underrun_lines() const { return m_underrun_lines.value; }

  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  void scan_out();  // SC_THREAD: one frame per start_frame
  // Fetches one line; true if it arrived by `due`.
  bool fetch_line(uint32_t address, uint8_t* line, const sc_core::sc_time& due);

  DisplayDmaParams m_params;
  // The frame being fetched is a member, not a local: the thread never
  // returns, and its stack is not unwound at the end of the simulation.
  std::vector<uint8_t> m_frame;
  sc_core::sc_event m_start;
  sc_core::sc_event m_fetched;
  bool m_fetching = false;
  uint32_t m_base = 0;
  sc_core::sc_time m_first_line_due;
  sc_core::sc_time m_line_time;
  ActivityCounter& m_frames_fetched;
  ActivityCounter& m_lines_fetched;
  ActivityCounter& m_underrun_lines;
  ActivityCounter& m_underrun_frames;
};

}  // namespace tessera
