// ArmCore: the ARMv4T programmer's model, ARM and Thumb execution, plain C++
// (no SystemC). Memory and CP15 are reached through small ports; timing is
// not here (tlm/host/iss/README.md: the layers).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace tessera::iss {

// Processor modes, the CPSR's M[4:0] values.
enum class Mode : uint8_t {
  usr = 0x10,
  fiq = 0x11,
  irq = 0x12,
  svc = 0x13,
  abt = 0x17,
  und = 0x1b,
  sys = 0x1f,
};

// Exceptions in priority order (highest first, the ARM ARM's table), with
// their vector offsets.
enum class Exception : uint8_t { reset, data_abort, fiq, irq, prefetch_abort, undefined, swi };

namespace psr {
constexpr uint32_t N = 1u << 31, Z = 1u << 30, C = 1u << 29, V = 1u << 28;
constexpr uint32_t I = 1u << 7, F = 1u << 6, T = 1u << 5;
constexpr uint32_t MODE_MASK = 0x1f;
constexpr uint32_t FLAGS = 0xf0000000u;
}  // namespace psr

// Lines of code the memory port lets the core fetch from without calling
// fetch(): the fetches that the port would answer from memory with no time
// and no effect but a count (an instruction-cache hit on a line the cache
// holds, a plain RAM read). The port grants a line after a fetch from it and
// takes it back (revoke) when that stops being true: the whole table when
// the cache's answer may change for any line (the cache invalidated or
// turned off, the memory's direct window withdrawn), one line when the cache
// evicts it. The core revokes them all on every coprocessor write too
// (CP15's c1 and c7), so that a port whose cache operations reach it late
// misses none. The core still compares each word with the decoded one
// (README.md, "The decode cache"), so a store into a line is never missed.
// Direct-mapped by line number: SLOTS lines, the instruction cache's 8 KB,
// so that a loop's branches between lines it holds stay in the core.
struct ResidentLines {
  static constexpr uint32_t BYTES = 32;  // the ARM922T's instruction-cache line
  static constexpr uint32_t NONE = 1;    // line addresses are multiples of 32: bit 0 is free
  static constexpr unsigned SLOTS = 256;
  struct Slot {
    uint32_t line = NONE;           // the line's address, or NONE
    const uint8_t* data = nullptr;  // its bytes, little-endian
  };
  static uint32_t line_of(uint32_t address) { return address & ~(BYTES - 1); }
  // The slot that holds `address`'s line if it is granted.
  Slot& slot(uint32_t address) { return m_slots[(address / BYTES) % SLOTS]; }
  // Grants `line` (a multiple of BYTES) with its bytes; `fetches` is counted
  // once per fetch from any granted line (the cache's hit count): one
  // counter per port.
  void grant(uint32_t line, const uint8_t* data, uint64_t* fetches) {
    Slot& s = slot(line);
    if (s.line == NONE && m_granted_count < m_granted.size()) m_granted[m_granted_count] = &s;
    if (s.line == NONE) ++m_granted_count;
    s = {line, data};
    this->fetches = fetches;
  }
  void revoke(uint32_t line) {
    Slot& s = slot(line);
    if (s.line == line) s.line = NONE;
  }
  // Every line: the slots granted since the last revoke_all (a few, most
  // often), or the whole table once more were.
  void revoke_all() {
    if (m_granted_count <= m_granted.size()) {
      for (unsigned i = 0; i < m_granted_count; ++i) m_granted[i]->line = NONE;
    } else {
      for (Slot& s : m_slots) s.line = NONE;
    }
    m_granted_count = 0;
  }
  uint64_t* fetches = nullptr;

 private:
  std::array<Slot, SLOTS> m_slots{};
  std::array<Slot*, 16> m_granted{};  // the first slots granted since revoke_all
  unsigned m_granted_count = 0;       // slots granted since revoke_all (may pass m_granted's size)
};

