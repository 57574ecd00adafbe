// Cp15: the ARM922T's system control coprocessor as far as a flat-mapped
// (MMU-less) model needs it: the ID and cache type registers, the control
// register (cache enables, high vectors), the cache and write-buffer
// operations of c7, and the registers software writes on start-up kept so
// that they read back (tlm/host/iss/README.md, "CP15").
#pragma once

#include <cstdint>

#include "host/iss/arm_core.h"

namespace tessera::iss {

// What the cache and write-buffer operations of c7 act on: the timing
// layer's caches. Every function has a do-nothing default, so that the
// core alone (no caches) accepts the operations.
class CacheMaintenance {
 public:
  virtual ~CacheMaintenance() = default;
  virtual void invalidate_instruction_cache() {}
  virtual void invalidate_instruction_line(uint32_t /*address*/) {}
  virtual void invalidate_data_cache() {}
  virtual void invalidate_data_line(uint32_t /*address*/) {}
  // clean: write a dirty line back; by address, or by set/way index
  virtual void clean_data_line(uint32_t /*address*/, bool /*invalidate*/) {}
  virtual void clean_data_index(uint32_t /*set_way*/, bool /*invalidate*/) {}
  virtual void drain_write_buffer() {}
  virtual void wait_for_interrupt() {}
  // The control register (c1) was written: the caches' enables (C, I) and
  // replacement (RR) as they now are.
  virtual void control_written(uint32_t /*control*/) {}
};

class Cp15 : public Coprocessors {
 public:
  // Implementer 0x41 (ARM), variant 1, architecture 2 (ARMv4T), part 0x922, revision 0.
  static constexpr uint32_t ID = 0x41129220u;
  // Harvard (S), write-back with clean by register 7 and format-A lockdown
  // (ctype 6); each side 8 KB, 64-way, 8-word lines.
  static constexpr uint32_t CACHE_TYPE = 0x0d132132u;
  // Control register bits.
  static constexpr uint32_t CONTROL_M = 1u << 0, CONTROL_A = 1u << 1, CONTROL_C = 1u << 2;
  static constexpr uint32_t CONTROL_I = 1u << 12, CONTROL_V = 1u << 13, CONTROL_RR = 1u << 14;
  // Bits 6..3 read as one; the writable ones: M, A, C, S, R, I, V, RR, nF, iA
  // (not B: the model is little-endian only).
  static constexpr uint32_t CONTROL_RESET = 0x00000078u;
  static constexpr uint32_t CONTROL_WRITABLE = 0xc0007307u;

  // The core's high-vector setting follows the V bit.
  Cp15(ArmCore& core, CacheMaintenance* caches = nullptr);

  bool mrc(unsigned cp, unsigned op1, unsigned crn, unsigned crm, unsigned op2, bool privileged,
           uint32_t& value) override;
  bool mcr(unsigned cp, unsigned op1, unsigned crn, unsigned crm, unsigned op2, bool privileged,
           uint32_t value) override;

  uint32_t control() const { return m_control; }
  bool instruction_cache_enabled() const { return (m_control & CONTROL_I) != 0; }
  bool data_cache_enabled() const { return (m_control & CONTROL_C) != 0; }

 private:
  bool cache_operation(unsigned crm, unsigned op2, uint32_t value);

  ArmCore& m_core;
  CacheMaintenance m_no_caches;
  CacheMaintenance& m_caches;
  uint32_t m_control = CONTROL_RESET;
  // Kept so that they read back; a flat map applies none of them.
  uint32_t m_translation_base = 0, m_domains = 0, m_data_lockdown = 0, m_instruction_lockdown = 0;
  uint32_t m_process_id = 0;
};

}  // namespace tessera::iss
