// The z-buffer unit beside the array (README.md), as a bus peripheral: the
// registers on `in` (zbuf_regs.def), the colour plane's window on
// `colour_in` (memory_map.def: zbuf_colour), and the port the array's zsend
// sends to (ap::PixelPort, which the SoC hands to the array's controller).
//
// The functional core (core/zbuf_core.h) tests and writes the pixels when
// the array's program runs, which is at its START (the array runs a program
// as a whole); so that nobody sees the planes before the array would have
// produced them, an access to the colour window waits, as the CIU's do, until
// the array's program and any clear have finished, and register writes that
// change the planes or the window (FRAME_ORIGIN, FRAME_SIZE, CONTROL) are
// refused meanwhile (a command error, STATUS.REFUSED, a warning). The unit
// runs on the array's clock (array.clock_mhz): its ports take pixels per
// array cycle.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tlm_utils/simple_target_socket.h>
#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "array/array_processor.h"
#include "array/core/pixel_port.h"
#include "common/peripheral.h"
#include "config/config.h"
#include "zbuf/core/zbuf_core.h"

namespace tessera {

struct ZbufParams {
  bool enabled = false;
  zbuf::ZbufCoreParams core;
  sc_core::sc_time clock_period;  // the array's clock (array.clock_mhz)

  // The parameters this block owns, the one place their defaults live.
  static ParamGroup parameters();
  // Reads zbuf.* and array.clock_mhz.
  static ZbufParams from_config(const Config& config);
  static ZbufParams defaults();
};

class ZbufUnit : public Peripheral, public ap::PixelPort {
 public:
  SC_HAS_PROCESS(ZbufUnit);

  tlm_utils::simple_target_socket<ZbufUnit, 32> colour_in;

#define TESSERA_REGISTER_TABLE "zbuf/zbuf_regs.def"
#include "common/register_members.inc"

  // `array` is the array whose programs send: the unit waits for them.
  ZbufUnit(sc_core::sc_module_name name, const ZbufParams& params, const ArrayProcessor& array);

  const ZbufParams& params() const {
    return m_params;
  }
  zbuf::ZbufCore& core() {
    return m_core;
  }
  const zbuf::ZbufCore& core() const {
    return m_core;
  }

  // ap::PixelPort: the array's zsend, during its controller's run.
  ap::SendTimes send(const std::vector<ap::SentPixel>& pixels, const ap::SendArrival& arrival) override;

  // When the planes are final: the array's program and any clear done.
  sc_core::sc_time free_from(const sc_core::sc_time& when) const;

  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  uint32_t read_STATUS() const;
  void write_FRAME(uint32_t unused);
  void write_CONTROL(uint32_t value);
  const char* write_refusal(const tlm::tlm_generic_payload& gp) const override;
  void colour_b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  unsigned colour_transport_dbg(tlm::tlm_generic_payload& gp);
  // Copies `length` bytes of the colour plane at byte `offset` to or from `data`.
  void copy_colour(uint64_t offset, uint8_t* data, uint64_t length, bool write);

  ZbufParams m_params;
  const ArrayProcessor& m_array;
  zbuf::ZbufCore m_core;
  sc_core::sc_time m_clear_until;
  mutable bool m_refused = false;
  mutable std::string m_refusal;
  sc_core::sc_signal<bool> m_no_irq{"no_irq", false};  // the unit raises no interrupt

  ActivityCounter& m_sends;
  ActivityCounter& m_pixels;
  ActivityCounter& m_written;
  ActivityCounter& m_failed;
  ActivityCounter& m_clipped;
  ActivityCounter& m_conflicts;
  ActivityCounter& m_port_cycles;
  ActivityCounter& m_clears;
  ActivityCounter& m_cleared_entries;
  ActivityCounter& m_window_words;
  ActivityCounter& m_window_waits;
};

}  // namespace tessera