// What the core reads and writes. Addresses of 2- and 4-byte accesses are
// aligned by the core (ARMv4 ignores the low bits; a word load rotates).
// false is an abort (the bus answered with an error).
class IssMemory {
 public:
  virtual ~IssMemory() = default;
  virtual bool read(uint32_t address, unsigned bytes, uint32_t& value) = 0;
  virtual bool write(uint32_t address, unsigned bytes, uint32_t value) = 0;
  // Instruction fetch (the I side); by default the same as a read.
  virtual bool fetch(uint32_t address, unsigned bytes, uint32_t& value) { return read(address, bytes, value); }
  // The lines fetches may skip fetch() for (ResidentLines), or nullptr:
  // asked once, when the core is made; the port keeps them up to date.
  virtual ResidentLines* resident_lines() { return nullptr; }
  // The ResidentLines::BYTES bytes of plain memory at `line` (a multiple of
  // 32), to be read directly while they stay where they are, or nullptr:
  // for a port that wraps this one and grants lines.
  virtual const uint8_t* code_line(uint32_t /*line*/) { return nullptr; }
  // LDM and STM: `count` words from `address` up, one access (a port that
  // has bursts makes it one); by default word by word, stopping at the
  // first that fails (the words before it are transferred, as on the core).
  virtual bool read_block(uint32_t address, uint32_t* words, unsigned count) {
    for (unsigned i = 0; i < count; ++i)
      if (!read(address + 4 * i, 4, words[i])) return false;
    return true;
  }
  virtual bool write_block(uint32_t address, const uint32_t* words, unsigned count) {
    for (unsigned i = 0; i < count; ++i)
      if (!write(address + 4 * i, 4, words[i])) return false;
    return true;
  }
};

// The 1, 2 or 4 bytes at `p` as a little-endian value, and back: for ports
// that hold the target's memory as bytes (fixed sizes, so that each is one
// load or store).
inline uint32_t load_little_endian(const uint8_t* p, unsigned bytes) {
  switch (bytes) {
    case 4: return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
    case 2: return uint32_t{p[0]} | uint32_t{p[1]} << 8;
    default: return p[0];
  }
}
inline void store_little_endian(uint8_t* p, unsigned bytes, uint32_t value) {
  switch (bytes) {
    case 4:
      p[3] = static_cast<uint8_t>(value >> 24);
      p[2] = static_cast<uint8_t>(value >> 16);
      [[fallthrough]];
    case 2: p[1] = static_cast<uint8_t>(value >> 8); [[fallthrough]];
    default: p[0] = static_cast<uint8_t>(value);
  }
}

// Coprocessor register transfers (MRC/MCR). false: no such register or not
// allowed; the core takes the undefined-instruction exception.
class Coprocessors {
 public:
  virtual ~Coprocessors() = default;
  virtual bool mrc(unsigned cp, unsigned op1, unsigned crn, unsigned crm, unsigned op2, bool privileged,
                   uint32_t& value) = 0;
  virtual bool mcr(unsigned cp, unsigned op1, unsigned crn, unsigned crm, unsigned op2, bool privileged,
                   uint32_t value) = 0;
};

// The condition field as a table: bit f of CONDITION_PASSES[cond] is set
// when the condition holds for the flags NZCV = f (NV never holds: ARMv4).
constexpr std::array<uint16_t, 16> condition_table() {
  std::array<uint16_t, 16> table{};
  for (unsigned f = 0; f < 16; ++f) {
    const bool n = f & 8u, z = f & 4u, c = f & 2u, v = f & 1u;
    const bool holds[16] = {z,       !z,     c,      !c,           n,           !n,   v,    !v, c && !z,
                            !c || z, n == v, n != v, !z && n == v, z || n != v, true, false};
    for (unsigned cond = 0; cond < 16; ++cond)
      if (holds[cond]) table[cond] = static_cast<uint16_t>(table[cond] | (1u << f));
  }
  return table;
}
inline constexpr std::array<uint16_t, 16> CONDITION_PASSES = condition_table();

