#include "host/iss/arm_core.h"

#include <cstdio>

namespace tessera::iss {

namespace {

constexpr uint32_t bit(uint32_t insn, unsigned n) {
  return (insn >> n) & 1u;
}
constexpr uint32_t bits(uint32_t insn, unsigned high, unsigned low) {
  return (insn >> low) & ((1u << (high - low + 1)) - 1u);
}
constexpr uint32_t ror(uint32_t value, unsigned amount) {
  amount &= 31;
  return amount == 0 ? value : (value >> amount) | (value << (32 - amount));
}

// Vector offsets, by Exception.
constexpr uint32_t VECTOR_OFFSET[] = {0x00, 0x10, 0x1c, 0x18, 0x0c, 0x04, 0x08};
constexpr Mode VECTOR_MODE[] = {Mode::svc, Mode::abt, Mode::fiq, Mode::irq, Mode::abt, Mode::und, Mode::svc};

uint32_t nz(uint32_t result) {
  return (result & psr::N) | (result == 0 ? psr::Z : 0);
}

}  // namespace

std::string address_text(uint64_t address) {
  char text[24];
  std::snprintf(text, sizeof text, "0x%08llx", static_cast<unsigned long long>(address));
  return text;
}

const char* fault_name(Exception exception) {
  switch (exception) {
    case Exception::undefined: return "undefined instruction";
    case Exception::prefetch_abort: return "prefetch abort (no memory at the PC)";
    case Exception::data_abort: return "data abort";
    default: return nullptr;
  }
}

ArmCore::ArmCore(IssMemory& memory, Coprocessors* coprocessors) : m_memory(memory), m_coprocessors(coprocessors) {
  m_cpsr = static_cast<uint32_t>(Mode::svc) | psr::I | psr::F;
}

unsigned ArmCore::bank_of(Mode mode) {
  switch (mode) {
    case Mode::fiq: return 1;
    case Mode::irq: return 2;
    case Mode::svc: return 3;
    case Mode::abt: return 4;
    case Mode::und: return 5;
    default: return 0;  // usr, sys and (unpredictable) reserved modes
  }
}

void ArmCore::switch_bank(unsigned from, unsigned to) {
  if (from == to) return;
  m_r13_14[from] = {m_r[13], m_r[14]};
  if (from == 1 || to == 1) {  // FIQ banks r8..r12 too
    auto& save = from == 1 ? m_fiq_r8_12 : m_user_r8_12;
    const auto& load = to == 1 ? m_fiq_r8_12 : m_user_r8_12;
    for (unsigned i = 0; i < 5; ++i) save[i] = m_r[8 + i];
    for (unsigned i = 0; i < 5; ++i) m_r[8 + i] = load[i];
  }
  m_r[13] = m_r13_14[to][0];
  m_r[14] = m_r13_14[to][1];
}

void ArmCore::set_cpsr(uint32_t value) {
  switch_bank(bank_of(mode()), bank_of(static_cast<Mode>(value & psr::MODE_MASK)));
  m_cpsr = value;
}

uint32_t ArmCore::spsr() const {
  const unsigned bank = bank_of(mode());
  return bank == 0 ? 0 : m_spsr[bank];
}

void ArmCore::set_spsr(uint32_t value) {
  const unsigned bank = bank_of(mode());
  if (bank != 0) m_spsr[bank] = value;
}

uint32_t ArmCore::banked(Mode m, unsigned n) const {
  const unsigned want = bank_of(m);
  const unsigned now = bank_of(mode());
  if (n == 15) return m_pc;
  if (n < 8 || (n < 13 && (want == 1) == (now == 1)) || (n >= 13 && want == now)) return m_r[n];
  if (n < 13) return want == 1 ? m_fiq_r8_12[n - 8] : m_user_r8_12[n - 8];
  return m_r13_14[want][n - 13];
}

void ArmCore::set_reg(unsigned n, uint32_t value) {
  if (n == 15)
    m_pc = value;
  else
    m_r[n] = value;
}

void ArmCore::reset() {
  set_cpsr(static_cast<uint32_t>(Mode::svc) | psr::I | psr::F);
  m_pc = m_high_vectors ? 0xffff0000u : 0;
}

void ArmCore::enter(Exception exception, uint32_t return_address) {
  if (exception == Exception::swi && m_swi_hook && m_swi_hook(m_current)) return;
  if (m_exception_hook) {
    const bool interrupt = exception == Exception::irq || exception == Exception::fiq;
    m_exception_hook(exception, interrupt || exception == Exception::reset ? m_pc : m_current);
  }
  const auto index = static_cast<unsigned>(exception);
  const uint32_t old = m_cpsr;
  uint32_t cpsr = (old & ~(psr::MODE_MASK | psr::T)) | static_cast<uint32_t>(VECTOR_MODE[index]) | psr::I;
  if (exception == Exception::reset || exception == Exception::fiq) cpsr |= psr::F;
  set_cpsr(cpsr);
  m_spsr[bank_of(VECTOR_MODE[index])] = old;
  m_r[14] = return_address;
  m_pc = (m_high_vectors ? 0xffff0000u : 0) + VECTOR_OFFSET[index];
  m_branched = true;
  m_info.exception = true;
}

bool ArmCore::condition(uint32_t cond) const {
  const bool n = m_cpsr & psr::N, z = m_cpsr & psr::Z, c = m_cpsr & psr::C, v = m_cpsr & psr::V;
  switch (cond) {
    case 0x0: return z;
    case 0x1: return !z;
    case 0x2: return c;
    case 0x3: return !c;
    case 0x4: return n;
    case 0x5: return !n;
    case 0x6: return v;
    case 0x7: return !v;
    case 0x8: return c && !z;
    case 0x9: return !c || z;
    case 0xa: return n == v;
    case 0xb: return n != v;
    case 0xc: return !z && n == v;
    case 0xd: return z || n != v;
    case 0xe: return true;
    default: return false;  // NV: never, on ARMv4
  }
}

void ArmCore::step() {
  // Interrupts are sampled between instructions; the handler returns with
  // SUBS pc, lr, #4 to the instruction that would have run.
  m_info = StepInfo{};
  if (m_fiq_line && !(m_cpsr & psr::F)) {
    enter(Exception::fiq, m_pc + 4);
    return;
  }
  if (m_irq_line && !(m_cpsr & psr::I)) {
    enter(Exception::irq, m_pc + 4);
    return;
  }
  m_current = m_pc;
  m_branched = false;
  if (thumb()) {
    uint32_t half = 0;
    if (!m_memory.fetch(m_current, 2, half)) {
      enter(Exception::prefetch_abort, m_current + 4);
      return;
    }
    ++m_instructions;
    m_r[15] = m_current + 4;
    m_info.executed = true;
    execute_thumb(half);
    if (!m_branched) m_pc = m_current + 2;
    m_info.pc_written = m_branched && !m_info.exception;
    return;
  }
  uint32_t insn = 0;
  if (!m_memory.fetch(m_current, 4, insn)) {
    enter(Exception::prefetch_abort, m_current + 4);
    return;
  }
  ++m_instructions;
  m_r[15] = m_current + 8;
  execute_arm(insn);
  if (!m_branched) m_pc = m_current + 4;
  m_info.pc_written = m_branched && !m_info.exception;
}

void ArmCore::execute_arm(uint32_t insn) {
  m_info.executed = condition(insn >> 28);
  if (m_info.executed) {
    switch (bits(insn, 27, 25)) {
      case 0:
        if ((insn & 0x0ffffff0u) == 0x012fff10u) {  // BX
          m_info.kind = InsnClass::branch;
          m_info.reads = static_cast<uint16_t>(1u << bits(insn, 3, 0));
          const uint32_t target = operand(bits(insn, 3, 0));
          m_cpsr = (m_cpsr & ~psr::T) | (target & 1u ? psr::T : 0);
          write_pc(target & (target & 1u ? ~1u : ~3u));
        } else if ((insn & 0x0fc000f0u) == 0x00000090u) {
          multiply(insn);
        } else if ((insn & 0x0f8000f0u) == 0x00800090u) {
          multiply_long(insn);
        } else if ((insn & 0x0fb00ff0u) == 0x01000090u) {
          swap(insn);
        } else if ((insn & 0x0e000090u) == 0x00000090u) {
          halfword_transfer(insn);
        } else if ((insn & 0x01900000u) == 0x01000000u) {  // TST..CMN without S: MRS/MSR
          status_transfer(insn);
        } else {
          data_processing(insn);
        }
        break;
      case 1:
        if ((insn & 0x01900000u) == 0x01000000u)
          status_transfer(insn);
        else
          data_processing(insn);
        break;
      case 2: single_transfer(insn); break;
      case 3:
        if (bit(insn, 4))
          undefined();
        else
          single_transfer(insn);
        break;
      case 4: block_transfer(insn); break;
      case 5: {  // B, BL
        m_info.kind = InsnClass::branch;
        const int32_t offset = static_cast<int32_t>(insn << 8) >> 6;
        if (bit(insn, 24)) m_r[14] = m_current + 4;
        write_pc(m_r[15] + static_cast<uint32_t>(offset));
        break;
      }
      case 6:  // LDC/STC: no coprocessor of the ARM922T has them
        undefined();
        break;
      default:
        if (bit(insn, 24)) {
          m_info.kind = InsnClass::exception;
          enter(Exception::swi, m_current + 4);
        } else if (bit(insn, 4))
          coprocessor_transfer(insn);
        else
          undefined();  // CDP
        break;
    }
  }
}

namespace {

// ARM encodings the Thumb instructions are executed as (condition AL).
constexpr uint32_t AL = 0xe0000000u;
constexpr uint32_t dp(uint32_t opcode, bool set_flags, uint32_t rn, uint32_t rd, uint32_t operand2) {
  return AL | (opcode << 21) | (set_flags ? 1u << 20 : 0) | (rn << 16) | (rd << 12) | operand2;
}
constexpr uint32_t IMMEDIATE = 1u << 25;
constexpr uint32_t shift_by_register(uint32_t rs, uint32_t type, uint32_t rm) {
  return (rs << 8) | (type << 5) | (1u << 4) | rm;
}
// Data-processing opcodes.
enum DpOpcode : uint32_t { and_ = 0, eor, sub, rsb, add, adc, sbc, rsc, tst, teq, cmp, cmn, orr, mov, bic, mvn };

}  // namespace

// Thumb (ARMv4T): each instruction is executed as the ARM instruction it
// stands for, r15 reading as the instruction's address + 4; the branches,
// the PC- and SP-relative additions and SWI are done here.
void ArmCore::execute_thumb(uint32_t insn) {
  const uint32_t rd = bits(insn, 2, 0), rs = bits(insn, 5, 3);
  switch (bits(insn, 15, 11)) {
    case 0x00:
    case 0x01:
    case 0x02:  // LSL, LSR, ASR Rd, Rs, #imm5
      data_processing(dp(mov, true, 0, rd, (bits(insn, 10, 6) << 7) | (bits(insn, 12, 11) << 5) | rs));
      return;
    case 0x03: {  // add, sub Rd, Rs, Rn / #imm3
      const uint32_t operand2 = bit(insn, 10) ? IMMEDIATE | bits(insn, 8, 6) : bits(insn, 8, 6);
      data_processing(dp(bit(insn, 9) ? sub : add, true, rs, rd, operand2));
      return;
    }
    case 0x04:
    case 0x05:
    case 0x06:
    case 0x07: {  // mov, cmp, add, sub Rd, #imm8
      static constexpr uint32_t IMMEDIATE_OPS[] = {mov, cmp, add, sub};
      const uint32_t r = bits(insn, 10, 8);
      data_processing(dp(IMMEDIATE_OPS[bits(insn, 12, 11)], true, r, bits(insn, 12, 11) == 1 ? 0 : r,
                         IMMEDIATE | bits(insn, 7, 0)));
      return;
    }
    case 0x08:
      if (!bit(insn, 10)) {  // ALU operations
        const uint32_t op = bits(insn, 9, 6);
        switch (op) {
          case 0x2:  // LSL, LSR, ASR, ROR by register
          case 0x3:
          case 0x4:
          case 0x7: {
            const uint32_t type = op == 0x7 ? 3 : op - 2;
            data_processing(dp(mov, true, 0, rd, shift_by_register(rs, type, rd)));
            return;
          }
          case 0x9:  // NEG
            data_processing(dp(rsb, true, rs, rd, IMMEDIATE));
            return;
          case 0xd:  // MUL Rd, Rs: Rd = Rs x Rd
            multiply(AL | (1u << 20) | (rd << 16) | (rd << 8) | 0x90u | rs);
            return;
          case 0xf:  // MVN
            data_processing(dp(mvn, true, 0, rd, rs));
            return;
          default: {
            static constexpr uint32_t ALU_OPS[] = {and_, eor, 0, 0, 0, adc, sbc, 0, tst, 0, cmp, cmn, orr, 0, bic, 0};
            const bool test_only = op == 0x8 || op == 0xa || op == 0xb;
            data_processing(dp(ALU_OPS[op], true, rd, test_only ? 0 : rd, rs));
            return;
          }
        }
      } else {  // high-register add, cmp, MOV; BX
        const uint32_t hd = rd | (bit(insn, 7) << 3), hs = bits(insn, 6, 3);
        switch (bits(insn, 9, 8)) {
          case 0: data_processing(dp(add, false, hd, hd, hs)); return;
          case 1: data_processing(dp(cmp, true, hd, 0, hs)); return;
          case 2: data_processing(dp(mov, false, 0, hd, hs)); return;
          default: {
            m_info.kind = InsnClass::branch;
            m_info.reads = static_cast<uint16_t>(1u << hs);
            const uint32_t target = operand(hs);
            m_cpsr = (m_cpsr & ~psr::T) | (target & 1u ? psr::T : 0);
            write_pc(target & (target & 1u ? ~1u : ~3u));
            return;
          }
        }
      }
    case 0x09:  // LDR Rd, [PC, #imm8 x 4]: the PC word-aligned
      m_r[15] = (m_current + 4) & ~3u;
      single_transfer(AL | (1u << 26) | (1u << 24) | (1u << 23) | (1u << 20) | (15u << 16) | (bits(insn, 10, 8) << 12) |
                      (bits(insn, 7, 0) << 2));
      return;
    case 0x0a:
    case 0x0b: {
      const uint32_t ro = bits(insn, 8, 6);
      if (!bit(insn, 9)) {  // STR, STRB, LDR, LDRB Rd, [Rb, Ro]
        single_transfer(AL | (3u << 25) | (1u << 24) | (1u << 23) | (bit(insn, 10) << 22) | (bit(insn, 11) << 20) |
                        (rs << 16) | (rd << 12) | ro);
      } else {                                            // STRH, LDRH, LDRSB, LDRSH Rd, [Rb, Ro]
        static constexpr uint32_t KIND[] = {1, 2, 1, 3};  // H S: 00 STRH, 01 LDRSB, 10 LDRH, 11 LDRSH
        const uint32_t hs = bits(insn, 11, 10);
        halfword_transfer(AL | (1u << 24) | (1u << 23) | ((hs != 0) ? 1u << 20 : 0) | (rs << 16) | (rd << 12) | 0x90u |
                          (KIND[hs] << 5) | ro);
      }
      return;
    }
    case 0x0c:
    case 0x0d:
    case 0x0e:
    case 0x0f: {  // STR, LDR, STRB, LDRB Rd, [Rb, #imm5 (x 4 for words)]
      const bool byte = bit(insn, 12);
      const uint32_t offset = bits(insn, 10, 6) << (byte ? 0 : 2);
      single_transfer(AL | (1u << 26) | (1u << 24) | (1u << 23) | (byte ? 1u << 22 : 0) | (bit(insn, 11) << 20) |
                      (rs << 16) | (rd << 12) | offset);
      return;
    }
    case 0x10:
    case 0x11: {  // STRH, LDRH Rd, [Rb, #imm5 x 2]
      const uint32_t offset = bits(insn, 10, 6) << 1;
      halfword_transfer(AL | (1u << 24) | (1u << 23) | (1u << 22) | (bit(insn, 11) << 20) | (rs << 16) | (rd << 12) |
                        ((offset >> 4) << 8) | 0xb0u | (offset & 15u));
      return;
    }
    case 0x12:
    case 0x13:  // STR, LDR Rd, [SP, #imm8 x 4]
      single_transfer(AL | (1u << 26) | (1u << 24) | (1u << 23) | (bit(insn, 11) << 20) | (13u << 16) |
                      (bits(insn, 10, 8) << 12) | (bits(insn, 7, 0) << 2));
      return;
    case 0x14:
    case 0x15: {  // add Rd, PC / SP, #imm8 x 4 (the PC word-aligned; no flags)
      m_info.kind = InsnClass::data_processing;
      m_info.reads = bit(insn, 11) ? 1u << 13 : 0;
      const uint32_t base = bit(insn, 11) ? m_r[13] : (m_current + 4) & ~3u;
      m_r[bits(insn, 10, 8)] = base + (bits(insn, 7, 0) << 2);
      return;
    }
    case 0x16:
    case 0x17:
      if (bits(insn, 10, 8) == 0) {  // add SP, #+-imm7 x 4
        m_info.kind = InsnClass::data_processing;
        m_info.reads = 1u << 13;
        const uint32_t offset = bits(insn, 6, 0) << 2;
        m_r[13] = bit(insn, 7) ? m_r[13] - offset : m_r[13] + offset;
      } else if (bits(insn, 10, 9) == 2) {  // PUSH {rlist, LR}, POP {rlist, PC}
        const uint32_t list = bits(insn, 7, 0) | (bit(insn, 8) << (bit(insn, 11) ? 15 : 14));
        if (list == 0) {
          undefined();
          return;
        }
        block_transfer(bit(insn, 11) ? AL | (4u << 25) | (1u << 23) | (1u << 21) | (1u << 20) | (13u << 16) | list
                                     : AL | (4u << 25) | (1u << 24) | (1u << 21) | (13u << 16) | list);
      } else {
        undefined();
      }
      return;
    case 0x18:
    case 0x19: {  // STMIA, LDMIA Rb!, {rlist}
      const uint32_t rb = bits(insn, 10, 8), list = bits(insn, 7, 0);
      if (list == 0) {
        undefined();
        return;
      }
      block_transfer(AL | (4u << 25) | (1u << 23) | (1u << 21) | (bit(insn, 11) << 20) | (rb << 16) | list);
      return;
    }
    case 0x1a:
    case 0x1b: {  // B<cond>, SWI
      const uint32_t cond = bits(insn, 11, 8);
      if (cond == 0xf) {
        m_info.kind = InsnClass::exception;
        enter(Exception::swi, m_current + 2);
      } else if (cond == 0xe) {
        undefined();
      } else {
        m_info.kind = InsnClass::branch;
        m_info.executed = condition(cond);
        if (m_info.executed) write_pc(m_current + 4 + static_cast<uint32_t>(static_cast<int32_t>(insn << 24) >> 23));
      }
      return;
    }
    case 0x1c:  // B
      m_info.kind = InsnClass::branch;
      write_pc(m_current + 4 + static_cast<uint32_t>(static_cast<int32_t>(insn << 21) >> 20));
      return;
    case 0x1e:  // BL, first half: LR = PC + (offset << 12)
      m_info.kind = InsnClass::data_processing;
      m_r[14] = m_current + 4 + static_cast<uint32_t>(static_cast<int32_t>(insn << 21) >> 9);
      return;
    case 0x1f: {  // BL, second half
      m_info.kind = InsnClass::branch;
      m_info.reads = 1u << 14;
      const uint32_t target = m_r[14] + (bits(insn, 10, 0) << 1);
      m_r[14] = (m_current + 2) | 1u;
      write_pc(target & ~1u);
      return;
    }
    default:  // 11101: BLX (ARMv5)
      undefined();
      return;
  }
}

// LR = the next instruction: + 4 in ARM state, + 2 in Thumb.
void ArmCore::undefined() {
  m_info.kind = InsnClass::exception;
  enter(Exception::undefined, m_current + (thumb() ? 2 : 4));
}

void ArmCore::unpredictable(const std::string& what) const {
  throw IssError("ISS: " + what + " at " + address_text(m_pc) + ": unpredictable on ARMv4T, not executed");
}

// The shifter operand of a register form: Rm shifted by an immediate or by
// Rs's bottom byte, with the shifter's carry-out.
uint32_t ArmCore::shifted_register(uint32_t insn, bool& carry) const {
  const unsigned rm = bits(insn, 3, 0);
  const unsigned type = bits(insn, 6, 5);
  const bool by_register = bit(insn, 4);
  // With a register shift, the instruction is a cycle longer and r15 reads +12.
  const uint32_t value = operand(rm) + (by_register && rm == 15 ? 4 : 0);
  const bool c = m_cpsr & psr::C;
  if (!by_register) {
    const unsigned amount = bits(insn, 11, 7);
    switch (type) {
      case 0: carry = amount == 0 ? c : (value >> (32 - amount)) & 1u; return amount == 0 ? value : value << amount;
      case 1:  // LSR #0 means #32
        carry = amount == 0 ? value >> 31 : (value >> (amount - 1)) & 1u;
        return amount == 0 ? 0 : value >> amount;
      case 2:  // ASR #0 means #32
        carry = amount == 0 ? value >> 31 : (value >> (amount - 1)) & 1u;
        return amount == 0 ? (value & psr::N ? ~0u : 0) : static_cast<uint32_t>(static_cast<int32_t>(value) >> amount);
      default:
        if (amount == 0) {  // RRX
          carry = value & 1u;
          return (c ? psr::N : 0) | (value >> 1);
        }
        carry = (value >> (amount - 1)) & 1u;
        return ror(value, amount);
    }
  }
  const unsigned amount = operand(bits(insn, 11, 8)) & 0xffu;
  if (amount == 0) {
    carry = c;
    return value;
  }
  switch (type) {
    case 0:
      carry = amount < 32 ? (value >> (32 - amount)) & 1u : amount == 32 ? value & 1u : 0;
      return amount < 32 ? value << amount : 0;
    case 1:
      carry = amount < 32 ? (value >> (amount - 1)) & 1u : amount == 32 ? value >> 31 : 0;
      return amount < 32 ? value >> amount : 0;
    case 2:
      if (amount >= 32) {
        carry = value >> 31;
        return value & psr::N ? ~0u : 0;
      }
      carry = (value >> (amount - 1)) & 1u;
      return static_cast<uint32_t>(static_cast<int32_t>(value) >> amount);
    default:
      if ((amount & 31) == 0) {
        carry = value >> 31;
        return value;
      }
      carry = (value >> ((amount & 31) - 1)) & 1u;
      return ror(value, amount);
  }
}

void ArmCore::data_processing(uint32_t insn) {
  bool shifter_carry = m_cpsr & psr::C;
  uint32_t op2;
  if (bit(insn, 25)) {
    const unsigned rotate = bits(insn, 11, 8) * 2;
    op2 = ror(bits(insn, 7, 0), rotate);
    if (rotate != 0) shifter_carry = op2 >> 31;
  } else {
    op2 = shifted_register(insn, shifter_carry);
  }
  const unsigned rn = bits(insn, 19, 16), rd = bits(insn, 15, 12), opcode = bits(insn, 24, 21);
  const bool set_flags = bit(insn, 20);
  m_info.kind = InsnClass::data_processing;
  m_info.register_shift = !bit(insn, 25) && bit(insn, 4);
  m_info.reads = static_cast<uint16_t>((opcode == 0xd || opcode == 0xf ? 0 : 1u << rn) |
                                       (bit(insn, 25) ? 0 : 1u << bits(insn, 3, 0)) |
                                       (m_info.register_shift ? 1u << bits(insn, 11, 8) : 0));
  const uint32_t a = operand(rn) + (!bit(insn, 25) && bit(insn, 4) && rn == 15 ? 4 : 0);
  const bool c_in = m_cpsr & psr::C;
  uint32_t result = 0;
  bool logical = false, carry = false, overflow = false;
  // a + b + carry_in, with the flags of the addition.
  auto add = [&](uint32_t x, uint32_t y, bool cin) {
    const uint64_t wide = uint64_t{x} + y + (cin ? 1 : 0);
    const auto sum = static_cast<uint32_t>(wide);
    carry = wide >> 32;
    overflow = (~(x ^ y) & (x ^ sum)) >> 31;
    return sum;
  };
  switch (opcode) {
    case 0x0:
    case 0x8:  // AND, TST
      result = a & op2;
      logical = true;
      break;
    case 0x1:
    case 0x9:  // EOR, TEQ
      result = a ^ op2;
      logical = true;
      break;
    case 0x2:
    case 0xa:  // SUB, CMP
      result = add(a, ~op2, true);
      break;
    case 0x3:  // RSB
      result = add(op2, ~a, true);
      break;
    case 0x4:
    case 0xb:  // ADD, CMN
      result = add(a, op2, false);
      break;
    case 0x5:  // ADC
      result = add(a, op2, c_in);
      break;
    case 0x6:  // SBC
      result = add(a, ~op2, c_in);
      break;
    case 0x7:  // RSC
      result = add(op2, ~a, c_in);
      break;
    case 0xc:  // ORR
      result = a | op2;
      logical = true;
      break;
    case 0xd:  // MOV
      result = op2;
      logical = true;
      break;
    case 0xe:  // BIC
      result = a & ~op2;
      logical = true;
      break;
    default:  // MVN
      result = ~op2;
      logical = true;
      break;
  }
  const bool test_only = opcode >= 0x8 && opcode <= 0xb;
  if (set_flags) {
    if (rd == 15 && !test_only) {  // SUBS pc, lr, ...: return from an exception
      set_cpsr(spsr());
    } else {
      uint32_t flags = nz(result);
      if (logical)
        flags |= (shifter_carry ? psr::C : 0) | (m_cpsr & psr::V);
      else
        flags |= (carry ? psr::C : 0) | (overflow ? psr::V : 0);
      m_cpsr = (m_cpsr & ~psr::FLAGS) | flags;
    }
  }
  if (!test_only) {
    if (rd == 15)
      write_pc(result & (thumb() ? ~1u : ~3u));
    else
      m_r[rd] = result;
  }
}

void ArmCore::multiply(uint32_t insn) {
  const unsigned rd = bits(insn, 19, 16), rn = bits(insn, 15, 12), rs = bits(insn, 11, 8), rm = bits(insn, 3, 0);
  m_info.kind = InsnClass::multiply;
  m_info.accumulate = bit(insn, 21);
  m_info.signed_multiply = true;
  m_info.multiplier = operand(rs);
  m_info.reads = static_cast<uint16_t>((1u << rm) | (1u << rs) | (m_info.accumulate ? 1u << rn : 0));
  uint32_t result = operand(rm) * operand(rs);
  if (bit(insn, 21)) result += operand(rn);
  if (bit(insn, 20))  // N and Z; C is left as it was (ARMv4: meaningless), V unchanged
    m_cpsr = (m_cpsr & ~(psr::N | psr::Z)) | nz(result);
  write_reg(rd, result);
}

void ArmCore::multiply_long(uint32_t insn) {
  const unsigned hi = bits(insn, 19, 16), lo = bits(insn, 15, 12), rs = bits(insn, 11, 8), rm = bits(insn, 3, 0);
  m_info.kind = InsnClass::multiply_long;
  m_info.accumulate = bit(insn, 21);
  m_info.signed_multiply = bit(insn, 22);
  m_info.multiplier = operand(rs);
  m_info.reads = static_cast<uint16_t>((1u << rm) | (1u << rs) | (m_info.accumulate ? (1u << hi) | (1u << lo) : 0));
  uint64_t result;
  if (bit(insn, 22))
    result = static_cast<uint64_t>(static_cast<int64_t>(static_cast<int32_t>(operand(rm))) *
                                   static_cast<int32_t>(operand(rs)));
  else
    result = uint64_t{operand(rm)} * operand(rs);
  if (bit(insn, 21)) result += (uint64_t{operand(hi)} << 32) | operand(lo);
  if (bit(insn, 20))
    m_cpsr =
        (m_cpsr & ~(psr::N | psr::Z)) | (static_cast<uint32_t>(result >> 32) & psr::N) | (result == 0 ? psr::Z : 0);
  write_reg(lo, static_cast<uint32_t>(result));
  write_reg(hi, static_cast<uint32_t>(result >> 32));
}

void ArmCore::single_transfer(uint32_t insn) {
  const bool pre = bit(insn, 24), up = bit(insn, 23), byte = bit(insn, 22), writeback = bit(insn, 21) || !pre;
  const bool load = bit(insn, 20);
  const unsigned rn = bits(insn, 19, 16), rd = bits(insn, 15, 12);
  uint32_t offset;
  if (bit(insn, 25)) {
    bool unused = false;
    offset = shifted_register(insn & ~0x10u, unused);  // immediate shifts only
  } else {
    offset = bits(insn, 11, 0);
  }
  const uint32_t base = operand(rn);
  const uint32_t moved = up ? base + offset : base - offset;
  const uint32_t address = pre ? moved : base;
  m_info.kind = load ? InsnClass::load : InsnClass::store;
  m_info.reads =
      static_cast<uint16_t>((1u << rn) | (bit(insn, 25) ? 1u << bits(insn, 3, 0) : 0) | (load ? 0 : 1u << rd));
  if (load) {
    m_info.narrow_load = byte || (address & 3u) != 0;
    m_info.loaded = static_cast<int8_t>(rd);
    uint32_t value = 0;
    if (!m_memory.read(byte ? address : address & ~3u, byte ? 1 : 4, value)) {
      enter(Exception::data_abort, m_current + 8);  // base restored: no register changed
      return;
    }
    if (!byte) value = ror(value, (address & 3u) * 8);  // ARMv4: an unaligned word load rotates
    if (writeback) write_reg(rn, moved);
    write_reg(rd, value);
  } else {
    // A stored r15 is the instruction's address + 12 (ARM9TDMI).
    const uint32_t value = rd == 15 ? m_current + 12 : operand(rd);
    if (!m_memory.write(byte ? address : address & ~3u, byte ? 1 : 4, byte ? value & 0xffu : value)) {
      enter(Exception::data_abort, m_current + 8);
      return;
    }
    if (writeback) write_reg(rn, moved);
  }
}

void ArmCore::halfword_transfer(uint32_t insn) {
  const bool pre = bit(insn, 24), up = bit(insn, 23), writeback = bit(insn, 21) || !pre, load = bit(insn, 20);
  const unsigned rn = bits(insn, 19, 16), rd = bits(insn, 15, 12), kind = bits(insn, 6, 5);
  if (!load && kind != 1) {  // LDRD/STRD are ARMv5TE
    undefined();
    return;
  }
  const uint32_t offset = bit(insn, 22) ? (bits(insn, 11, 8) << 4) | bits(insn, 3, 0) : operand(bits(insn, 3, 0));
  const uint32_t base = operand(rn);
  const uint32_t moved = up ? base + offset : base - offset;
  const uint32_t address = pre ? moved : base;
  m_info.kind = load ? InsnClass::load : InsnClass::store;
  m_info.reads =
      static_cast<uint16_t>((1u << rn) | (bit(insn, 22) ? 0 : 1u << bits(insn, 3, 0)) | (load ? 0 : 1u << rd));
  if (load) {
    m_info.narrow_load = true;
    m_info.loaded = static_cast<int8_t>(rd);
    const bool half = kind != 2;
    uint32_t value = 0;
    if (!m_memory.read(half ? address & ~1u : address, half ? 2 : 1, value)) {
      enter(Exception::data_abort, m_current + 8);
      return;
    }
    if (kind == 2)
      value = static_cast<uint32_t>(static_cast<int32_t>(static_cast<int8_t>(value & 0xffu)));
    else if (kind == 3)
      value = static_cast<uint32_t>(static_cast<int16_t>(value));
    if (writeback) write_reg(rn, moved);
    write_reg(rd, value);
  } else {
    const uint32_t value = rd == 15 ? m_current + 12 : operand(rd);
    if (!m_memory.write(address & ~1u, 2, value & 0xffffu)) {
      enter(Exception::data_abort, m_current + 8);
      return;
    }
    if (writeback) write_reg(rn, moved);
  }
}

void ArmCore::block_transfer(uint32_t insn) {
  const bool pre = bit(insn, 24), up = bit(insn, 23), user_bank = bit(insn, 22), writeback = bit(insn, 21);
  const bool load = bit(insn, 20);
  const unsigned rn = bits(insn, 19, 16);
  const uint32_t list = bits(insn, 15, 0);
  if (list == 0) unpredictable("LDM/STM with an empty register list");
  const auto count = static_cast<uint32_t>(__builtin_popcount(list));
  const uint32_t base = operand(rn);
  // The lowest register goes to the lowest address, whatever the direction.
  uint32_t address = up ? base + (pre ? 4 : 0) : base - 4 * count + (pre ? 0 : 4);
  const uint32_t final_base = up ? base + 4 * count : base - 4 * count;
  const bool loads_pc = load && (list & 0x8000u);
  m_info.kind = load ? InsnClass::load_multiple : InsnClass::store_multiple;
  m_info.registers = static_cast<uint8_t>(count);
  m_info.reads = static_cast<uint16_t>((1u << rn) | (load ? 0 : list));
  if (load && !loads_pc) m_info.loaded = static_cast<int8_t>(31 - __builtin_clz(list));
  // S without r15 loaded: the user-mode registers (r8..r14 of usr).
  const bool user_registers = user_bank && !loads_pc;
  const unsigned bank = bank_of(mode());
  auto user_reg = [&](unsigned n) -> uint32_t& {
    if (n >= 8 && n < 13 && bank == 1) return m_user_r8_12[n - 8];
    if (n >= 13 && n < 15 && bank != 0) return m_r13_14[0][n - 13];
    return m_r[n];
  };
  std::array<uint32_t, 16> loaded{};
  bool first = true;
  for (unsigned n = 0; n < 16; ++n) {
    if (!(list & (1u << n))) continue;
    if (load) {
      if (!m_memory.read(address, 4, loaded[n])) {
        enter(Exception::data_abort, m_current + 8);
        return;
      }
    } else {
      uint32_t value;
      if (n == 15)
        value = m_current + 12;
      else if (user_registers)
        value = user_reg(n);
      else if (n == rn && writeback && !first)  // ARM9TDMI: the base after write-back
        value = final_base;
      else
        value = operand(n);
      if (!m_memory.write(address, 4, value)) {
        enter(Exception::data_abort, m_current + 8);
        return;
      }
    }
    first = false;
    address += 4;
  }
  if (writeback) m_r[rn] = final_base;  // rn == 15 is unpredictable; never the PC here
  if (load) {
    for (unsigned n = 0; n < 15; ++n)
      if (list & (1u << n)) (user_registers ? user_reg(n) : m_r[n]) = loaded[n];
    if (loads_pc) {
      if (user_bank) set_cpsr(spsr());  // LDM ..^ with the PC: return from an exception
      write_pc(loaded[15] & (thumb() ? ~1u : ~3u));
    }
  }
}

void ArmCore::swap(uint32_t insn) {
  const bool byte = bit(insn, 22);
  const unsigned rn = bits(insn, 19, 16), rd = bits(insn, 15, 12), rm = bits(insn, 3, 0);
  const uint32_t address = operand(rn);
  m_info.kind = InsnClass::swap;
  m_info.reads = static_cast<uint16_t>((1u << rn) | (1u << rm));
  m_info.loaded = static_cast<int8_t>(rd);
  m_info.narrow_load = byte || (address & 3u) != 0;
  uint32_t old = 0;
  if (!m_memory.read(byte ? address : address & ~3u, byte ? 1 : 4, old) ||
      !m_memory.write(byte ? address : address & ~3u, byte ? 1 : 4, byte ? operand(rm) & 0xffu : operand(rm))) {
    enter(Exception::data_abort, m_current + 8);
    return;
  }
  write_reg(rd, byte ? old : ror(old, (address & 3u) * 8));
}

void ArmCore::status_transfer(uint32_t insn) {
  const bool use_spsr = bit(insn, 22);
  m_info.kind = bit(insn, 21) ? InsnClass::status_write : InsnClass::status_read;
  if (!bit(insn, 21)) {  // MRS
    if ((insn & 0x0fbf0fffu) != 0x010f0000u) {
      undefined();
      return;
    }
    write_reg(bits(insn, 15, 12), use_spsr ? spsr() : m_cpsr);
    return;
  }
  uint32_t value;
  if (bit(insn, 25)) {
    value = ror(bits(insn, 7, 0), bits(insn, 11, 8) * 2);
  } else {
    value = operand(bits(insn, 3, 0));
    m_info.reads = static_cast<uint16_t>(1u << bits(insn, 3, 0));
  }
  uint32_t mask = 0;
  const uint32_t fields = bits(insn, 19, 16);
  m_info.control_write = !use_spsr && (fields & 1u);
  if (fields & 8u) mask |= 0xff000000u;
  if (fields & 4u) mask |= 0x00ff0000u;
  if (fields & 2u) mask |= 0x0000ff00u;
  if (fields & 1u) mask |= 0x000000ffu;
  const bool privileged = mode() != Mode::usr;
  if (use_spsr) {
    set_spsr((spsr() & ~mask) | (value & mask));
    return;
  }
  if (!privileged) mask &= psr::FLAGS;  // user mode writes the flags only
  mask &= ~psr::T;                      // MSR does not change the state (ARMv4T)
  set_cpsr((m_cpsr & ~mask) | (value & mask));
}

void ArmCore::coprocessor_transfer(uint32_t insn) {
  const unsigned cp = bits(insn, 11, 8), op1 = bits(insn, 23, 21), crn = bits(insn, 19, 16);
  const unsigned rd = bits(insn, 15, 12), op2 = bits(insn, 7, 5), crm = bits(insn, 3, 0);
  const bool privileged = mode() != Mode::usr;
  m_info.kind = bit(insn, 20) ? InsnClass::coprocessor_read : InsnClass::coprocessor_write;
  if (!bit(insn, 20)) m_info.reads = static_cast<uint16_t>(1u << rd);
  if (m_coprocessors == nullptr) {
    undefined();
    return;
  }
  if (bit(insn, 20)) {  // MRC
    uint32_t value = 0;
    if (!m_coprocessors->mrc(cp, op1, crn, crm, op2, privileged, value)) {
      undefined();
      return;
    }
    if (rd == 15)  // flags from the value
      m_cpsr = (m_cpsr & ~psr::FLAGS) | (value & psr::FLAGS);
    else
      m_r[rd] = value;
  } else if (!m_coprocessors->mcr(cp, op1, crn, crm, op2, privileged, rd == 15 ? m_current + 12 : operand(rd))) {
    undefined();
  }
}

}  // namespace tessera::iss
