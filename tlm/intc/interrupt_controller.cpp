#include "intc/interrupt_controller.h"

#include "intc/intc_regs.h"

namespace tessera {

namespace {

constexpr RegisterInfo REGISTERS[] = {
#define TESSERA_INTC_REG(name, offset, reset, access) {#name, offset, reset, RegAccess::access},
#include "intc/intc_regs.def"
#undef TESSERA_INTC_REG
};

const RegisterInfo& info(uint32_t offset) {
  for (const RegisterInfo& r : REGISTERS)
    if (r.offset == offset) return r;
  throw std::logic_error("intc_regs.def has no register at this offset");
}

}  // namespace

InterruptController::InterruptController(sc_core::sc_module_name name, const sc_core::sc_time& clock_period,
                                         unsigned line_count)
    : Peripheral(name, clock_period),
      lines("lines", line_count),
      fiq("fiq"),
      m_irq_assertions(counter("irq_assertions", "times the core's IRQ input was asserted")),
      m_fiq_assertions(counter("fiq_assertions", "times the core's FIQ input was asserted")) {
  if (line_count > 32)
    throw std::invalid_argument("intc: at most 32 interrupt lines, got " + std::to_string(line_count));
  using namespace intc_regs;
  m_regs.add(info(RAW), [this] { return raw(); });
  m_regs.add(info(IRQ_STATUS), [this] { return raw() & m_regs.get(IRQ_ENABLE); });
  m_regs.add(info(FIQ_STATUS), [this] { return raw() & m_regs.get(FIQ_ENABLE); });
  // An enable written ahead of the kernel (the host runs ahead in its
  // quantum) moves the outputs at the access's time.
  const auto enable_written = [this](uint32_t offset) {
    return [this, offset](uint32_t value) {
      m_regs.set(offset, value);
      m_enable_written.notify(m_regs.access_delay());
    };
  };
  m_regs.add(info(IRQ_ENABLE), {}, enable_written(IRQ_ENABLE));
  m_regs.add(info(FIQ_ENABLE), {}, enable_written(FIQ_ENABLE));
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

void InterruptController::update_outputs() {
  const uint32_t pending = raw();
  const bool irq_level = (pending & m_regs.get(intc_regs::IRQ_ENABLE)) != 0;
  const bool fiq_level = (pending & m_regs.get(intc_regs::FIQ_ENABLE)) != 0;
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
