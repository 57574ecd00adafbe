// Memory-mapped registers of a peripheral. A peripheral lists each register
// once (name, offset, reset value, access) -- in a .def file shared with the
// driver -- and gives handlers where a register does more than store a value.
// Bad accesses get a TLM error response, never an assert.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <tlm>

namespace tessera {

enum class RegAccess {
  rw,   // read and write
  ro,   // read only: a write is a command error
  wo,   // write only: a read is a command error
  w1c,  // read; writing 1 to a bit clears it
};

struct RegisterInfo {
  const char* name;
  uint32_t offset;
  uint32_t reset;
  RegAccess access;
};

class RegisterBank {
 public:
  using ReadHandler = std::function<uint32_t()>;
  using WriteHandler = std::function<void(uint32_t)>;

  explicit RegisterBank(std::string owner) : m_owner(std::move(owner)) {}

  // Declares a register. Without handlers it stores what is written
  // (according to its access) and reads back its value. A read handler
  // computes the value without side effects: debug reads call it too.
  void add(const RegisterInfo& info, ReadHandler on_read = {}, WriteHandler on_write = {});

  // Hardware-side access to the stored value.
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
  struct Entry {
    RegisterInfo info;
    uint32_t value;
    ReadHandler on_read;
    WriteHandler on_write;
  };
  Entry* find(uint64_t offset);
  const Entry* find(uint64_t offset) const;
  tlm::tlm_response_status check(const tlm::tlm_generic_payload& gp, Entry*& entry);

  std::string m_owner;
  std::vector<Entry> m_entries;
  sc_core::sc_time m_access_delay;
};

}  // namespace tessera
