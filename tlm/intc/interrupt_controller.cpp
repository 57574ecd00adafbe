#include "intc/interrupt_controller.h"

namespace tessera {

InterruptController::InterruptController(sc_core::sc_module_name name, const sc_core::sc_time& clock_period,
                                         unsigned line_count)
    : Peripheral(name, clock_period),
      lines("lines", line_count),
      fiq("fiq"),
      m_irq_assertions(counter("irq_assertions", "times the core's IRQ input was asserted")),
      m_fiq_assertions(counter("fiq_assertions", "times the core's FIQ input was asserted")) {
  if (line_count > 32)
    throw std::invalid_argument("intc: at most 32 interrupt lines, got " + std::to_string(line_count));
  RAW.on_read(this, &InterruptController::raw);
  IRQ_STATUS.on_read(this, &InterruptController::read_IRQ_STATUS);
  FIQ_STATUS.on_read(this, &InterruptController::read_FIQ_STATUS);
  IRQ_ENABLE.on_write(this, &InterruptController::write_IRQ_ENABLE);
  FIQ_ENABLE.on_write(this, &InterruptController::write_FIQ_ENABLE);
  SC_METHOD(update_outputs);
  for (auto& line : lines) sensitive << line.value_changed();
  sensitive << m_enable_written;
}

uint32_t InterruptController::raw() const {
  uint32_t bits = 0;
  for (unsigned i = 0; i < lines.size(); ++i)
    if (lines[i].read()) bits |= 1u << i;
  return bits;
}

uint32_t InterruptController::read_IRQ_STATUS() const {
  return raw() & IRQ_ENABLE.get();
}

uint32_t InterruptController::read_FIQ_STATUS() const {
  return raw() & FIQ_ENABLE.get();
}

// An enable written ahead of the kernel (the host runs ahead in its quantum)
// moves the outputs at the access's time.
void InterruptController::write_IRQ_ENABLE(uint32_t value) {
  IRQ_ENABLE.set(value);
  m_enable_written.notify(m_regs.access_delay());
}

void InterruptController::write_FIQ_ENABLE(uint32_t value) {
  FIQ_ENABLE.set(value);
  m_enable_written.notify(m_regs.access_delay());
}

void InterruptController::update_outputs() {
  const uint32_t pending = raw();
  const bool irq_level = (pending & IRQ_ENABLE.get()) != 0;
  const bool fiq_level = (pending & FIQ_ENABLE.get()) != 0;
  if (irq_level && !irq.read()) ++m_irq_assertions;
  if (fiq_level && !fiq.read()) ++m_fiq_assertions;
  irq.write(irq_level);
  fiq.write(fiq_level);
}

SummaryRow InterruptController::summary_row(const sc_core::sc_time& /*elapsed*/) const {
  return {std::nullopt, std::nullopt,
          std::to_string(m_irq_assertions.value) + " IRQ, " + std::to_string(m_fiq_assertions.value) + " FIQ"};
}

void InterruptController::trace_signals(sc_core::sc_trace_file* file) {
  sc_core::sc_trace(file, irq, std::string(name()) + ".irq");
  sc_core::sc_trace(file, fiq, std::string(name()) + ".fiq");
}

}  // namespace tessera
