#include "soc/roi_register.h"

#include <cstring>

namespace tessera {

RoiRegister::RoiRegister(sc_core::sc_module_name name, const sc_core::sc_time& clock_period, Edge on_edge)
    : Peripheral(name, clock_period), m_on_edge(std::move(on_edge)) {
  irq.bind(m_no_interrupt);
  ROI.on_write(this, &RoiRegister::write_ROI);
}

const char* RoiRegister::write_refusal(const tlm::tlm_generic_payload& gp) const {
  if (!gp.is_write() || gp.get_address() != sim_control_regs::ROI || gp.get_data_length() != 4 || !gp.get_data_ptr())
    return nullptr;
  uint32_t value = 0;
  std::memcpy(&value, gp.get_data_ptr(), sizeof value);
  return value > 1 ? "ROI takes 1 (the region of interest begins) or 0 (it ends)" : nullptr;
}

SummaryRow RoiRegister::summary_row(const sc_core::sc_time& /*elapsed*/) const {
  return {std::nullopt, std::nullopt, ROI.get() ? "in the region of interest" : "outside the region of interest"};
}

void RoiRegister::write_ROI(uint32_t value) {
  if (value == ROI.get()) return;
  ROI.set(value);
  m_on_edge(value == 1, access_time());
}

}  // namespace tessera
