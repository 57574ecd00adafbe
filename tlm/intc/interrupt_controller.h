// The host's interrupt controller: the SoC's interrupt lines (irq_map.def)
// in, the ARM922T's two interrupt inputs out. Software on the ISS
// (host.model=iss) reads which lines are high and chooses which of them
// assert the core's nIRQ or nFIQ; the host-compiled model waits on the lines
// directly and has no use for it, so the SoC builds it only with
// host.model=iss (tlm/intc/README.md).
#pragma once

#include <cstdint>

#include <systemc>

#include "common/peripheral.h"

namespace tessera {

class InterruptController : public Peripheral {
 public:
  SC_HAS_PROCESS(InterruptController);

  sc_core::sc_vector<sc_core::sc_in<bool>> lines;  // the host's interrupt lines
  // Peripheral::irq is the core's IRQ input (high: asserted); this its FIQ input.
  sc_core::sc_out<bool> fiq;

  // The registers, one member each (intc_regs.def).
#define TESSERA_REGISTER_TABLE "intc/intc_regs.def"
#include "common/register_members.inc"

  InterruptController(sc_core::sc_module_name name, const sc_core::sc_time& clock_period, unsigned line_count);

  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  void trace_signals(sc_core::sc_trace_file* file) override;

 private:
  uint32_t raw() const;
  uint32_t read_IRQ_STATUS() const;
  uint32_t read_FIQ_STATUS() const;
  void write_IRQ_ENABLE(uint32_t value);
  void write_FIQ_ENABLE(uint32_t value);
  void update_outputs();  // SC_METHOD: the lines, or an enable register written

  sc_core::sc_event m_enable_written;
  ActivityCounter& m_irq_assertions;
  ActivityCounter& m_fiq_assertions;
};

}  // namespace tessera
