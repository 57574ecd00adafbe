// The ISS against an independent ARM emulator (Unicorn, QEMU's TI925T: an
// ARMv4T core), one random instruction at a time from random register and
// memory states: after each, every register, the flags, the mode and the
// data memory must agree. Encodings whose result the architecture leaves
// unpredictable, or implementation-defined where the ARM9TDMI and QEMU
// differ (a stored r15, the base in an STM list), are not generated; they
// have their own tests in test_iss.cpp.
#include <unicorn/unicorn.h>

#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "host/iss/arm_core.h"

namespace {

using tessera::iss::ArmCore;
using tessera::iss::IssMemory;

constexpr uint32_t MEMORY_BYTES = 0x10000;
constexpr uint32_t CODE = 0x1000;  // the one instruction of each trial
constexpr uint32_t DATA = 0x8000;  // loads and stores land in [DATA, DATA + DATA_BYTES)
constexpr uint32_t DATA_BYTES = 0x4000;

class FlatMemory : public IssMemory {
 public:
  std::vector<uint8_t> bytes = std::vector<uint8_t>(MEMORY_BYTES);
  bool read(uint32_t address, unsigned size, uint32_t& value) override {
    if (address + size > bytes.size()) return false;
    value = 0;
    for (unsigned i = 0; i < size; ++i) value |= uint32_t{bytes[address + i]} << (8 * i);
    return true;
  }
  uint64_t writes = 0;
  bool write(uint32_t address, unsigned size, uint32_t value) override {
    ++writes;
    if (address + size > bytes.size()) return false;
    for (unsigned i = 0; i < size; ++i) bytes[address + i] = static_cast<uint8_t>(value >> (8 * i));
    return true;
  }
};

// usr, then the privileged modes.
const uint32_t MODES[7] = {0x10, 0x11, 0x12, 0x13, 0x17, 0x1b, 0x1f};

const int UNICORN_REGS[16] = {UC_ARM_REG_R0,  UC_ARM_REG_R1, UC_ARM_REG_R2,  UC_ARM_REG_R3,
                              UC_ARM_REG_R4,  UC_ARM_REG_R5, UC_ARM_REG_R6,  UC_ARM_REG_R7,
                              UC_ARM_REG_R8,  UC_ARM_REG_R9, UC_ARM_REG_R10, UC_ARM_REG_R11,
                              UC_ARM_REG_R12, UC_ARM_REG_SP, UC_ARM_REG_LR,  UC_ARM_REG_PC};

// Random encodings of the ARM-state instruction classes, within the
// architecture's defined behaviour.
class Generator {
 public:
  explicit Generator(uint32_t seed) : m_rng(seed) {}

  uint32_t any(uint32_t n) { return std::uniform_int_distribution<uint32_t>(0, n - 1)(m_rng); }
  uint32_t word() { return static_cast<uint32_t>(m_rng()); }
  uint32_t cond() { return any(4) == 0 ? any(15) : 0xe; }  // not NV
  unsigned reg_not_pc() { return any(15); }

  // A register a memory instruction uses as its base, set to an address
  // in the data window with room for offset bytes either side.
  unsigned base(std::vector<std::pair<unsigned, uint32_t>>& setup, uint32_t room, uint32_t align) {
    const unsigned rn = reg_not_pc();
    const uint32_t address = DATA + room + any(DATA_BYTES - 2 * room);
    setup.emplace_back(rn, address & ~(align - 1));
    return rn;
  }

  uint32_t shifter_operand(bool allow_pc) {
    switch (any(3)) {
      case 0: return (1u << 25) | (any(16) << 8) | any(256);
      case 1: {
        const unsigned rm = allow_pc ? any(16) : reg_not_pc();
        return (any(32) << 7) | (any(4) << 5) | rm;
      }
      default:  // shift by register: no r15 operands
        return (reg_not_pc() << 8) | (any(4) << 5) | (1u << 4) | reg_not_pc();
    }
  }

  uint32_t data_processing() {
    const uint32_t opcode = any(16);
    const bool test_only = opcode >= 8 && opcode <= 11;
    const uint32_t s = test_only ? 1 : any(2);
    const uint32_t op2 = shifter_operand(true);
    const bool register_shift = !(op2 & (1u << 25)) && (op2 & (1u << 4));
    const bool move = opcode == 13 || opcode == 15;  // MOV, MVN: Rn should be zero
    const unsigned rn = move ? 0 : register_shift ? reg_not_pc() : any(16);
    const unsigned rd = test_only ? 0 : reg_not_pc();  // TST..CMN: Rd should be zero
    return (cond() << 28) | op2 | (opcode << 21) | (s << 20) | (rn << 16) | (rd << 12);
  }

