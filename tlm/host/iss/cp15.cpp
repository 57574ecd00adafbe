#include "host/iss/cp15.h"

namespace tessera::iss {

Cp15::Cp15(ArmCore& core, CacheMaintenance* caches) : m_core(core), m_caches(caches ? *caches : m_no_caches) {
  m_core.set_high_vectors(false);
}

bool Cp15::mrc(unsigned cp, unsigned op1, unsigned crn, unsigned crm, unsigned op2, bool privileged, uint32_t& value) {
  if (cp != 15 || op1 != 0 || !privileged) return false;
  switch (crn) {
    case 0:
      if (crm != 0 || op2 > 1) return false;
      value = op2 == 0 ? ID : CACHE_TYPE;
      return true;
    case 1: value = m_control; return crm == 0 && op2 == 0;
    case 2: value = m_translation_base; return crm == 0 && op2 == 0;
    case 3: value = m_domains; return crm == 0 && op2 == 0;
    case 5:  // fault status, data and prefetch: no MMU faults on a flat map
    case 6:  // fault address
      value = 0;
      return crm == 0 && op2 <= 1;
    case 9: value = op2 == 0 ? m_data_lockdown : m_instruction_lockdown; return crm == 0 && op2 <= 1;
    case 13: value = m_process_id; return crm == 0 && op2 == 0;
    default: return false;
  }
}

bool Cp15::mcr(unsigned cp, unsigned op1, unsigned crn, unsigned crm, unsigned op2, bool privileged, uint32_t value) {
  if (cp != 15 || op1 != 0 || !privileged) return false;
  switch (crn) {
    case 1:
      if (crm != 0 || op2 != 0) return false;
      m_control = CONTROL_RESET | (value & CONTROL_WRITABLE);
      m_core.set_high_vectors((m_control & CONTROL_V) != 0);
      m_caches.control_written(m_control);
      return true;
    case 2: m_translation_base = value & ~0x3fffu; return crm == 0 && op2 == 0;
    case 3: m_domains = value; return crm == 0 && op2 == 0;
    case 5:
    case 6: return crm == 0 && op2 <= 1;
    case 7: return cache_operation(crm, op2, value);
    case 8:  // TLB operations: no TLB on a flat map
      return crm == 5 || crm == 6 || crm == 7;
    case 9: (op2 == 0 ? m_data_lockdown : m_instruction_lockdown) = value; return crm == 0 && op2 <= 1;
    case 13: m_process_id = value & 0xfe000000u; return crm == 0 && op2 == 0;
    default: return false;
  }
}

// The ARM922T's register 7 operations (ARM922T TRM, "Register 7, cache
// operations"): CRm selects the cache and the kind, Opcode_2 whole cache
// (0), by address (1) or by set/way index (2).
bool Cp15::cache_operation(unsigned crm, unsigned op2, uint32_t value) {
  switch ((crm << 3) | op2) {
    case (0 << 3) | 4: m_caches.wait_for_interrupt(); return true;
    case (5 << 3) | 0: m_caches.invalidate_instruction_cache(); return true;
    case (5 << 3) | 1: m_caches.invalidate_instruction_line(value); return true;
    case (6 << 3) | 0: m_caches.invalidate_data_cache(); return true;
    case (6 << 3) | 1: m_caches.invalidate_data_line(value); return true;
    case (7 << 3) | 0:
      m_caches.invalidate_instruction_cache();
      m_caches.invalidate_data_cache();
      return true;
    case (10 << 3) | 1: m_caches.clean_data_line(value, false); return true;
    case (10 << 3) | 2: m_caches.clean_data_index(value, false); return true;
    case (10 << 3) | 4: m_caches.drain_write_buffer(); return true;
    case (13 << 3) | 1:  // prefetch an instruction line: a hint
      return true;
    case (14 << 3) | 1: m_caches.clean_data_line(value, true); return true;
    case (14 << 3) | 2: m_caches.clean_data_index(value, true); return true;
    default: return false;
  }
}

}  // namespace tessera::iss
