// Display controller: the display's registers, its port and its frame
// output, with two ways to get a frame on screen:
//  - port mode (display.dma=false, as on the J2210): the host copies the
//    finished frame into the display port window and writes PRESENT; the
//    host's time for the copy is its own cost.
//  - DMA mode (display.dma=true, the proposed hardware): the controller
//    times the refresh periods (vertical blank, then the visible lines) and
//    has the display DMA (display_dma.h), its scan-out engine, fetch the
//    front buffer over the bus once per period. The host draws into the
//    back buffer and requests a SWAP, which takes effect at the next
//    vertical blank.
// Every distinct frame shown goes to the output port: a callback that
// soc_sim turns into a PNG file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "common/direct_transport.h"
#include "common/peripheral.h"
#include "common/pixel_format.h"
#include "common/schedule_untouched.h"
#include "common/timed_trace.h"
#include "config/config.h"
#include "display/display_dma.h"

namespace tessera {

struct DisplayParams {
  unsigned width = 0;
  unsigned height = 0;
  PixelFormat format = PixelFormat::rgb565;
  bool dma = false;
  double refresh_hz = 0;
  unsigned vblank_lines = 0;
  sc_core::sc_time clock_period;  // set by the SoC: the bus clock
  unsigned port_cycles = 0;       // cycles the display port takes per 32-bit word written (the data phase)

  // The parameters this block owns (the one place their defaults live),
  // read back from a configuration that holds them; fields marked "set by the
  // SoC" are other blocks' values and stay zero here.
  static ParamGroup parameters();
  static DisplayParams from_config(const Config& config);
  // from_config of the defaults alone.
  static DisplayParams defaults();
};

struct Frame {
  unsigned index;       // 0, 1, 2, ... in the order shown
  double time_seconds;  // simulated time at which it was complete on screen
  // When software handed it to the display: the time of the SWAP write (DMA
  // mode; the last one before the vertical blank that took it) or of the
  // PRESENT write (port mode, the same as time_seconds).
  double requested_seconds;
  unsigned width;
  unsigned height;
  std::vector<uint8_t> rgba;  // width * height * 4, row 0 at the top
};

class DisplayController : public Peripheral {
 public:
  SC_HAS_PROCESS(DisplayController);

  // Registers on `in` and the interrupt on `irq` (Peripheral); the display
  // port window on `port_in`, whose forward interface is a Port (below).
  tlm::tlm_target_socket<32> port_in;

  // The registers, one member each (display_regs.def).
#define TESSERA_REGISTER_TABLE "display/display_regs.def"
#include "common/register_members.inc"

  DisplayController(sc_core::sc_module_name name, const DisplayParams& params);

  // Adds a receiver of the output port: every receiver gets every frame
  // shown, in the order they were added.
  void on_frame(std::function<void(const Frame&)> receiver) {
    m_receivers.push_back(std::move(receiver));
  }
  // Whether the frames handed to the receivers carry their pixels (Frame::rgba;
  // on by default). soc_sim turns it off when it writes no images: the
  // conversion to RGBA is about 5% of an `arm` teapot frame (perf).
  void keep_pixels(bool keep) {
    m_keep_pixels = keep;
  }
  // Adds a receiver of requests: called, from within the write, whenever
  // software hands the display a frame (SWAP in DMA mode, PRESENT in port
  // mode), with the write's annotated time, the Frame's requested time.
  void on_request(std::function<void(const sc_core::sc_time&)> receiver) {
    m_request_receivers.push_back(std::move(receiver));
  }
  // The scan-out engine of DMA mode; its geometry must be this display's.
  void connect_dma(DisplayDma& dma);

  unsigned bytes_per_pixel() const {
    return tessera::bytes_per_pixel(m_params.format);
  }
  uint64_t frame_bytes() const {
    return uint64_t{m_params.width} * m_params.height * bytes_per_pixel();
  }
  uint64_t frames_shown() const {
    return m_frames.value;
  }
  uint64_t underruns() const {
    return m_dma ? m_dma->underrun_lines() : 0;
  }
  // True while a frame has been handed to the display but not yet shown.
  bool frame_pending() const;
  const sc_core::sc_event& frame_shown_event() const {
    return m_frame_shown;
  }