  uint32_t multiply() {
    const unsigned rm = reg_not_pc();
    unsigned rd = reg_not_pc();
    while (rd == rm) rd = reg_not_pc();
    const uint32_t accumulate = any(2);  // MUL's Rn should be zero
    return (cond() << 28) | (accumulate << 21) | (any(2) << 20) | (rd << 16) | ((accumulate ? reg_not_pc() : 0) << 12) |
           (reg_not_pc() << 8) | 0x90u | rm;
  }

  uint32_t multiply_long() {
    unsigned hi = reg_not_pc(), lo = reg_not_pc(), rm = reg_not_pc();
    while (lo == hi) lo = reg_not_pc();
    while (rm == hi || rm == lo) rm = reg_not_pc();
    return (cond() << 28) | 0x00800090u | (any(4) << 20) | (hi << 16) | (lo << 12) | (reg_not_pc() << 8) | rm;
  }

  uint32_t single_transfer(std::vector<std::pair<unsigned, uint32_t>>& setup) {
    const uint32_t byte = any(2), load = any(2), pre = any(2), writeback = pre ? any(2) : 0;
    // Words aligned: an unaligned word load rotates on ARMv4, while QEMU's
    // TI925T reads the four bytes at the address (test_iss.cpp checks the rotation).
    const unsigned rn = base(setup, 0x1000, byte ? 1 : 4);
    unsigned rd = reg_not_pc();
    while ((writeback || !pre) && rd == rn) rd = reg_not_pc();
    uint32_t offset;
    if (any(2) == 0) {
      offset = any(0x1000) & (byte ? ~0u : ~3u);
    } else {  // Rm, shifted by a small amount, Rm set to a small value
      unsigned rm = reg_not_pc();
      while (rm == rn) rm = reg_not_pc();
      setup.emplace_back(rm, any(64) * (byte ? 1 : 4));
      offset = (1u << 25) | (any(3) << 7) | rm;  // LSL #0..2
      if (rm == rd && !load) setup.back().second &= ~3u;
    }
    return (cond() << 28) | (1u << 26) | offset | (pre << 24) | (any(2) << 23) | (byte << 22) | (writeback << 21) |
           (load << 20) | (rn << 16) | (rd << 12);
  }

  uint32_t halfword_transfer(std::vector<std::pair<unsigned, uint32_t>>& setup) {
    const uint32_t load = any(2), kind = load ? 1 + any(3) : 1;  // STRH, LDRH, LDRSB, LDRSH
    const uint32_t pre = any(2), writeback = pre ? any(2) : 0;
    const unsigned rn = base(setup, 0x100, 2);
    unsigned rd = reg_not_pc();
    while ((writeback || !pre) && rd == rn) rd = reg_not_pc();
    uint32_t offset;
    if (any(2) == 0) {
      const uint32_t value = any(256) & ~1u;
      offset = (1u << 22) | ((value >> 4) << 8) | (value & 15);
    } else {
      unsigned rm = reg_not_pc();
      while (rm == rn || rm == rd) rm = reg_not_pc();
      setup.emplace_back(rm, any(128) & ~1u);
      offset = rm;
    }
    return (cond() << 28) | offset | (pre << 24) | (any(2) << 23) | (writeback << 21) | (load << 20) | (rn << 16) |
           (rd << 12) | 0x90u | (kind << 5);
  }

  uint32_t block_transfer(std::vector<std::pair<unsigned, uint32_t>>& setup) {
    const uint32_t load = any(2), writeback = any(2);
    const unsigned rn = base(setup, 0x100, 4);
    uint32_t list = 0;
    while (list == 0) {
      list = any(0x8000);                  // r0..r14: no PC
      if (writeback) list &= ~(1u << rn);  // the base in the list with write-back: unpredictable
      if (!load) list &= ~(1u << rn);      // a stored base is implementation-defined
    }
    return (cond() << 28) | (4u << 25) | (any(2) << 24) | (any(2) << 23) | (writeback << 21) | (load << 20) |
           (rn << 16) | list;
  }

