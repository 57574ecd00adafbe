// The region of interest's register (contract/soc/sim_control_regs.def): the
// model's own marker, not the chip's. Software writes ROI = 1 where its
// region of interest begins and 0 where it ends (the SDK's
// tessera_roi_begin/end); each change is handed, with the access's time, to
// the SoC's recorder, which reports the region's statistics apart
// (soc_recorder.h). A write that changes nothing (a begin inside the region)
// is counted and ignored; a value other than 0 or 1 is refused as a command
// error. Not one of the SoC's blocks: it has no statistics of its own, so a
// run that never writes it is the run it was without it.
#pragma once

#include <functional>

#include <systemc>

#include "common/peripheral.h"
#include "soc/sim_control_regs.h"

namespace tessera {

class RoiRegister : public Peripheral {
 public:
  // Called at every change: true where a region begins, with the access's time.
  using Edge = std::function<void(bool begins, const sc_core::sc_time& when)>;

#define TESSERA_REGISTER_TABLE "soc/sim_control_regs.def"
#include "common/register_members.inc"

  RoiRegister(sc_core::sc_module_name name, const sc_core::sc_time& clock_period, Edge on_edge);

  // Not in the SoC's summary (it is not one of its blocks); for completeness.
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;

 private:
  const char* write_refusal(const tlm::tlm_generic_payload& gp) const override;
  void write_ROI(uint32_t value);

  Edge m_on_edge;
  sc_core::sc_signal<bool> m_no_interrupt{"no_interrupt", false};  // Peripheral::irq, never raised
};

}  // namespace tessera