// "0x%08x": how the ISS's messages write an address or a PC.
std::string address_text(uint64_t address);

// The faults a launcher without handlers stops at, named for its message:
// "undefined instruction", "prefetch abort (no memory at the PC)", "data
// abort"; nullptr for reset, SWI and interrupts, which go to the vectors.
const char* fault_name(Exception exception);

// An instruction the ISS will not execute (one whose result ARMv4T leaves
// unpredictable, e.g. LDM/STM with no registers): an error naming the
// address, never a silent guess.
class IssError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A fault that a launcher without handlers stops the program at (one
// fault_name names), thrown from the core's exception hook: which exception
// it was, so that a debugger shows the stop with the matching signal.
class ProgramFault : public IssError {
 public:
  ProgramFault(Exception exception, const std::string& what) : IssError(what), m_exception(exception) {}
  Exception exception() const { return m_exception; }

 private:
  Exception m_exception;
};

// What the last step executed, for the timing layer (Arm922tTiming): the
// instruction's class and the operands its cycle count depends on. Thumb
// instructions report the ARM instruction they are executed as.
enum class InsnClass : uint8_t {
  none,               // no instruction: an interrupt taken or a failed fetch
  data_processing,    // ALU operations, Thumb's address additions, BL's first half
  multiply,           // MUL, MLA
  multiply_long,      // UMULL, UMLAL, SMULL, SMLAL
  load,               // LDR, LDRB, LDRH, LDRSB, LDRSH
  store,              // STR, STRB, STRH
  load_multiple,      // LDM, POP
  store_multiple,     // STM, PUSH
  swap,               // SWP, SWPB
  branch,             // B, BL, BX, Thumb's B<cond>, B and BL's second half
  status_read,        // MRS
  status_write,       // MSR
  coprocessor_read,   // MRC
  coprocessor_write,  // MCR
  exception,          // SWI, an undefined instruction (CDP, LDC/STC included)
};

struct StepInfo {
  InsnClass kind = InsnClass::none;
  bool executed = false;         // false: the condition failed
  bool pc_written = false;       // the instruction wrote the PC (a branch, a load or an ALU result)
  bool exception = false;        // an exception was entered (SWI, undefined, abort, interrupt)
  bool register_shift = false;   // data processing with a shift by a register
  bool narrow_load = false;      // a byte, halfword or unaligned word was loaded (rotated in Write)
  bool accumulate = false;       // MLA, UMLAL, SMLAL
  bool signed_multiply = false;  // SMULL, SMLAL (and MUL/MLA: the multiplier's sign counts)
  bool control_write = false;    // MSR wrote the CPSR's control field (mode, I, F)
  uint8_t registers = 0;         // LDM/STM: the number of registers in the list
  int8_t loaded = -1;            // the register a load wrote last (for load-use interlocks); -1: none
  uint16_t reads = 0;            // registers read (bit n: rn)
  uint32_t multiplier = 0;       // the multiplier operand (Rs) for early termination
};

class ArmCore {
 public:
  // coprocessors may be null: every MRC/MCR is then undefined.
  ArmCore(IssMemory& memory, Coprocessors* coprocessors = nullptr);

  // The coprocessors may need the core (CP15 sets the vectors): attach them after.
  void set_coprocessors(Coprocessors* coprocessors) { m_coprocessors = coprocessors; }

  // Reset: supervisor mode, ARM state, IRQ and FIQ masked, PC at the reset
  // vector (0, or 0xffff0000 with high vectors).
  void reset();

  // Executes one instruction, or enters a pending interrupt's handler.
  // Always inline (below): a run loop's body, where the compiler keeps the
  // core's state in registers across the step and what the caller does with
  // its StepInfo (the timing layer's step); GCC left it a call in the SoC
  // launcher's loop.
  __attribute__((always_inline)) inline void step();

  // Executes instructions, each exactly as step() does, calling `after()`
  // (the caller's timing, interrupt lines and checks: anything but a step
  // of this core) after each one, until it returns false. The instructions
  // of a block (README.md, "Blocks"), a straight run within one resident
  // line, go on from the decoded entry of the one before: no fetch call, no
  // decode-cache look-up, no return to the caller's loop between them.
  template <class After>
  __attribute__((always_inline)) inline void run(After&& after);

  // Registers as the current mode sees them; r15 is the address of the
  // next instruction to execute (not the +8 an instruction reads).
  uint32_t reg(unsigned n) const { return n == 15 ? m_pc : m_r[n]; }
  void set_reg(unsigned n, uint32_t value);
  uint32_t cpsr() const { return m_cpsr; }
  void set_cpsr(uint32_t value);  // switches the register bank with the mode
  // The current mode's SPSR (none in user and system modes: 0, and a write is ignored).
  uint32_t spsr() const;
  void set_spsr(uint32_t value);
  // A banked register of a given mode, e.g. (Mode::irq, 13).
  uint32_t banked(Mode mode, unsigned n) const;

  Mode mode() const { return static_cast<Mode>(m_cpsr & psr::MODE_MASK); }
  bool thumb() const { return (m_cpsr & psr::T) != 0; }

  // Interrupt inputs (level-sensitive, taken before the next instruction
  // when not masked).
  void set_irq(bool level) { m_interrupt_lines = (m_interrupt_lines & ~psr::I) | (level ? psr::I : 0); }
  void set_fiq(bool level) { m_interrupt_lines = (m_interrupt_lines & ~psr::F) | (level ? psr::F : 0); }
  // Called on every exception entry, before the core changes mode, with the
  // address of the instruction that caused it (for interrupts: the next
  // one). A launcher that has no handlers to vector to throws from it.
  using ExceptionHook = std::function<void(Exception exception, uint32_t pc)>;
  void on_exception(ExceptionHook hook) { m_exception_hook = std::move(hook); }

  // Called when a SWI is about to be taken, with its address; true: the
  // call was served outside the program (semihosting), so the core goes on
  // with the next instruction instead of entering the SWI vector.
  using SwiHook = std::function<bool(uint32_t pc)>;
  void on_swi(SwiHook hook) { m_swi_hook = std::move(hook); }

  // Exception vectors at 0xffff0000 (CP15 control bit V).
  void set_high_vectors(bool high) { m_high_vectors = high; }

  uint64_t instructions() const { return m_instructions; }
  // Instructions decoded: once per address and state, again when the word
  // there changed (a word 0 comes decoded; README.md, "The decode cache").
  uint64_t decodes() const { return m_decodes; }
  // What the last step() executed (the timing layer's input).
  const StepInfo& last_step() const { return m_info; }

 private:
  // The decode cache (README.md, "The decode cache"): every instruction is
  // decoded once per address and state into a Decoded entry, the handler
  // that executes it with its fields extracted and the static part of its
  // StepInfo; the word it was decoded from is kept, and an entry whose word
  // differs from what the fetch returned is decoded again, so a store into
  // code (by the program, a debugger or a DMA) is never missed.
  struct Decoded;
  using Handler = void (*)(ArmCore& core, const Decoded& insn);
  struct Decoded {
    Handler handler;
    uint32_t raw;   // the fetched word (ARM) or halfword (Thumb) this entry was decoded from
    uint32_t insn;  // the ARM encoding executed (Thumb: the one it stands for, or the halfword itself)
    uint32_t imm;   // operand 2's immediate, a signed load/store offset, a branch displacement
    uint8_t cond;   // condition field (Thumb: AL, B<cond> tests its own)
    uint8_t rd, rn, rm, rs;
    uint8_t shift_type, shift_amount;  // an immediate shift, or the immediate's rotation
    bool up;                           // a register offset is added (else subtracted)
    StepInfo info;                     // what the step reports, but for the operand-dependent fields
  };
  struct Exec;  // the handlers (arm_core.cpp)
  friend struct Exec;
  // Decoded entries per page of code and state; the pages are found through
  // a small direct-mapped table of recent ones.
  static constexpr unsigned PAGE_BITS = 12;
  static constexpr unsigned RECENT_PAGES = 64;
  static constexpr size_t MAX_PAGES = 256;  // beyond: all dropped (a program running from all of memory)
  struct RecentPage {
    uint32_t key = ~0u;  // page number << 1 | Thumb
    Decoded* entries = nullptr;
  };
  // Always inline: the step's hot path (GCC left it a call in ArmCore::run).
  __attribute__((always_inline)) inline Decoded& decoded(uint32_t address, uint32_t raw, bool thumb);
  // The fetched instruction `insn` at m_current, executed (step() after its fetch and look-up).
  __attribute__((always_inline)) inline void execute(const Decoded& insn, bool thumb);
  Decoded* decoded_page(uint32_t key);
  void decode(Decoded& entry, uint32_t raw, bool thumb);  // an entry made or remade: out of the hot path
  void take_interrupt(uint32_t pending);
  void take_prefetch_abort();

  static unsigned bank_of(Mode mode);
  void switch_bank(unsigned from, unsigned to);
  void enter(Exception exception, uint32_t return_address);

  void write_pc(uint32_t address) {
    m_pc = address;
    m_branched = true;
  }
  void write_reg(unsigned n, uint32_t value) {
    if (n == 15)
      write_pc(value & ~3u);
    else
      m_r[n] = value;
  }
  bool condition(uint32_t cond) const { return (CONDITION_PASSES[cond] >> (m_cpsr >> 28)) & 1u; }
  void undefined();
  // Throws IssError if a branch to itself can never be left (IRQ and FIQ masked).
  void check_progress() const;
  [[noreturn]] void unpredictable(const std::string& what) const;

  IssMemory& m_memory;
  ResidentLines* m_resident;  // the port's, or null: asked once
  Coprocessors* m_coprocessors;
  std::array<uint32_t, 16> m_r{};  // the current mode's view; m_r[15] = instruction + 8 while executing
  uint32_t m_pc = 0;               // the next instruction's address
  uint32_t m_cpsr = 0;
  uint32_t m_current = 0;  // address of the executing instruction
  bool m_branched = false;
  // Banked copies: r13/r14 per bank (usr/sys, fiq, irq, svc, abt, und),
  // r8..r12 for user and FIQ, SPSR per exception mode.
  std::array<std::array<uint32_t, 2>, 6> m_r13_14{};
  std::array<uint32_t, 5> m_user_r8_12{};
  std::array<uint32_t, 5> m_fiq_r8_12{};
  std::array<uint32_t, 6> m_spsr{};
  uint32_t m_interrupt_lines = 0;  // psr::I while the IRQ line is high, psr::F for FIQ: masked by the CPSR's bits
  bool m_high_vectors = false;
  uint64_t m_instructions = 0;
  uint64_t m_decodes = 0;
  StepInfo m_info;
  ExceptionHook m_exception_hook;
  SwiHook m_swi_hook;
  std::array<RecentPage, RECENT_PAGES> m_recent_pages{};
  std::unordered_map<uint32_t, std::unique_ptr<Decoded[]>> m_pages;
};

inline ArmCore::Decoded& ArmCore::decoded(uint32_t address, uint32_t raw, bool thumb) {
  const uint32_t key = (address >> PAGE_BITS) << 1 | (thumb ? 1u : 0u);
  const RecentPage& recent = m_recent_pages[key % RECENT_PAGES];
  Decoded* page = recent.key == key ? recent.entries : decoded_page(key);
  Decoded& entry = page[(address & ((1u << PAGE_BITS) - 1)) >> (thumb ? 1 : 2)];
  if (__builtin_expect(entry.raw != raw, 0)) decode(entry, raw, thumb);
  return entry;
}

inline void ArmCore::step() {
  // Interrupts are sampled between instructions, FIQ first; the handler
  // returns with SUBS pc, lr, #4 to the instruction that would have run.
  if (const uint32_t pending = m_interrupt_lines & ~m_cpsr) {
    take_interrupt(pending);
    return;
  }
  m_current = m_pc;
  m_branched = false;
  const bool thumb = (m_cpsr & psr::T) != 0;
  uint32_t raw = 0;
  const ResidentLines::Slot* slot = m_resident != nullptr ? &m_resident->slot(m_current) : nullptr;
  if (slot != nullptr && ResidentLines::line_of(m_current) == slot->line) {
    // What fetch() would do, without the call (ResidentLines).
    const uint8_t* bytes = slot->data + (m_current & (ResidentLines::BYTES - 1));
    raw = thumb ? load_little_endian(bytes, 2) : load_little_endian(bytes, 4);
    ++*m_resident->fetches;
  } else if (!m_memory.fetch(m_current, thumb ? 2 : 4, raw)) {
    take_prefetch_abort();
    return;
  }
  ++m_instructions;
  execute(decoded(m_current, raw, thumb), thumb);
}

inline void ArmCore::execute(const Decoded& insn, bool thumb) {
  m_r[15] = m_current + (thumb ? 4 : 8);
  if (condition(insn.cond)) {
    m_info = insn.info;
    insn.handler(*this, insn);
  } else {
    m_info = StepInfo{};  // executed: false
  }
  if (!m_branched) m_pc = m_current + (thumb ? 2 : 4);
  m_info.pc_written = m_branched && !m_info.exception;
}

template <class After>
inline void ArmCore::run(After&& after) {
  constexpr uint32_t LINE_MASK = ~(ResidentLines::BYTES - 1);
  for (;;) {
    // A block's first instruction: step(), with the entry it executed kept.
    if (const uint32_t pending = m_interrupt_lines & ~m_cpsr) {
      take_interrupt(pending);
      if (!after()) return;
      continue;
    }
    m_current = m_pc;
    m_branched = false;
    const bool thumb = (m_cpsr & psr::T) != 0;
    uint32_t raw = 0;
    const uint32_t line = m_current & LINE_MASK;
    const ResidentLines::Slot* slot = m_resident != nullptr ? &m_resident->slot(line) : nullptr;
    if (slot != nullptr && line == slot->line) {
      const uint8_t* bytes = slot->data + (m_current & ~LINE_MASK);
      raw = thumb ? load_little_endian(bytes, 2) : load_little_endian(bytes, 4);
      ++*m_resident->fetches;
    } else if (!m_memory.fetch(m_current, thumb ? 2 : 4, raw)) {
      take_prefetch_abort();
      if (!after()) return;
      continue;
    }
    ++m_instructions;
    Decoded* insn = &decoded(m_current, raw, thumb);
    for (;;) {
      execute(*insn, thumb);
      if (!after()) return;
      // The block goes on while step() would fetch the next instruction
      // from the same resident line in the same state, and take no
      // interrupt first: its entry is then the next one of the same page
      // (a line never crosses a page), which no look-up since has dropped
      // (only decoded() drops pages). Without a branch the state is the
      // same: only BX, exceptions and writes of the PC change T. The
      // line's slot is the same whether the fetch above granted it or not.
      if (m_branched || (m_pc & LINE_MASK) != line || (m_interrupt_lines & ~m_cpsr) != 0 || slot == nullptr ||
          slot->line != line)
        break;
      m_current = m_pc;
      const uint8_t* bytes = slot->data + (m_current & ~LINE_MASK);
      raw = thumb ? load_little_endian(bytes, 2) : load_little_endian(bytes, 4);
      ++*m_resident->fetches;
      ++m_instructions;
      ++insn;
      if (__builtin_expect(insn->raw != raw, 0)) decode(*insn, raw, thumb);
    }
  }
}

}  // namespace tessera::iss
