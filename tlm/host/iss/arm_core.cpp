#include "host/iss/arm_core.h"

#include <algorithm>
#include <cstdio>
#include <utility>

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

// x + y + carry_in, with the addition's carry and overflow.
inline uint32_t add_with_flags(uint32_t x, uint32_t y, bool carry_in, bool& carry, bool& overflow) {
  const uint64_t wide = uint64_t{x} + y + (carry_in ? 1 : 0);
  const auto sum = static_cast<uint32_t>(wide);
  carry = (wide >> 32) != 0;
  overflow = ((~(x ^ y) & (x ^ sum)) >> 31) != 0;
  return sum;
}

// A register operand shifted by an immediate, as encoded (LSR and ASR #0
// mean #32, ROR #0 is RRX), with the shifter's carry-out; c is the C flag.
inline uint32_t shift_by_immediate(uint32_t value, unsigned type, unsigned amount, bool c, bool& carry) {
  switch (type) {
    case 0:
      if (amount == 0) {
        carry = c;
        return value;
      }
      carry = (value >> (32 - amount)) & 1u;
      return value << amount;
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

// A register operand shifted by Rs's bottom byte (0..255), with the carry-out.
inline uint32_t shift_by_register(uint32_t value, unsigned type, unsigned amount, bool c, bool& carry) {
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

// ARM encodings the Thumb instructions are executed as (condition AL).
constexpr uint32_t AL = 0xe0000000u;
constexpr uint32_t dp(uint32_t opcode, bool set_flags, uint32_t rn, uint32_t rd, uint32_t operand2) {
  return AL | (opcode << 21) | (set_flags ? 1u << 20 : 0) | (rn << 16) | (rd << 12) | operand2;
}
constexpr uint32_t IMMEDIATE = 1u << 25;
constexpr uint32_t shift_by_register_operand(uint32_t rs, uint32_t type, uint32_t rm) {
  return (rs << 8) | (type << 5) | (1u << 4) | rm;
}
// Data-processing opcodes.
enum DpOpcode : uint32_t { and_ = 0, eor, sub, rsb, add, adc, sbc, rsc, tst, teq, cmp, cmn, orr, mov, bic, mvn };

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

ArmCore::ArmCore(IssMemory& memory, Coprocessors* coprocessors)
    : m_memory(memory), m_resident(memory.resident_lines()), m_coprocessors(coprocessors) {
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

// LR = the next instruction: + 4 in ARM state, + 2 in Thumb.
void ArmCore::undefined() {
  m_info.kind = InsnClass::exception;
  enter(Exception::undefined, m_current + (thumb() ? 2 : 4));
}

void ArmCore::unpredictable(const std::string& what) const {
  throw IssError("ISS: " + what + " at " + address_text(m_pc) + ": unpredictable on ARMv4T, not executed");
}

// A taken branch to itself. With IRQ and FIQ both masked nothing can take
// the core out of it (no interrupt is taken, the flags the branch tested do
// not change), so the program has stopped for good: refused at once rather
// than run to the instruction limit (minutes of wall time in the SoC).
void ArmCore::check_progress() const {
  if ((m_cpsr & (psr::I | psr::F)) == (psr::I | psr::F))
    throw IssError("ISS: a branch to itself at pc " + address_text(m_current) +
                   " with IRQ and FIQ masked: the program can never leave it (a hung program, stopped)");
}

// The handlers, one per instruction form, and the decoders that choose
// them. A handler finds its operands' register numbers and immediates in the
// entry and the static part of its StepInfo already in m_info; it adds what
// depends on the operands (an unaligned load, the multiplier, an exception).
struct ArmCore::Exec {
  enum class Form : uint8_t { immediate, plain_register, shift_by_immediate, shift_by_register };

  template <unsigned OP, bool S, Form F>
  static void data_processing(ArmCore& c, const Decoded& d) {
    constexpr bool TEST_ONLY = OP >= tst && OP <= cmn;
    constexpr bool LOGICAL = OP == and_ || OP == eor || OP == tst || OP == teq || OP >= orr;
    const bool c_in = (c.m_cpsr & psr::C) != 0;
    [[maybe_unused]] bool shifter_carry = c_in;
    uint32_t a = c.m_r[d.rn];
    uint32_t b;
    if constexpr (F == Form::immediate) {
      b = d.imm;
      if (d.shift_amount != 0) shifter_carry = b >> 31;
    } else if constexpr (F == Form::plain_register) {
      b = c.m_r[d.rm];
    } else if constexpr (F == Form::shift_by_immediate) {
      b = shift_by_immediate(c.m_r[d.rm], d.shift_type, d.shift_amount, c_in, shifter_carry);
    } else {  // with a register shift, r15 reads as the instruction's address + 12
      b = shift_by_register(c.m_r[d.rm] + (d.rm == 15 ? 4 : 0), d.shift_type, c.m_r[d.rs] & 0xffu, c_in, shifter_carry);
      if (d.rn == 15) a += 4;
    }
    [[maybe_unused]] bool carry = false, overflow = false;
    uint32_t result;
    if constexpr (OP == and_ || OP == tst)
      result = a & b;
    else if constexpr (OP == eor || OP == teq)
      result = a ^ b;
    else if constexpr (OP == sub || OP == cmp)
      result = add_with_flags(a, ~b, true, carry, overflow);
    else if constexpr (OP == rsb)
      result = add_with_flags(b, ~a, true, carry, overflow);
    else if constexpr (OP == add || OP == cmn)
      result = add_with_flags(a, b, false, carry, overflow);
    else if constexpr (OP == adc)
      result = add_with_flags(a, b, c_in, carry, overflow);
    else if constexpr (OP == sbc)
      result = add_with_flags(a, ~b, c_in, carry, overflow);
    else if constexpr (OP == rsc)
      result = add_with_flags(b, ~a, c_in, carry, overflow);
    else if constexpr (OP == orr)
      result = a | b;
    else if constexpr (OP == mov)
      result = b;
    else if constexpr (OP == bic)
      result = a & ~b;
    else
      result = ~b;
    if constexpr (S) {
      if (!TEST_ONLY && d.rd == 15) {  // SUBS pc, lr, ...: return from an exception
        c.set_cpsr(c.spsr());
      } else {
        uint32_t flags = nz(result);
        if constexpr (LOGICAL)
          flags |= (shifter_carry ? psr::C : 0) | (c.m_cpsr & psr::V);
        else
          flags |= (carry ? psr::C : 0) | (overflow ? psr::V : 0);
        c.m_cpsr = (c.m_cpsr & ~psr::FLAGS) | flags;
      }
    }
    if constexpr (!TEST_ONLY) {
      if (d.rd == 15)
        c.write_pc(result & (c.thumb() ? ~1u : ~3u));
      else
        c.m_r[d.rd] = result;
    }
  }

  // MUL, MLA: rd is bits 19:16, rn (the accumulator) bits 15:12.
  static void multiply(ArmCore& c, const Decoded& d) {
    const uint32_t multiplier = c.m_r[d.rs];
    c.m_info.multiplier = multiplier;
    uint32_t result = c.m_r[d.rm] * multiplier;
    if (bit(d.insn, 21)) result += c.m_r[d.rn];
    if (bit(d.insn, 20))  // N and Z; C is left as it was (ARMv4: meaningless), V unchanged
      c.m_cpsr = (c.m_cpsr & ~(psr::N | psr::Z)) | nz(result);
    c.write_reg(d.rd, result);
  }

  // UMULL, UMLAL, SMULL, SMLAL: rd is RdHi (bits 19:16), rn RdLo (15:12).
  static void multiply_long(ArmCore& c, const Decoded& d) {
    const uint32_t multiplier = c.m_r[d.rs];
    c.m_info.multiplier = multiplier;
    uint64_t result;
    if (bit(d.insn, 22))
      result = static_cast<uint64_t>(static_cast<int64_t>(static_cast<int32_t>(c.m_r[d.rm])) *
                                     static_cast<int32_t>(multiplier));
    else
      result = uint64_t{c.m_r[d.rm]} * multiplier;
    if (bit(d.insn, 21)) result += (uint64_t{c.m_r[d.rd]} << 32) | c.m_r[d.rn];
    if (bit(d.insn, 20))
      c.m_cpsr =
          (c.m_cpsr & ~(psr::N | psr::Z)) | (static_cast<uint32_t>(result >> 32) & psr::N) | (result == 0 ? psr::Z : 0);
    c.write_reg(d.rn, static_cast<uint32_t>(result));
    c.write_reg(d.rd, static_cast<uint32_t>(result >> 32));
  }

  // LDR, STR, LDRB, STRB; an immediate offset is in imm with its sign.
  template <bool LOAD, bool BYTE, bool REGISTER_OFFSET>
  static void single_transfer(ArmCore& c, const Decoded& d) {
    const uint32_t base = c.m_r[d.rn];
    uint32_t moved;
    if constexpr (REGISTER_OFFSET) {
      bool unused = false;
      const uint32_t offset =
          shift_by_immediate(c.m_r[d.rm], d.shift_type, d.shift_amount, (c.m_cpsr & psr::C) != 0, unused);
      moved = d.up ? base + offset : base - offset;
    } else {
      moved = base + d.imm;
    }
    const bool pre = bit(d.insn, 24), writeback = bit(d.insn, 21) || !pre;
    const uint32_t address = pre ? moved : base;
    if constexpr (LOAD) {
      if (!BYTE && (address & 3u) != 0) c.m_info.narrow_load = true;
      uint32_t value = 0;
      if (!c.m_memory.read(BYTE ? address : address & ~3u, BYTE ? 1 : 4, value)) {
        c.enter(Exception::data_abort, c.m_current + 8);  // base restored: no register changed
        return;
      }
      if constexpr (!BYTE) value = ror(value, (address & 3u) * 8);  // ARMv4: an unaligned word load rotates
      if (writeback) c.write_reg(d.rn, moved);
      c.write_reg(d.rd, value);
    } else {
      // A stored r15 is the instruction's address + 12 (ARM9TDMI).
      const uint32_t value = d.rd == 15 ? c.m_current + 12 : c.m_r[d.rd];
      if (!c.m_memory.write(BYTE ? address : address & ~3u, BYTE ? 1 : 4, BYTE ? value & 0xffu : value)) {
        c.enter(Exception::data_abort, c.m_current + 8);
        return;
      }
      if (writeback) c.write_reg(d.rn, moved);
    }
  }

  // Thumb's LDR Rd, [PC, #imm8 x 4]: the PC word-aligned.
  static void thumb_load_literal(ArmCore& c, const Decoded& d) {
    c.m_r[15] &= ~3u;
    single_transfer<true, false, false>(c, d);
  }

  // LDRH, STRH, LDRSB, LDRSH; an immediate offset is in imm with its sign.
  static void halfword_transfer(ArmCore& c, const Decoded& d) {
    const bool pre = bit(d.insn, 24), writeback = bit(d.insn, 21) || !pre, load = bit(d.insn, 20);
    const unsigned kind = bits(d.insn, 6, 5);
    const uint32_t base = c.m_r[d.rn];
    const uint32_t moved = bit(d.insn, 22) ? base + d.imm : d.up ? base + c.m_r[d.rm] : base - c.m_r[d.rm];
    const uint32_t address = pre ? moved : base;
    if (load) {
      const bool half = kind != 2;
      uint32_t value = 0;
      if (!c.m_memory.read(half ? address & ~1u : address, half ? 2 : 1, value)) {
        c.enter(Exception::data_abort, c.m_current + 8);
        return;
      }
      if (kind == 2)
        value = static_cast<uint32_t>(static_cast<int32_t>(static_cast<int8_t>(value & 0xffu)));
      else if (kind == 3)
        value = static_cast<uint32_t>(static_cast<int16_t>(value));
      if (writeback) c.write_reg(d.rn, moved);
      c.write_reg(d.rd, value);
    } else {
      const uint32_t value = d.rd == 15 ? c.m_current + 12 : c.m_r[d.rd];
      if (!c.m_memory.write(address & ~1u, 2, value & 0xffffu)) {
        c.enter(Exception::data_abort, c.m_current + 8);
        return;
      }
      if (writeback) c.write_reg(d.rn, moved);
    }
  }

  // LDM, STM (and Thumb's PUSH, POP, LDMIA, STMIA as the LDM/STM they are).
  static void block_transfer(ArmCore& c, const Decoded& d) {
    const uint32_t insn = d.insn;
    const bool pre = bit(insn, 24), up = bit(insn, 23), user_bank = bit(insn, 22), writeback = bit(insn, 21);
    const bool load = bit(insn, 20);
    const unsigned rn = d.rn;
    const uint32_t list = bits(insn, 15, 0);
    const uint32_t count = d.info.registers;
    const uint32_t base = c.m_r[rn];
    // The lowest register goes to the lowest address, whatever the direction.
    uint32_t address = up ? base + (pre ? 4 : 0) : base - 4 * count + (pre ? 0 : 4);
    const uint32_t final_base = up ? base + 4 * count : base - 4 * count;
    const bool loads_pc = load && (list & 0x8000u);
    // S without r15 loaded: the user-mode registers (r8..r14 of usr).
    const bool user_registers = user_bank && !loads_pc;
    const unsigned bank = bank_of(c.mode());
    auto user_reg = [&](unsigned n) -> uint32_t& {
      if (n >= 8 && n < 13 && bank == 1) return c.m_user_r8_12[n - 8];
      if (n >= 13 && n < 15 && bank != 0) return c.m_r13_14[0][n - 13];
      return c.m_r[n];
    };
    // The transfer is one block access of the port (a burst where the host
    // makes one), the lowest register at the lowest address: word i is the
    // list's i-th register, found by its set bits in turn.
    std::array<uint32_t, 16> words;  // the first `count` are written before they are read
    if (!load) {
      unsigned i = 0;
      for (uint32_t rest = list; rest != 0; rest &= rest - 1, ++i) {
        const auto n = static_cast<unsigned>(__builtin_ctz(rest));
        if (n == 15)
          words[i] = c.m_current + 12;
        else if (user_registers)
          words[i] = user_reg(n);
        else if (n == rn && writeback && i != 0)  // ARM9TDMI: the base after write-back
          words[i] = final_base;
        else
          words[i] = c.m_r[n];
      }
    }
    if (!(load ? c.m_memory.read_block(address, words.data(), count)
               : c.m_memory.write_block(address, words.data(), count))) {
      c.enter(Exception::data_abort, c.m_current + 8);
      return;
    }
    if (writeback) c.m_r[rn] = final_base;  // rn == 15 is unpredictable; never the PC here
    if (load) {
      // After the write-back: a loaded base keeps the value loaded.
      unsigned i = 0;
      for (uint32_t rest = list & 0x7fffu; rest != 0; rest &= rest - 1, ++i) {
        const auto n = static_cast<unsigned>(__builtin_ctz(rest));
        (user_registers ? user_reg(n) : c.m_r[n]) = words[i];
      }
      if (loads_pc) {                         // the highest register: the last word
        if (user_bank) c.set_cpsr(c.spsr());  // LDM ..^ with the PC: return from an exception
        c.write_pc(words[count - 1] & (c.thumb() ? ~1u : ~3u));
      }
    }
  }

  static void empty_register_list(ArmCore& c, const Decoded&) {
    c.unpredictable("LDM/STM with an empty register list");
  }

  static void swap(ArmCore& c, const Decoded& d) {
    const bool byte = bit(d.insn, 22);
    const uint32_t address = c.m_r[d.rn];
    if ((address & 3u) != 0) c.m_info.narrow_load = true;
    uint32_t old = 0;
    if (!c.m_memory.read(byte ? address : address & ~3u, byte ? 1 : 4, old) ||
        !c.m_memory.write(byte ? address : address & ~3u, byte ? 1 : 4, byte ? c.m_r[d.rm] & 0xffu : c.m_r[d.rm])) {
      c.enter(Exception::data_abort, c.m_current + 8);
      return;
    }
    c.write_reg(d.rd, byte ? old : ror(old, (address & 3u) * 8));
  }

  static void status_read(ArmCore& c, const Decoded& d) { c.write_reg(d.rd, bit(d.insn, 22) ? c.spsr() : c.m_cpsr); }

  static void status_write(ArmCore& c, const Decoded& d) {
    const bool use_spsr = bit(d.insn, 22);
    const uint32_t value = bit(d.insn, 25) ? d.imm : c.m_r[d.rm];
    uint32_t mask = 0;
    const uint32_t fields = bits(d.insn, 19, 16);
    if (fields & 8u) mask |= 0xff000000u;
    if (fields & 4u) mask |= 0x00ff0000u;
    if (fields & 2u) mask |= 0x0000ff00u;
    if (fields & 1u) mask |= 0x000000ffu;
    if (use_spsr) {
      c.set_spsr((c.spsr() & ~mask) | (value & mask));
      return;
    }
    if (c.mode() == Mode::usr) mask &= psr::FLAGS;  // user mode writes the flags only
    mask &= ~psr::T;                                // MSR does not change the state (ARMv4T)
    c.set_cpsr((c.m_cpsr & ~mask) | (value & mask));
  }

  static void coprocessor_transfer(ArmCore& c, const Decoded& d) {
    const uint32_t insn = d.insn;
    const unsigned cp = bits(insn, 11, 8), op1 = bits(insn, 23, 21), crn = bits(insn, 19, 16);
    const unsigned rd = bits(insn, 15, 12), op2 = bits(insn, 7, 5), crm = bits(insn, 3, 0);
    const bool privileged = c.mode() != Mode::usr;
    if (c.m_coprocessors == nullptr) {
      c.undefined();
      return;
    }
    if (bit(insn, 20)) {  // MRC
      uint32_t value = 0;
      if (!c.m_coprocessors->mrc(cp, op1, crn, crm, op2, privileged, value)) {
        c.undefined();
        return;
      }
      if (rd == 15)  // flags from the value
        c.m_cpsr = (c.m_cpsr & ~psr::FLAGS) | (value & psr::FLAGS);
      else
        c.m_r[rd] = value;
    } else {
      // A write may turn the instruction cache off or invalidate it: the
      // next fetch asks the port again (ResidentLines).
      if (c.m_resident != nullptr) c.m_resident->revoke_all();
      if (!c.m_coprocessors->mcr(cp, op1, crn, crm, op2, privileged, rd == 15 ? c.m_current + 12 : c.m_r[rd]))
        c.undefined();
    }
  }

  // B, BL: imm is the displacement from the instruction + 8.
  static void branch(ArmCore& c, const Decoded& d) {
    const uint32_t target = c.m_r[15] + d.imm;
    if (target == c.m_current) c.check_progress();
    if (bit(d.insn, 24)) c.m_r[14] = c.m_current + 4;
    c.write_pc(target);
  }

  // BX, in either state.
  static void branch_exchange(ArmCore& c, const Decoded& d) {
    const uint32_t target = c.m_r[d.rm];
    c.m_cpsr = (c.m_cpsr & ~psr::T) | (target & 1u ? psr::T : 0);
    c.write_pc(target & (target & 1u ? ~1u : ~3u));
  }

  // SWI: LR = the next instruction.
  static void software_interrupt(ArmCore& c, const Decoded&) {
    c.enter(Exception::swi, c.m_current + (c.thumb() ? 2 : 4));
  }

  static void undefined_instruction(ArmCore& c, const Decoded&) { c.undefined(); }

  // Thumb's ADD Rd, PC / SP, #imm8 x 4 (the PC word-aligned; no flags): rn is 13 or 15.
  static void thumb_add_address(ArmCore& c, const Decoded& d) {
    const uint32_t base = d.rn == 13 ? c.m_r[13] : (c.m_current + 4) & ~3u;
    c.m_r[d.rd] = base + d.imm;
  }

  // Thumb's ADD SP, #+-imm7 x 4: imm with its sign.
  static void thumb_adjust_sp(ArmCore& c, const Decoded& d) { c.m_r[13] += d.imm; }

  // Thumb's B<cond>: its own condition (bits 11:8), imm from the instruction.
  static void thumb_branch_conditional(ArmCore& c, const Decoded& d) {
    c.m_info.executed = c.condition(bits(d.insn, 11, 8));
    if (!c.m_info.executed) return;
    if (d.imm == 0) c.check_progress();
    c.write_pc(c.m_current + d.imm);
  }

  // Thumb's B: imm from the instruction.
  static void thumb_branch(ArmCore& c, const Decoded& d) {
    if (d.imm == 0) c.check_progress();
    c.write_pc(c.m_current + d.imm);
  }

  // BL, first half: LR = PC + (offset << 12), imm from the instruction.
  static void thumb_branch_link_high(ArmCore& c, const Decoded& d) { c.m_r[14] = c.m_current + d.imm; }

  // BL, second half.
  static void thumb_branch_link_low(ArmCore& c, const Decoded& d) {
    const uint32_t target = c.m_r[14] + d.imm;
    c.m_r[14] = (c.m_current + 2) | 1u;
    c.write_pc(target & ~1u);
  }

  template <Form F, bool S, size_t... OP>
  static constexpr std::array<Handler, 16> data_processing_row(std::index_sequence<OP...>) {
    return {{&data_processing<OP, S, F>...}};
  }

  static Handler data_processing_handler(Form form, bool set_flags, unsigned opcode) {
    constexpr auto OPS = std::make_index_sequence<16>();
    static constexpr std::array<std::array<Handler, 16>, 8> TABLE = {
        data_processing_row<Form::immediate, false>(OPS),
        data_processing_row<Form::immediate, true>(OPS),
        data_processing_row<Form::plain_register, false>(OPS),
        data_processing_row<Form::plain_register, true>(OPS),
        data_processing_row<Form::shift_by_immediate, false>(OPS),
        data_processing_row<Form::shift_by_immediate, true>(OPS),
        data_processing_row<Form::shift_by_register, false>(OPS),
        data_processing_row<Form::shift_by_register, true>(OPS),
    };
    return TABLE[static_cast<unsigned>(form) * 2 + (set_flags ? 1 : 0)][opcode];
  }

  static Handler single_transfer_handler(bool load, bool byte, bool register_offset) {
    static constexpr Handler TABLE[8] = {
        &single_transfer<false, false, false>, &single_transfer<false, false, true>,
        &single_transfer<false, true, false>,  &single_transfer<false, true, true>,
        &single_transfer<true, false, false>,  &single_transfer<true, false, true>,
        &single_transfer<true, true, false>,   &single_transfer<true, true, true>,
    };
    return TABLE[(load ? 4 : 0) + (byte ? 2 : 0) + (register_offset ? 1 : 0)];
  }

  static void decode_undefined(Decoded& d) {
    d.handler = &undefined_instruction;
    d.info.kind = InsnClass::exception;
  }

  static void decode_data_processing(uint32_t insn, Decoded& d) {
    const unsigned opcode = bits(insn, 24, 21);
    const bool immediate = bit(insn, 25);
    d.info.kind = InsnClass::data_processing;
    d.info.register_shift = !immediate && bit(insn, 4);
    d.info.reads = static_cast<uint16_t>((opcode == mov || opcode == mvn ? 0 : 1u << d.rn) |
                                         (immediate ? 0 : 1u << d.rm) | (d.info.register_shift ? 1u << d.rs : 0));
    Form form;
    if (immediate) {
      form = Form::immediate;
      d.shift_amount = static_cast<uint8_t>(bits(insn, 11, 8) * 2);
      d.imm = ror(bits(insn, 7, 0), d.shift_amount);
    } else {
      d.shift_type = static_cast<uint8_t>(bits(insn, 6, 5));
      d.shift_amount = static_cast<uint8_t>(bits(insn, 11, 7));
      if (bit(insn, 4))
        form = Form::shift_by_register;
      else if (d.shift_type == 0 && d.shift_amount == 0)  // LSL #0: the register as it is
        form = Form::plain_register;
      else
        form = Form::shift_by_immediate;
    }
    d.handler = data_processing_handler(form, bit(insn, 20), opcode);
  }

  static void decode_single_transfer(uint32_t insn, Decoded& d) {
    const bool load = bit(insn, 20), byte = bit(insn, 22), register_offset = bit(insn, 25);
    d.info.kind = load ? InsnClass::load : InsnClass::store;
    d.info.reads = static_cast<uint16_t>((1u << d.rn) | (register_offset ? 1u << d.rm : 0) | (load ? 0 : 1u << d.rd));
    if (load) {
      d.info.narrow_load = byte;  // and an unaligned word, found when executed
      d.info.loaded = static_cast<int8_t>(d.rd);
    }
    d.up = bit(insn, 23);
    if (register_offset) {
      d.shift_type = static_cast<uint8_t>(bits(insn, 6, 5));
      d.shift_amount = static_cast<uint8_t>(bits(insn, 11, 7));
    } else {
      d.imm = d.up ? bits(insn, 11, 0) : 0u - bits(insn, 11, 0);
    }
    d.handler = single_transfer_handler(load, byte, register_offset);
  }

  static void decode_halfword_transfer(uint32_t insn, Decoded& d) {
    const bool load = bit(insn, 20);
    if (!load && bits(insn, 6, 5) != 1) {  // LDRD/STRD are ARMv5TE
      decode_undefined(d);
      return;
    }
    const bool immediate = bit(insn, 22);
    d.info.kind = load ? InsnClass::load : InsnClass::store;
    d.info.reads = static_cast<uint16_t>((1u << d.rn) | (immediate ? 0 : 1u << d.rm) | (load ? 0 : 1u << d.rd));
    if (load) {
      d.info.narrow_load = true;
      d.info.loaded = static_cast<int8_t>(d.rd);
    }
    d.up = bit(insn, 23);
    const uint32_t offset = (bits(insn, 11, 8) << 4) | bits(insn, 3, 0);
    if (immediate) d.imm = d.up ? offset : 0u - offset;
    d.handler = &halfword_transfer;
  }

  static void decode_block_transfer(uint32_t insn, Decoded& d) {
    const uint32_t list = bits(insn, 15, 0);
    if (list == 0) {
      d.handler = &empty_register_list;
      return;
    }
    const bool load = bit(insn, 20);
    const bool loads_pc = load && (list & 0x8000u);
    d.info.kind = load ? InsnClass::load_multiple : InsnClass::store_multiple;
    d.info.registers = static_cast<uint8_t>(__builtin_popcount(list));
    d.info.reads = static_cast<uint16_t>((1u << d.rn) | (load ? 0 : list));
    if (load && !loads_pc) d.info.loaded = static_cast<int8_t>(31 - __builtin_clz(list));
    d.handler = &block_transfer;
  }

  static void decode_status_transfer(uint32_t insn, Decoded& d) {
    if (!bit(insn, 21)) {  // MRS
      if ((insn & 0x0fbf0fffu) != 0x010f0000u) {
        decode_undefined(d);
        return;
      }
      d.info.kind = InsnClass::status_read;
      d.handler = &status_read;
      return;
    }
    d.info.kind = InsnClass::status_write;
    if (bit(insn, 25))
      d.imm = ror(bits(insn, 7, 0), bits(insn, 11, 8) * 2);
    else
      d.info.reads = static_cast<uint16_t>(1u << d.rm);
    d.info.control_write = !bit(insn, 22) && (bits(insn, 19, 16) & 1u);
    d.handler = &status_write;
  }

  static void decode_arm(uint32_t insn, Decoded& d) {
    d = Decoded{};
    d.insn = insn;
    d.cond = static_cast<uint8_t>(insn >> 28);
    d.rd = static_cast<uint8_t>(bits(insn, 15, 12));
    d.rn = static_cast<uint8_t>(bits(insn, 19, 16));
    d.rm = static_cast<uint8_t>(bits(insn, 3, 0));
    d.rs = static_cast<uint8_t>(bits(insn, 11, 8));
    d.info.executed = true;
    switch (bits(insn, 27, 25)) {
      case 0:
        if ((insn & 0x0ffffff0u) == 0x012fff10u) {  // BX
          d.info.kind = InsnClass::branch;
          d.info.reads = static_cast<uint16_t>(1u << d.rm);
          d.handler = &branch_exchange;
        } else if ((insn & 0x0fc000f0u) == 0x00000090u) {  // MUL, MLA: Rd is bits 19:16, Rn 15:12
          std::swap(d.rd, d.rn);
          d.info.kind = InsnClass::multiply;
          d.info.accumulate = bit(insn, 21);
          d.info.signed_multiply = true;
          d.info.reads = static_cast<uint16_t>((1u << d.rm) | (1u << d.rs) | (d.info.accumulate ? 1u << d.rn : 0));
          d.handler = &multiply;
        } else if ((insn & 0x0f8000f0u) == 0x00800090u) {  // RdHi is bits 19:16, RdLo 15:12
          const unsigned hi = bits(insn, 19, 16), lo = bits(insn, 15, 12);
          d.rd = static_cast<uint8_t>(hi);
          d.rn = static_cast<uint8_t>(lo);
          d.info.kind = InsnClass::multiply_long;
          d.info.accumulate = bit(insn, 21);
          d.info.signed_multiply = bit(insn, 22);
          d.info.reads =
              static_cast<uint16_t>((1u << d.rm) | (1u << d.rs) | (d.info.accumulate ? (1u << hi) | (1u << lo) : 0));
          d.handler = &multiply_long;
        } else if ((insn & 0x0fb00ff0u) == 0x01000090u) {
          d.info.kind = InsnClass::swap;
          d.info.reads = static_cast<uint16_t>((1u << d.rn) | (1u << d.rm));
          d.info.loaded = static_cast<int8_t>(d.rd);
          d.info.narrow_load = bit(insn, 22);  // and an unaligned word, found when executed
          d.handler = &swap;
        } else if ((insn & 0x0e000090u) == 0x00000090u) {
          decode_halfword_transfer(insn, d);
        } else if ((insn & 0x01900000u) == 0x01000000u) {  // TST..CMN without S: MRS/MSR
          decode_status_transfer(insn, d);
        } else {
          decode_data_processing(insn, d);
        }
        break;
      case 1:
        if ((insn & 0x01900000u) == 0x01000000u)
          decode_status_transfer(insn, d);
        else
          decode_data_processing(insn, d);
        break;
      case 2: decode_single_transfer(insn, d); break;
      case 3:
        if (bit(insn, 4))
          decode_undefined(d);
        else
          decode_single_transfer(insn, d);
        break;
      case 4: decode_block_transfer(insn, d); break;
      case 5:  // B, BL
        d.info.kind = InsnClass::branch;
        d.imm = static_cast<uint32_t>(static_cast<int32_t>(insn << 8) >> 6);
        d.handler = &branch;
        break;
      case 6:  // LDC/STC: no coprocessor of the ARM922T has them
        decode_undefined(d);
        break;
      default:
        if (bit(insn, 24)) {
          d.info.kind = InsnClass::exception;
          d.handler = &software_interrupt;
        } else if (bit(insn, 4)) {
          d.info.kind = bit(insn, 20) ? InsnClass::coprocessor_read : InsnClass::coprocessor_write;
          if (!bit(insn, 20)) d.info.reads = static_cast<uint16_t>(1u << d.rd);
          d.handler = &coprocessor_transfer;
        } else {
          decode_undefined(d);  // CDP
        }
        break;
    }
  }

  // Thumb (ARMv4T): most instructions are decoded as the ARM instruction
  // they stand for (r15 then reads as the instruction's address + 4); the
  // branches, the PC- and SP-relative additions and SWI have handlers of
  // their own, which find the halfword in insn.
  // Longer than 150 lines: one switch over the Thumb formats, each case a
  // few lines of field extraction; split, the table would read in pieces.
  static void decode_thumb(uint32_t insn, Decoded& d) {
    const uint32_t rd = bits(insn, 2, 0), rs = bits(insn, 5, 3);
    switch (bits(insn, 15, 11)) {
      case 0x00:
      case 0x01:
      case 0x02:  // LSL, LSR, ASR Rd, Rs, #imm5
        decode_arm(dp(mov, true, 0, rd, (bits(insn, 10, 6) << 7) | (bits(insn, 12, 11) << 5) | rs), d);
        return;
      case 0x03: {  // add, sub Rd, Rs, Rn / #imm3
        const uint32_t operand2 = bit(insn, 10) ? IMMEDIATE | bits(insn, 8, 6) : bits(insn, 8, 6);
        decode_arm(dp(bit(insn, 9) ? sub : add, true, rs, rd, operand2), d);
        return;
      }
      case 0x04:
      case 0x05:
      case 0x06:
      case 0x07: {  // mov, cmp, add, sub Rd, #imm8
        static constexpr uint32_t IMMEDIATE_OPS[] = {mov, cmp, add, sub};
        const uint32_t r = bits(insn, 10, 8);
        decode_arm(dp(IMMEDIATE_OPS[bits(insn, 12, 11)], true, r, bits(insn, 12, 11) == 1 ? 0 : r,
                      IMMEDIATE | bits(insn, 7, 0)),
                   d);
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
              decode_arm(dp(mov, true, 0, rd, shift_by_register_operand(rs, type, rd)), d);
              return;
            }
            case 0x9:  // NEG
              decode_arm(dp(rsb, true, rs, rd, IMMEDIATE), d);
              return;
            case 0xd:  // MUL Rd, Rs: Rd = Rs x Rd
              decode_arm(AL | (1u << 20) | (rd << 16) | (rd << 8) | 0x90u | rs, d);
              return;
            case 0xf:  // MVN
              decode_arm(dp(mvn, true, 0, rd, rs), d);
              return;
            default: {
              static constexpr uint32_t ALU_OPS[] = {and_, eor, 0, 0, 0, adc, sbc, 0, tst, 0, cmp, cmn, orr, 0, bic, 0};
              const bool test_only = op == 0x8 || op == 0xa || op == 0xb;
              decode_arm(dp(ALU_OPS[op], true, rd, test_only ? 0 : rd, rs), d);
              return;
            }
          }
        } else {  // high-register add, cmp, MOV; BX
          const uint32_t hd = rd | (bit(insn, 7) << 3), hs = bits(insn, 6, 3);
          switch (bits(insn, 9, 8)) {
            case 0: decode_arm(dp(add, false, hd, hd, hs), d); return;
            case 1: decode_arm(dp(cmp, true, hd, 0, hs), d); return;
            case 2: decode_arm(dp(mov, false, 0, hd, hs), d); return;
            default: decode_arm(AL | 0x012fff10u | hs, d); return;  // BX, as ARM's
          }
        }
      case 0x09:  // LDR Rd, [PC, #imm8 x 4]: the PC word-aligned
        decode_arm(AL | (1u << 26) | (1u << 24) | (1u << 23) | (1u << 20) | (15u << 16) | (bits(insn, 10, 8) << 12) |
                       (bits(insn, 7, 0) << 2),
                   d);
        d.handler = &thumb_load_literal;
        return;
      case 0x0a:
      case 0x0b: {
        const uint32_t ro = bits(insn, 8, 6);
        if (!bit(insn, 9)) {  // STR, STRB, LDR, LDRB Rd, [Rb, Ro]
          decode_arm(AL | (3u << 25) | (1u << 24) | (1u << 23) | (bit(insn, 10) << 22) | (bit(insn, 11) << 20) |
                         (rs << 16) | (rd << 12) | ro,
                     d);
        } else {                                            // STRH, LDRH, LDRSB, LDRSH Rd, [Rb, Ro]
          static constexpr uint32_t KIND[] = {1, 2, 1, 3};  // H S: 00 STRH, 01 LDRSB, 10 LDRH, 11 LDRSH
          const uint32_t hs = bits(insn, 11, 10);
          decode_arm(AL | (1u << 24) | (1u << 23) | ((hs != 0) ? 1u << 20 : 0) | (rs << 16) | (rd << 12) | 0x90u |
                         (KIND[hs] << 5) | ro,
                     d);
        }
        return;
      }
      case 0x0c:
      case 0x0d:
      case 0x0e:
      case 0x0f: {  // STR, LDR, STRB, LDRB Rd, [Rb, #imm5 (x 4 for words)]
        const bool byte = bit(insn, 12);
        const uint32_t offset = bits(insn, 10, 6) << (byte ? 0 : 2);
        decode_arm(AL | (1u << 26) | (1u << 24) | (1u << 23) | (byte ? 1u << 22 : 0) | (bit(insn, 11) << 20) |
                       (rs << 16) | (rd << 12) | offset,
                   d);
        return;
      }
      case 0x10:
      case 0x11: {  // STRH, LDRH Rd, [Rb, #imm5 x 2]
        const uint32_t offset = bits(insn, 10, 6) << 1;
        decode_arm(AL | (1u << 24) | (1u << 23) | (1u << 22) | (bit(insn, 11) << 20) | (rs << 16) | (rd << 12) |
                       ((offset >> 4) << 8) | 0xb0u | (offset & 15u),
                   d);
        return;
      }
      case 0x12:
      case 0x13:  // STR, LDR Rd, [SP, #imm8 x 4]
        decode_arm(AL | (1u << 26) | (1u << 24) | (1u << 23) | (bit(insn, 11) << 20) | (13u << 16) |
                       (bits(insn, 10, 8) << 12) | (bits(insn, 7, 0) << 2),
                   d);
        return;
      default: break;
    }
    // The instructions done directly.
    d = Decoded{};
    d.insn = insn;
    d.cond = 0xe;
    d.info.executed = true;
    switch (bits(insn, 15, 11)) {
      case 0x14:
      case 0x15:  // add Rd, PC / SP, #imm8 x 4
        d.info.kind = InsnClass::data_processing;
        d.info.reads = bit(insn, 11) ? 1u << 13 : 0;
        d.rn = bit(insn, 11) ? 13 : 15;
        d.rd = static_cast<uint8_t>(bits(insn, 10, 8));
        d.imm = bits(insn, 7, 0) << 2;
        d.handler = &thumb_add_address;
        return;
      case 0x16:
      case 0x17:
        if (bits(insn, 10, 8) == 0) {  // add SP, #+-imm7 x 4
          d.info.kind = InsnClass::data_processing;
          d.info.reads = 1u << 13;
          const uint32_t offset = bits(insn, 6, 0) << 2;
          d.imm = bit(insn, 7) ? 0u - offset : offset;
          d.handler = &thumb_adjust_sp;
        } else if (bits(insn, 10, 9) == 2) {  // PUSH {rlist, LR}, POP {rlist, PC}
          const uint32_t list = bits(insn, 7, 0) | (bit(insn, 8) << (bit(insn, 11) ? 15 : 14));
          if (list == 0)
            decode_undefined(d);
          else
            decode_arm(bit(insn, 11) ? AL | (4u << 25) | (1u << 23) | (1u << 21) | (1u << 20) | (13u << 16) | list
                                     : AL | (4u << 25) | (1u << 24) | (1u << 21) | (13u << 16) | list,
                       d);
        } else {
          decode_undefined(d);
        }
        return;
      case 0x18:
      case 0x19: {  // STMIA, LDMIA Rb!, {rlist}
        const uint32_t rb = bits(insn, 10, 8), list = bits(insn, 7, 0);
        if (list == 0)
          decode_undefined(d);
        else
          decode_arm(AL | (4u << 25) | (1u << 23) | (1u << 21) | (bit(insn, 11) << 20) | (rb << 16) | list, d);
        return;
      }
      case 0x1a:
      case 0x1b: {  // B<cond>, SWI
        const uint32_t cond = bits(insn, 11, 8);
        if (cond == 0xf) {
          d.info.kind = InsnClass::exception;
          d.handler = &software_interrupt;
        } else if (cond == 0xe) {
          decode_undefined(d);
        } else {
          d.info.kind = InsnClass::branch;
          d.imm = 4 + static_cast<uint32_t>(static_cast<int32_t>(insn << 24) >> 23);
          d.handler = &thumb_branch_conditional;
        }
        return;
      }
      case 0x1c:  // B
        d.info.kind = InsnClass::branch;
        d.imm = 4 + static_cast<uint32_t>(static_cast<int32_t>(insn << 21) >> 20);
        d.handler = &thumb_branch;
        return;
      case 0x1e:  // BL, first half
        d.info.kind = InsnClass::data_processing;
        d.imm = 4 + static_cast<uint32_t>(static_cast<int32_t>(insn << 21) >> 9);
        d.handler = &thumb_branch_link_high;
        return;
      case 0x1f:  // BL, second half
        d.info.kind = InsnClass::branch;
        d.info.reads = 1u << 14;
        d.imm = bits(insn, 10, 0) << 1;
        d.handler = &thumb_branch_link_low;
        return;
      default:  // 11101: BLX (ARMv5)
        decode_undefined(d);
        return;
    }
  }
};

ArmCore::Decoded* ArmCore::decoded_page(uint32_t key) {
  auto found = m_pages.find(key);
  if (found == m_pages.end()) {
    if (m_pages.size() >= MAX_PAGES) {
      m_pages.clear();
      m_recent_pages.fill(RecentPage{});
    }
    const bool thumb = key & 1u;
    const size_t count = size_t{1} << (PAGE_BITS - (thumb ? 1 : 2));
    // Every entry starts as the decoding of the word 0, so that the one
    // check of an entry, its word against the fetched one, also catches an
    // entry never decoded.
    Decoded zero{};
    if (thumb)
      Exec::decode_thumb(0, zero);
    else
      Exec::decode_arm(0, zero);
    zero.raw = 0;
    auto entries = std::make_unique<Decoded[]>(count);
    std::fill_n(entries.get(), count, zero);
    found = m_pages.emplace(key, std::move(entries)).first;
  }
  m_recent_pages[key % RECENT_PAGES] = {key, found->second.get()};
  return found->second.get();
}

void ArmCore::decode(Decoded& entry, uint32_t raw, bool thumb) {
  ++m_decodes;
  if (thumb)
    Exec::decode_thumb(raw, entry);
  else
    Exec::decode_arm(raw, entry);
  entry.raw = raw;
}

void ArmCore::take_interrupt(uint32_t pending) {
  m_info = StepInfo{};
  enter(pending & psr::F ? Exception::fiq : Exception::irq, m_pc + 4);
}

void ArmCore::take_prefetch_abort() {
  m_info = StepInfo{};
  enter(Exception::prefetch_abort, m_current + 4);
}

}  // namespace tessera::iss
