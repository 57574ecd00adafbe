// Memory-mapped registers of a peripheral. A peripheral lists each register
// once (name, offset, reset value, access) in a register table shared with
// the driver (contract/<block>/<block>_regs.def), declares them from it as
// members (register_members.inc), and gives read_<reg> / write_<reg>
// handlers where a register does more than store a value. Bad accesses get
// a TLM error response, never an assert.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <tlm>

#include "common/register_table.h"

namespace tessera {

class RegisterBank;

// One register: its row of the table, its value and its handlers. Without
// handlers it stores what is written (according to its access) and reads
// back its value. A read handler computes the value without side effects:
// debug reads call it too.
class Register {
 public:
  using ReadHandler = std::function<uint32_t()>;
  using WriteHandler = std::function<void(uint32_t)>;

  // Joins `bank` at the table's offset.
  Register(RegisterBank& bank, const RegisterInfo& info);
  Register(const Register&) = delete;
  Register& operator=(const Register&) = delete;

  const RegisterInfo& info() const { return m_info; }
  // Hardware-side access to the stored value.
  uint32_t get() const { return m_value; }
  void set(uint32_t value) { m_value = value; }
  // A reset value the block chooses at construction (from a parameter)
  // instead of the table's.
  void set_reset(uint32_t value) { m_info.reset = m_value = value; }
  void reset() { m_value = m_info.reset; }

  void on_read(ReadHandler handler) { m_on_read = std::move(handler); }
  void on_write(WriteHandler handler) { m_on_write = std::move(handler); }
  template <class Owner>
  void on_read(const Owner* owner, uint32_t (Owner::*handler)() const) {
    m_on_read = [owner, handler] { return (owner->*handler)(); };
  }
  template <class Owner>
  void on_write(Owner* owner, void (Owner::*handler)(uint32_t)) {
    m_on_write = [owner, handler](uint32_t value) { (owner->*handler)(value); };
  }

  // The bus's view: what a read returns, what a write does.
  uint32_t read() const { return m_on_read ? m_on_read() : m_value; }
  void write(uint32_t value);

 private:
  RegisterInfo m_info;
  uint32_t m_value;
  ReadHandler m_on_read;
  WriteHandler m_on_write;
};

class RegisterBank {
 public:
  using ReadHandler = Register::ReadHandler;
  using WriteHandler = Register::WriteHandler;

  explicit RegisterBank(std::string owner) : m_owner(std::move(owner)) {}

  // Called by Register's constructor; a bad or duplicate offset is a
  // programming error (std::logic_error).
  void attach(Register& reg);
  // Declares a register the bank itself holds, for a block (or a test)
  // without a register table.
  Register& add(const RegisterInfo& info, ReadHandler on_read = {}, WriteHandler on_write = {});

  // Hardware-side access to the stored value by offset.
  uint32_t get(uint32_t offset) const;
  void set(uint32_t offset, uint32_t value);
  void reset();

  // Handles one bus access: 32-bit, aligned, no byte enables. `delay` is the
  // access's annotated time (offset from the kernel's time); handlers read
  // it through access_delay() to make what they start happen then. Sets the
  // response status; returns the name of the register touched (nullptr on
  // error). Adds no latency: that is the owner's.
  const char* transport(tlm::tlm_generic_payload& gp, const sc_core::sc_time& delay);
  // Debug access: same checks, reads without side effects, writes store.
  unsigned transport_dbg(tlm::tlm_generic_payload& gp);

  const std::string& owner() const { return m_owner; }
  // The annotated time of the access being handled (zero outside transport).
  const sc_core::sc_time& access_delay() const { return m_access_delay; }

 private:
  Register* find(uint64_t offset) const;
  tlm::tlm_response_status check(const tlm::tlm_generic_payload& gp, Register*& reg) const;

  std::string m_owner;
  std::vector<Register*> m_registers;  // in the order declared
  std::vector<std::unique_ptr<Register>> m_owned;
  sc_core::sc_time m_access_delay;
};

}  // namespace tessera
