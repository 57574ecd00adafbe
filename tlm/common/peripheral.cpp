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

void Peripheral::bind_irq_registers(Register& status, Register& enable) {
  m_irq_status = &status;
  m_irq_enable = &enable;
  // The line follows a write at the access's time. At the kernel's time it
  // would fall in the very time step in which it rose whenever the host
  // (ahead of the kernel in its quantum) answers at once, and a trace,
  // which records one value per time step, would never show the pulse.
  m_line_status = status.get();
  m_line_enable = enable.get();
  status.on_write([this](uint32_t value) {
    m_irq_status->set(m_irq_status->get() & ~value);
    schedule_irq_change({IrqChange::Kind::clear_status, value}, m_regs.access_delay());
  });
  enable.on_write([this](uint32_t value) {
    m_irq_enable->set(value);
    schedule_irq_change({IrqChange::Kind::write_enable, value}, m_regs.access_delay());
  });
}

void Peripheral::add_irq_registers(const RegisterInfo& status, const RegisterInfo& enable) {
  Register& status_register = m_regs.add(status);
  Register& enable_register = m_regs.add(enable);
  bind_irq_registers(status_register, enable_register);
}

void Peripheral::raise_irq(uint32_t bits, const sc_core::sc_time& delay) {
  m_irq_status->set(m_irq_status->get() | bits);
  schedule_irq_change({IrqChange::Kind::set_status, bits}, delay);
}

void Peripheral::schedule_irq_change(IrqChange change, const sc_core::sc_time& delay) {
  m_irq_changes.emplace(sc_core::sc_time_stamp() + delay, change);
  m_irq_update.notify(delay);
}

void Peripheral::update_irq() {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  // Changes due by now, in time order (equal times in the order made).
  auto it = m_irq_changes.begin();
  for (; it != m_irq_changes.end() && it->first <= now; ++it) {
    const IrqChange& change = it->second;
    switch (change.kind) {
      case IrqChange::Kind::set_status: m_line_status |= change.bits; break;
      case IrqChange::Kind::clear_status: m_line_status &= ~change.bits; break;
      case IrqChange::Kind::write_enable: m_line_enable = change.bits; break;
    }
  }
  m_irq_changes.erase(m_irq_changes.begin(), it);
  if (m_irq_changes.empty()) {
    // Nothing is pending: the line's view is the registers as software
    // reads them. They differ only where two changes were made out of time
    // order (a clear ahead of the kernel, then a raise at the kernel's
    // time), and then what software reads wins.
    m_line_status = m_irq_status->get();
    m_line_enable = m_irq_enable->get();
  }
  irq.write((m_line_status & m_line_enable) != 0);
  if (!m_irq_changes.empty()) m_irq_update.notify(m_irq_changes.begin()->first - now);
}

const char* Peripheral::write_refusal(const tlm::tlm_generic_payload& gp) const {
  (void)gp;
  return nullptr;
}

void Peripheral::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  mark_used(delay);
  m_access_delay = delay;
  if (const char* refusal = write_refusal(gp)) {
    ++m_refused_writes;
    gp.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    log::warning(name(), "register write at offset " + log::hex(gp.get_address()) + " refused: " + refusal);
  } else {
    m_regs.transport(gp, delay);
  }
  m_access_delay = sc_core::SC_ZERO_TIME;
  delay += m_clock_period;
}

unsigned Peripheral::transport_dbg(tlm::tlm_generic_payload& gp) {
  return m_regs.transport_dbg(gp);
}

}  // namespace tessera