  uint32_t swap(std::vector<std::pair<unsigned, uint32_t>>& setup) {
    const uint32_t byte = any(2);
    const unsigned rn = base(setup, 4, byte ? 1 : 4);
    unsigned rd = reg_not_pc(), rm = reg_not_pc();
    while (rd == rn) rd = reg_not_pc();
    while (rm == rn) rm = reg_not_pc();
    return (cond() << 28) | 0x01000090u | (byte << 22) | (rn << 16) | (rd << 12) | rm;
  }

  // B, BL to a target in mapped memory (Unicorn fetches there before it stops),
  // never to itself (with I and F set the ISS stops that as a hung program: test_iss).
  uint32_t branch() {
    int32_t words = static_cast<int32_t>(any(0x3000)) - 0x400;  // 0x1008 + 4 x words >= 8
    if (words == -2) words = -1;
    return (cond() << 28) | (5u << 25) | (any(2) << 24) | (static_cast<uint32_t>(words) & 0xffffffu);
  }

  uint32_t status() {
    if (any(2) == 0) return (cond() << 28) | 0x010f0000u | (reg_not_pc() << 12);  // MRS Rd, CPSR
    switch (any(3)) {
      case 0:  // MSR CPSR_f, #imm
        return (cond() << 28) | 0x0328f000u | (any(16) << 8) | any(256);
      case 1:  // MSR CPSR_f, Rm
        return (cond() << 28) | 0x0128f000u | reg_not_pc();
      default: {  // MSR CPSR_c / CPSR_fc, #imm: a privileged mode, I and F (the T bit kept)
        const uint32_t value = MODES[1 + any(6)] | (any(4) << 6);
        return (cond() << 28) | 0x0321f000u | (any(2) << 19) | value;
      }
    }
  }

  uint32_t instruction(std::vector<std::pair<unsigned, uint32_t>>& setup) {
    switch (any(10)) {
      case 0:
      case 1:
      case 2: return data_processing();
      case 3: return any(2) ? multiply() : multiply_long();
      case 4: return single_transfer(setup);
      case 5: return halfword_transfer(setup);
      case 6: return block_transfer(setup);
      case 7: return swap(setup);
      case 8: return branch();
      default: return status();
    }
  }

  // Thumb (ARMv4T), every format but SWI and BX (tested by hand): low
  // registers at random, bases in the data window, branch targets mapped.
  unsigned low() { return any(8); }
  unsigned low_base(std::vector<std::pair<unsigned, uint32_t>>& setup, uint32_t align) {
    const unsigned rb = low();
    setup.emplace_back(rb, (DATA + 0x100 + any(DATA_BYTES - 0x200)) & ~(align - 1));
    return rb;
  }
  unsigned other_low(unsigned not_this) {
    unsigned r = low();
    while (r == not_this) r = low();
    return r;
  }

