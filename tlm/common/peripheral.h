// A block with memory-mapped registers and an interrupt line. Peripheral
// gives it the register target socket `in` (the register bank answers; an
// access costs one cycle of the block's clock as target latency), the
// interrupt registers every peripheral has (a status register whose bits
// the block raises and software clears by writing 1s, and an enable
// register) and the `irq` output, which follows status & enable != 0. What
// a peripheral adds is its own registers: members declared from its register
// table (register_members.inc), in m_regs, with their read_<reg> /
// write_<reg> handlers.
//
// Timing: a register write takes effect at the access's annotated time
// (RegisterBank::access_delay()), not at the kernel's time, which may be a
// quantum behind the initiator. Register values change when the access is
// made (a later access by the same initiator must see them); the interrupt
// line, which other processes see at the kernel's time, changes at the
// annotated time.
#pragma once

#include <cstdint>
#include <map>

#include <tlm_utils/simple_target_socket.h>
#include <systemc>
#include <tlm>

#include "common/block.h"
#include "common/register_bank.h"

namespace tessera {

class Peripheral : public Block {
 public:
  SC_HAS_PROCESS(Peripheral);

  tlm_utils::simple_target_socket<Peripheral, 32> in;  // registers
  sc_core::sc_out<bool> irq;                           // status & enable != 0

 protected:
  Peripheral(sc_core::sc_module_name name, sc_core::sc_time clock_period);

  // Makes `status` (w1c) and `enable` (rw), the block's interrupt registers,
  // drive `irq`: a write to either moves the line at the access's annotated
  // time.
  void bind_irq_registers(Register& status, Register& enable);
  // The same for registers the bank holds (a block without a register table).
  void add_irq_registers(const RegisterInfo& status, const RegisterInfo& enable);
  // Sets status bits; the line follows `delay` after the kernel's time.
  void raise_irq(uint32_t bits, const sc_core::sc_time& delay = sc_core::SC_ZERO_TIME);
  uint32_t irq_status() const { return m_irq_status ? m_irq_status->get() : 0; }

  // Why a register write must be refused with a command error (nullptr:
  // accept it). Each refusal is counted (refused_register_writes) and
  // reported as a warning naming the offset and the reason.
  virtual const char* write_refusal(const tlm::tlm_generic_payload& gp) const;

  const sc_core::sc_time& clock_period() const { return m_clock_period; }
  // The time of the register access being handled (the kernel's time plus
  // its annotated delay), for write_refusal() and the handlers.
  sc_core::sc_time access_time() const { return sc_core::sc_time_stamp() + m_access_delay; }

  RegisterBank m_regs;

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  unsigned transport_dbg(tlm::tlm_generic_payload& gp);
  // A change of the interrupt registers as the line sees it, at its time.
  struct IrqChange {
    enum class Kind { set_status, clear_status, write_enable } kind;
    uint32_t bits;
  };
  void schedule_irq_change(IrqChange change, const sc_core::sc_time& delay);
  void update_irq();  // SC_METHOD: applies the changes that are due

  sc_core::sc_time m_clock_period;
  sc_core::sc_time m_access_delay;
  ActivityCounter& m_refused_writes;
  Register* m_irq_status = nullptr;
  Register* m_irq_enable = nullptr;
  // The registers change when they are accessed; the line follows each
  // change at its own time, in time order, through its own copy of the two
  // registers. (An event keeps only its earliest notification, so the later
  // changes wait here.)
  std::multimap<sc_core::sc_time, IrqChange> m_irq_changes;
  uint32_t m_line_status = 0;
  uint32_t m_line_enable = 0;
  sc_core::sc_event m_irq_update;
};

}  // namespace tessera
