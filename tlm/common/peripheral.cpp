#include "common/peripheral.h"

#include "common/log.h"

namespace tessera {

Peripheral::Peripheral(sc_core::sc_module_name name, sc_core::sc_time clock_period)
    : Block(name),
      in("in"),
      irq("irq"),
      m_regs(this->name()),
      m_clock_period(clock_period),
      m_refused_writes(counter("refused_register_writes", "register writes refused by the block's rules")) {
  in.register_b_transport(this, &Peripheral::b_transport);
  in.register_transport_dbg(this, &Peripheral::transport_dbg);
  SC_METHOD(update_irq);
  sensitive << m_irq_update;
  dont_initialize();
}

void Peripheral::add_irq_registers(const RegisterInfo& status, const RegisterInfo& enable) {
  m_irq_status_offset = status.offset;
  m_irq_enable_offset = enable.offset;
  m_regs.add(status, {}, [this](uint32_t value) {
    m_regs.set(m_irq_status_offset, m_regs.get(m_irq_status_offset) & ~value);
    schedule_irq_update(sc_core::SC_ZERO_TIME);
  });
  m_regs.add(enable, {}, [this](uint32_t value) {
    m_regs.set(m_irq_enable_offset, value);
    schedule_irq_update(sc_core::SC_ZERO_TIME);
  });
}

void Peripheral::raise_irq(uint32_t bits, const sc_core::sc_time& delay) {
  m_regs.set(m_irq_status_offset, m_regs.get(m_irq_status_offset) | bits);
  schedule_irq_update(delay);
}

void Peripheral::schedule_irq_update(const sc_core::sc_time& delay) {
  m_irq_updates.insert(sc_core::sc_time_stamp() + delay);
  m_irq_update.notify(delay);
}

void Peripheral::update_irq() {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  while (!m_irq_updates.empty() && *m_irq_updates.begin() <= now) m_irq_updates.erase(m_irq_updates.begin());
  irq.write((m_regs.get(m_irq_status_offset) & m_regs.get(m_irq_enable_offset)) != 0);
  if (!m_irq_updates.empty()) m_irq_update.notify(*m_irq_updates.begin() - now);
}

const char* Peripheral::write_refusal(const tlm::tlm_generic_payload& gp) const {
  (void)gp;
  return nullptr;
}

void Peripheral::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  if (const char* refusal = write_refusal(gp)) {
    ++m_refused_writes;
    gp.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    log::warning(name(), "register write at offset " + log::hex(gp.get_address()) + " refused: " + refusal);
  } else {
    m_regs.transport(gp, delay);
  }
  delay += m_clock_period;
}

unsigned Peripheral::transport_dbg(tlm::tlm_generic_payload& gp) {
  return m_regs.transport_dbg(gp);
}

}  // namespace tessera