  uint32_t thumb_instruction(std::vector<std::pair<unsigned, uint32_t>>& setup) {
    switch (any(19)) {
      case 0:  // LSL, LSR, ASR #imm5
        return (any(3) << 11) | (any(32) << 6) | (low() << 3) | low();
      case 1:  // ADD, SUB register / #imm3
        return 0x1800u | (any(4) << 9) | (any(8) << 6) | (low() << 3) | low();
      case 2:  // MOV, CMP, ADD, SUB #imm8
        return 0x2000u | (any(4) << 11) | (low() << 8) | any(256);
      case 3:  // ALU operations
        return 0x4000u | (any(16) << 6) | (low() << 3) | low();
      case 4: {  // ADD, CMP, MOV with a high register; never into the PC
        unsigned hd = any(15), hs = any(16);
        while (hd < 8 && hs < 8) hs = 8 + any(8);
        return 0x4400u | (any(3) << 8) | ((hd >> 3) << 7) | (hs << 3) | (hd & 7);
      }
      case 5:  // LDR Rd, [PC, #imm8 x 4]
        return 0x4800u | (low() << 8) | any(256);
      case 6: {  // STR, STRB, LDR, LDRB Rd, [Rb, Ro]
        const uint32_t lb = any(4);
        const unsigned rb = low_base(setup, lb & 1 ? 1 : 4), ro = other_low(rb);
        setup.emplace_back(ro, any(64) * (lb & 1 ? 1 : 4));
        return 0x5000u | (lb << 10) | (ro << 6) | (rb << 3) | low();
      }
      case 7: {  // STRH, LDRSB, LDRH, LDRSH Rd, [Rb, Ro]
        const uint32_t hs = any(4);
        const unsigned rb = low_base(setup, 2), ro = other_low(rb);
        setup.emplace_back(ro, any(64) * 2);
        return 0x5200u | (hs << 10) | (ro << 6) | (rb << 3) | low();
      }
      case 8: {  // STR, LDR, STRB, LDRB Rd, [Rb, #imm5]
        const uint32_t bl = any(4);
        return 0x6000u | (bl << 11) | (any(32) << 6) | (low_base(setup, bl & 2 ? 1 : 4) << 3) | low();
      }
      case 9:  // STRH, LDRH Rd, [Rb, #imm5 x 2]
        return 0x8000u | (any(2) << 11) | (any(32) << 6) | (low_base(setup, 2) << 3) | low();
      case 10:  // STR, LDR Rd, [SP, #imm8 x 4]
        setup.emplace_back(13, (DATA + any(DATA_BYTES - 0x400)) & ~3u);
        return 0x9000u | (any(2) << 11) | (low() << 8) | any(256);
      case 11:  // ADD Rd, PC / SP, #imm8 x 4
        return 0xa000u | (any(2) << 11) | (low() << 8) | any(256);
      case 12:  // ADD SP, #+-imm7 x 4
        return 0xb000u | any(256);
      case 13: {  // PUSH {rlist, LR}, POP {rlist} (POP {PC} by hand)
        setup.emplace_back(13, (DATA + 0x100 + any(DATA_BYTES - 0x200)) & ~3u);
        const uint32_t pop = any(2), extra = pop ? 0 : any(2);
        uint32_t list = any(256);
        if (list == 0 && !extra) list = 1u << low();
        return 0xb400u | (pop << 11) | (extra << 8) | list;
      }
      case 14: {  // STMIA, LDMIA Rb!, {rlist without Rb}
        const unsigned rb = low_base(setup, 4);
        uint32_t list = any(256) & ~(1u << rb);
        if (list == 0) list = 1u << other_low(rb);
        return 0xc000u | (any(2) << 11) | (rb << 8) | list;
      }
      case 15: {  // B<cond>, conditions EQ..LE, not to itself (offset -2 halfwords: see branch())
        const uint32_t offset = any(255);
        return 0xd000u | (any(14) << 8) | (offset == 0xfe ? 0xffu : offset);
      }
      case 16: {  // B, not to itself
        const uint32_t offset = any(2047);
        return 0xe000u | (offset == 0x7fe ? 0x7ffu : offset);
      }
      case 17: {  // BL, both halves (Unicorn runs them as one instruction): a target in the code area
        const uint32_t offset = any(0x800);  // halfwords from CODE + 4
        return (0xf000u) | ((0xf800u | offset) << 16);
      }
      default:                                          // BL, second half, from an LR in the code area
        setup.emplace_back(14, CODE + 2 * any(0x400));  // even, as a first half leaves it
        return 0xf800u | any(1024);
    }
  }

 private:
  std::mt19937 m_rng;
};

class Lockstep : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(uc_open(UC_ARCH_ARM, UC_MODE_ARM, &uc_), UC_ERR_OK);
    ASSERT_EQ(uc_ctl_set_cpu_model(uc_, UC_CPU_ARM_TI925T), UC_ERR_OK);
    ASSERT_EQ(uc_mem_map(uc_, 0, MEMORY_BYTES, UC_PROT_ALL), UC_ERR_OK);
  }
  void TearDown() override { uc_close(uc_); }
  void run(bool thumb, uint32_t seed, int trials);

  uint32_t uc_reg(int id) {
    uint32_t value = 0;
    uc_reg_read(uc_, id, &value);
    return value;
  }

  uc_engine* uc_ = nullptr;
};

std::string hex(uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", value);
  return text;
}