  void trace_signals(sc_core::sc_trace_file* file) override;
  // Track "frames": each frame shown, from the frame before it (the start
  // for the first); track "vblank" (DMA mode): the vertical blanks.
  void timeline_to(TimelineSink& sink) override;
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  // The port's forward interface: its socket's one virtual call, and a
  // DirectTransport, which the bus calls without the socket's hops. A
  // port write moves bytes and counts them, scheduling nothing in the
  // kernel: it says so (ScheduleUntouched), so that the host keeps its
  // answer on what is scheduled (common/schedule_untouched.h).
  class Port : public tlm::tlm_fw_transport_if<>, public DirectTransport {
   public:
    explicit Port(DisplayController& display) : m_display(display) {}
    void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) final {
      if (m_display.port_b_transport(gp, delay)) mark_schedule_untouched(gp);
    }
    void direct_b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay, DirectExtras& extras) override {
      if (m_display.port_b_transport(gp, delay)) extras.untouched = true;
    }
    bool quote_accesses(tlm::tlm_command command, uint64_t address, unsigned bytes, size_t count, unsigned transfers,
                        uint64_t& latency_ticks, bool& untouched) override {
      return transfers == 1 && m_display.port_quote(command, address, bytes, count, latency_ticks, untouched);
    }
    void direct_accesses(tlm::tlm_command /*command*/, uint64_t address, uint8_t* data, unsigned bytes,
                         size_t count) override {
      m_display.port_write_accesses(address, data, bytes, count);
    }
    unsigned transport_dbg(tlm::tlm_generic_payload& gp) override { return m_display.port_transport_dbg(gp); }
    bool get_direct_mem_ptr(tlm::tlm_generic_payload& /*gp*/, tlm::tlm_dmi& dmi) override {
      dmi.allow_none();
      return false;
    }
    tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase,
                                       sc_core::sc_time& delay) override;

   private:
    DisplayController& m_display;
  };
  // Both doors' access: true when it succeeded (and so scheduled nothing).
  bool port_b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  // Writes as a unit (DirectTransport::quote_accesses, direct_accesses).
  bool port_quote(tlm::tlm_command command, uint64_t address, unsigned bytes, size_t count, uint64_t& latency_ticks,
                  bool& untouched) const;
  void port_write_accesses(uint64_t address, const uint8_t* data, unsigned bytes, size_t count);
  // The data phase of an access of `length` bytes, in integer ticks (the
  // port's cycles per word).
  uint64_t port_ticks(uint64_t length) const {
    return m_params.clock_period.value() * m_params.port_cycles * ((length + 3) / 4);
  }
  unsigned port_transport_dbg(tlm::tlm_generic_payload& gp);

  uint32_t read_STATUS() const;
  void write_SWAP(uint32_t value);
  void write_PRESENT(uint32_t value);
  uint32_t read_FRAMES() const;
  uint32_t read_REFRESHES() const;
  uint32_t read_UNDERRUNS() const;

  void end_of_elaboration() override;
  void requested(const sc_core::sc_time& when);
  void refresh();  // SC_THREAD, DMA mode: one refresh period after another
  // Shows a frame `delay` after the kernel's time (a register write's
  // annotated time), requested at `requested`.
  void show(const std::vector<uint8_t>& pixels, const sc_core::sc_time& requested,
            const sc_core::sc_time& delay = sc_core::SC_ZERO_TIME);
  bool in_vblank() const;

  DisplayParams m_params;
  DisplayDma* m_dma = nullptr;
  std::vector<std::function<void(const Frame&)>> m_receivers;
  bool m_keep_pixels = true;
  std::vector<std::function<void(const sc_core::sc_time&)>> m_request_receivers;
  Port m_port{*this};
  std::vector<uint8_t> m_port_frame;
  sc_core::sc_event m_frame_shown;

  bool m_swap_pending = false;
  sc_core::sc_time m_swap_requested;  // annotated time of the pending SWAP
  sc_core::sc_time m_scan_requested;  // ... of the SWAP whose frame is being scanned out
  bool m_front_valid = false;
  bool m_frame_in_scan = false;  // a new frame is being scanned out, not yet shown
  ActivityCounter& m_frames;
  ActivityCounter& m_refreshes;
  ActivityCounter& m_port_bytes;
  TimedTrace m_vblank;                 // for the VCD; in_vblank() answers from the times below
  TimelineSink* m_timeline = nullptr;  // timeline_to: null without a timeline
  unsigned m_frame_track = 0, m_vblank_track = 0;
  sc_core::sc_time m_frame_start;
  sc_core::sc_time m_active_start;
  sc_core::sc_time m_first_frame_time;
  sc_core::sc_time m_last_frame_time;
};

}  // namespace tessera