void Lockstep::run(bool thumb, uint32_t seed, int trials) {
  FlatMemory memory;
  ArmCore core(memory);
  Generator gen(seed);
  int executed = 0, memory_compares = 0;
  uint64_t their_writes = 0;
  uc_hook hook{};
  uc_hook_add(uc_, &hook, UC_HOOK_MEM_WRITE,
              reinterpret_cast<void*>(+[](uc_engine*, uc_mem_type, uint64_t, int, int64_t, void* count) {
                ++*static_cast<uint64_t*>(count);
              }),
              &their_writes, 1, 0);
  for (int trial = 0; trial < trials; ++trial) {
    // Every 64 trials: random data memory and every mode's banked
    // registers, the same in both.
    if (trial % 64 == 0) {
      for (uint32_t a = DATA; a < DATA + DATA_BYTES; a += 4) memory.write(a, 4, gen.word());
      uc_mem_write(uc_, DATA, memory.bytes.data() + DATA, DATA_BYTES);
      for (const uint32_t mode : MODES) {
        core.set_cpsr(mode | 0xc0u);
        const uint32_t cpsr = core.cpsr();
        uc_reg_write(uc_, UC_ARM_REG_CPSR, &cpsr);
        for (unsigned n = mode == 0x11 ? 8 : 13; n < 15; ++n) {
          const uint32_t value = gen.word();
          core.set_reg(n, value);
          uc_reg_write(uc_, UNICORN_REGS[n], &value);
        }
      }
    }
    std::vector<std::pair<unsigned, uint32_t>> setup;
    const uint32_t insn = thumb ? gen.thumb_instruction(setup) : gen.instruction(setup);
    uint32_t regs[15];
    for (auto& value : regs)
      value = gen.any(4) == 0 ? gen.any(40) : gen.word();  // small values: shifts past 32 and zero results
    for (const auto& [n, value] : setup) regs[n] = value;
    // Any mode, the flags at random, interrupts masked.
    const uint32_t cpsr = (gen.word() & 0xf0000000u) | 0xc0u | MODES[gen.any(7)] | (thumb ? 0x20u : 0);
    memory.write(CODE, 4, insn);
    core.set_cpsr(cpsr);
    for (unsigned n = 0; n < 15; ++n) core.set_reg(n, regs[n]);
    core.set_reg(15, CODE);

    uc_mem_write(uc_, CODE, memory.bytes.data() + CODE, 4);
    uc_reg_write(uc_, UC_ARM_REG_CPSR, &cpsr);
    for (unsigned n = 0; n < 15; ++n) uc_reg_write(uc_, UNICORN_REGS[n], &regs[n]);
    uint32_t pc = CODE;
    uc_reg_write(uc_, UC_ARM_REG_PC, &pc);

    const uint64_t our_writes = memory.writes, their_writes_before = their_writes;
    core.step();
    if (thumb && (insn & 0xf800u) == 0xf000u) core.step();  // the BL's second half
    const uc_err err = uc_emu_start(uc_, CODE | (thumb ? 1 : 0), CODE + (thumb ? 2 : 4), 0, 1);
    ASSERT_EQ(err, UC_ERR_OK) << "Unicorn: " << uc_strerror(err) << " on " << hex(insn);

    std::string diff;
    for (unsigned n = 0; n < 16; ++n) {
      const uint32_t theirs = uc_reg(UNICORN_REGS[n]);
      if (core.reg(n) != theirs) diff += " r" + std::to_string(n) + ": " + hex(core.reg(n)) + " vs " + hex(theirs);
    }
    const uint32_t their_cpsr = uc_reg(UC_ARM_REG_CPSR);
    if ((core.cpsr() & 0xf00000ffu) != (their_cpsr & 0xf00000ffu))
      diff += " cpsr: " + hex(core.cpsr()) + " vs " + hex(their_cpsr);
    if (memory.writes != our_writes || their_writes != their_writes_before) {  // either stored: compare
      std::vector<uint8_t> theirs(DATA_BYTES);
      uc_mem_read(uc_, DATA, theirs.data(), DATA_BYTES);
      if (std::memcmp(theirs.data(), memory.bytes.data() + DATA, DATA_BYTES) != 0) diff += " data memory differs";
      ++memory_compares;
    }
    ASSERT_TRUE(diff.empty()) << "trial " << trial << ", " << hex(insn) << " from cpsr " << hex(cpsr) << ":" << diff;
    ++executed;
  }
  EXPECT_EQ(executed, trials);
  EXPECT_GT(memory_compares, trials / 20);  // the stores were there to compare
  uc_hook_del(uc_, hook);
}

TEST_F(Lockstep, RandomArmInstructionsAgreeWithAnIndependentEmulator) {
  run(false, 20261124, 500000);
}

TEST_F(Lockstep, RandomThumbInstructionsAgreeWithAnIndependentEmulator) {
  run(true, 20261125, 500000);
}

}  // namespace
