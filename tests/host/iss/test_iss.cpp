// The ISS's modes, banked registers, exceptions and the ARMv4/ARM9TDMI
// behaviours the lock-step test leaves out (test_iss_lockstep.cpp), on
// hand-encoded instructions with their assembly beside them; expected
// values worked out from the ARM Architecture Reference Manual (ARMv4T).
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/iss/arm922t_timing.h"
#include "host/iss/arm_core.h"
#include "host/iss/cp15.h"

namespace {

using tessera::iss::Arm922tTiming;
using tessera::iss::ArmCore;
using tessera::iss::CacheMaintenance;
using tessera::iss::Coprocessors;
using tessera::iss::Cp15;
using tessera::iss::IssError;
using tessera::iss::IssMemory;
using tessera::iss::Mode;
namespace psr = tessera::iss::psr;

class Memory : public IssMemory {
 public:
  std::vector<uint8_t> bytes = std::vector<uint8_t>(0x10000);
  uint32_t abort_from = 0xffffffffu;  // accesses at or above this address abort
  bool read(uint32_t address, unsigned size, uint32_t& value) override {
    if (address >= abort_from || address + size > bytes.size()) return false;
    value = 0;
    for (unsigned i = 0; i < size; ++i) value |= uint32_t{bytes[address + i]} << (8 * i);
    return true;
  }
  bool write(uint32_t address, unsigned size, uint32_t value) override {
    if (address >= abort_from || address + size > bytes.size()) return false;
    for (unsigned i = 0; i < size; ++i) bytes[address + i] = static_cast<uint8_t>(value >> (8 * i));
    return true;
  }
  uint32_t word(uint32_t address) {
    uint32_t value = 0;
    read(address, 4, value);
    return value;
  }
  void program(uint32_t address, std::initializer_list<uint32_t> words) {
    for (uint32_t w : words) {
      write(address, 4, w);
      address += 4;
    }
  }
};

constexpr uint32_t SYS = 0x1f, USR = 0x10;

struct Iss : ::testing::Test {
  Memory memory;
  ArmCore core{memory};
  void start(uint32_t pc, uint32_t cpsr) {
    core.set_cpsr(cpsr);
    core.set_reg(15, pc);
  }
  void run(int steps) {
    for (int i = 0; i < steps; ++i) core.step();
  }
};

TEST_F(Iss, ResetEntersSupervisorModeAtVectorZeroWithInterruptsMasked) {
  start(0x400, USR);
  core.reset();
  EXPECT_EQ(core.mode(), Mode::svc);
  EXPECT_EQ(core.reg(15), 0u);
  EXPECT_EQ(core.cpsr() & (psr::I | psr::F | psr::T), psr::I | psr::F);
  core.set_high_vectors(true);
  core.reset();
  EXPECT_EQ(core.reg(15), 0xffff0000u);
}

// A program spinning on a branch to itself with IRQ and FIQ
// masked can never leave it; the core stops it at once, naming the PC,
// instead of letting it run to the instruction limit.
TEST_F(Iss, ABranchToItselfWithInterruptsMaskedIsAHungProgram) {
  const uint32_t masked = SYS | psr::I | psr::F;
  const auto hangs = [&](uint32_t pc, uint32_t cpsr, const char* what) {
    start(pc, cpsr);
    try {
      run(3);
      ADD_FAILURE() << what << ": not stopped";
    } catch (const IssError& error) {
      char at[32];
      std::snprintf(at, sizeof at, "at pc 0x%08x", pc);
      EXPECT_NE(std::string(error.what()).find(at), std::string::npos) << what << ": " << error.what();
      EXPECT_NE(std::string(error.what()).find("branch to itself"), std::string::npos) << error.what();
    }
    EXPECT_EQ(core.reg(15), pc) << what;
  };
  memory.program(0x200, {0xeafffffe});  // b .
  hangs(0x200, masked, "b .");
  memory.program(0x210, {0x0afffffe});  // beq . (Z set: taken, and the flags never change)
  hangs(0x210, masked | psr::Z, "beq .");
  memory.program(0x220, {0xebfffffe});  // bl .
  hangs(0x220, masked, "bl .");
  memory.program(0x230, {0x0000e7fe});  // Thumb: b .
  hangs(0x230, masked | psr::T, "Thumb b .");
  memory.program(0x240, {0x0000d0fe});  // Thumb: beq .
  hangs(0x240, masked | psr::T | psr::Z, "Thumb beq .");

  // Not hung: an interrupt may still come (I or F clear), or the branch is not taken.
  start(0x200, SYS | psr::I);
  run(1000);
  EXPECT_EQ(core.reg(15), 0x200u);
  start(0x200, SYS | psr::F);
  run(1000);
  EXPECT_EQ(core.reg(15), 0x200u);
  start(0x210, masked);  // beq with Z clear: falls through
  run(1);
  EXPECT_EQ(core.reg(15), 0x214u);
  start(0x240, masked | psr::T);
  run(1);
  EXPECT_EQ(core.reg(15), 0x242u);
}

TEST_F(Iss, AnUnalignedWordLoadRotatesTheAlignedWord) {
  memory.program(0x100, {0xe5901001,    // ldr r1, [r0, #1]
                         0xe5902003});  // ldr r2, [r0, #3]
  memory.write(0x8000, 4, 0x44332211);
  start(0x100, SYS);
  core.set_reg(0, 0x8000);
  run(2);
  EXPECT_EQ(core.reg(1), 0x11443322u);
  EXPECT_EQ(core.reg(2), 0x33221144u);
}

TEST_F(Iss, AStoredPcIsTheInstructionsAddressPlus12) {
  memory.program(0x100, {0xe580f000,                 // str pc, [r0]
                         0xe8800000 | (1u << 15)});  // stmia r0, {pc}
  start(0x100, SYS);
  core.set_reg(0, 0x8000);
  run(1);
  EXPECT_EQ(memory.word(0x8000), 0x10cu);
  run(1);
  EXPECT_EQ(memory.word(0x8000), 0x110u);
}

TEST_F(Iss, SwiEntersSupervisorModeAndMovsPcLrReturns) {
  memory.program(0x100, {0xef000012});  // swi 0x12
  memory.program(0x008, {0xe1b0f00e});  // movs pc, lr
  const uint32_t user = USR | psr::Z | psr::C;
  start(0x100, user);
  core.set_reg(13, 0x1111);
  core.set_reg(14, 0x2222);
  run(1);
  EXPECT_EQ(core.mode(), Mode::svc);
  EXPECT_EQ(core.reg(15), 0x08u);
  EXPECT_EQ(core.reg(14), 0x104u);
  EXPECT_EQ(core.spsr(), user);
  EXPECT_TRUE(core.cpsr() & psr::I);
  EXPECT_EQ(core.banked(Mode::usr, 13), 0x1111u);
  run(1);
  EXPECT_EQ(core.cpsr(), user);
  EXPECT_EQ(core.reg(15), 0x104u);
  EXPECT_EQ(core.reg(13), 0x1111u);  // the user bank again
  EXPECT_EQ(core.reg(14), 0x2222u);
}

TEST_F(Iss, AnIrqIsTakenBetweenInstructionsWhenUnmaskedAndReturnsWithSubs) {
  memory.program(0x100, {0xe1a00000, 0xe1a00000});  // nop; nop
  memory.program(0x018, {0xe25ef004});              // subs pc, lr, #4
  start(0x100, SYS | psr::I);
  core.set_irq(true);
  run(1);  // masked: the nop runs
  EXPECT_EQ(core.reg(15), 0x104u);
  core.set_cpsr(SYS);
  run(1);
  EXPECT_EQ(core.mode(), Mode::irq);
  EXPECT_EQ(core.reg(15), 0x18u);
  EXPECT_EQ(core.reg(14), 0x108u);
  core.set_irq(false);
  run(1);
  EXPECT_EQ(core.mode(), Mode::sys);
  EXPECT_EQ(core.reg(15), 0x104u);  // the instruction that had not run
}

TEST_F(Iss, FiqBanksR8ToR14AndHasPriorityOverIrq) {
  memory.program(0x100, {0xe1a00000});
  memory.program(0x01c, {0xe3a08001});  // mov r8, #1
  start(0x100, SYS);
  for (unsigned n = 8; n < 15; ++n) core.set_reg(n, 0x80 + n);
  core.set_irq(true);
  core.set_fiq(true);
  run(1);
  EXPECT_EQ(core.mode(), Mode::fiq);
  EXPECT_TRUE(core.cpsr() & psr::F);
  EXPECT_TRUE(core.cpsr() & psr::I);
  run(1);
  EXPECT_EQ(core.reg(8), 1u);
  EXPECT_EQ(core.banked(Mode::usr, 8), 0x88u);
  EXPECT_EQ(core.banked(Mode::usr, 12), 0x8cu);
  EXPECT_EQ(core.banked(Mode::sys, 14), 0x8eu);
}

TEST_F(Iss, ADataAbortLeavesTheBaseAsItWas) {
  memory.program(0x100, {0xe5b32004});  // ldr r2, [r3, #4]!
  memory.abort_from = 0x9000;
  start(0x100, SYS | psr::N);
  core.set_reg(2, 0x2222);
  core.set_reg(3, 0x9000);
  run(1);
  EXPECT_EQ(core.mode(), Mode::abt);
  EXPECT_EQ(core.reg(15), 0x10u);
  EXPECT_EQ(core.reg(14), 0x108u);  // the aborted instruction + 8
  EXPECT_EQ(core.spsr(), SYS | psr::N);
  EXPECT_EQ(core.reg(3), 0x9000u);
  EXPECT_EQ(core.reg(2), 0x2222u);
}

TEST_F(Iss, APrefetchAbortReturnsToTheInstructionPlus4) {
  memory.abort_from = 0x9000;
  start(0x9000, SYS);
  run(1);
  EXPECT_EQ(core.mode(), Mode::abt);
  EXPECT_EQ(core.reg(15), 0x0cu);
  EXPECT_EQ(core.reg(14), 0x9004u);
}

TEST_F(Iss, UndefinedInstructionsAndCoprocessorsWithoutAHandler) {
  memory.program(0x100, {0xe7f000f0,    // an undefined encoding
                         0xee100f10});  // mrc p15, 0, r0, c0, c0, 0
  start(0x100, SYS);
  run(1);
  EXPECT_EQ(core.mode(), Mode::und);
  EXPECT_EQ(core.reg(15), 0x04u);
  EXPECT_EQ(core.reg(14), 0x104u);
  start(0x104, SYS);
  run(1);
  EXPECT_EQ(core.mode(), Mode::und);
  EXPECT_EQ(core.reg(14), 0x108u);
}

struct IdRegister : Coprocessors {
  bool mrc(unsigned cp, unsigned op1, unsigned crn, unsigned crm, unsigned op2, bool privileged,
           uint32_t& value) override {
    if (cp != 15 || op1 || crn || crm || op2 || !privileged) return false;
    value = 0x41129200;
    return true;
  }
  bool mcr(unsigned, unsigned, unsigned, unsigned, unsigned, bool, uint32_t) override { return false; }
};

TEST_F(Iss, MrcReadsACoprocessorRegisterOnlyWhenPrivileged) {
  IdRegister cp15;
  ArmCore with_cp15(memory, &cp15);
  memory.program(0x100, {0xee100f10});  // mrc p15, 0, r0, c0, c0, 0
  with_cp15.set_cpsr(SYS);
  with_cp15.set_reg(15, 0x100);
  with_cp15.step();
  EXPECT_EQ(with_cp15.reg(0), 0x41129200u);
  with_cp15.set_cpsr(USR);
  with_cp15.set_reg(15, 0x100);
  with_cp15.step();
  EXPECT_EQ(with_cp15.mode(), Mode::und);
}

TEST_F(Iss, UserModeMsrChangesTheFlagsButNotTheMode) {
  memory.program(0x100, {0xe329f013});  // msr cpsr_cf, #0x13
  start(0x100, USR);
  run(1);
  EXPECT_EQ(core.mode(), Mode::usr);
  start(0x100, SYS);
  run(1);
  EXPECT_EQ(core.mode(), Mode::svc);
}

TEST_F(Iss, LdmWithThePcAndCaretRestoresTheCpsrFromTheSpsr) {
  memory.program(0x100, {0xe8fd8000});  // ldmia sp!, {pc}^
  memory.write(0x8000, 4, 0x200);
  start(0x100, static_cast<uint32_t>(Mode::svc));
  core.set_spsr(USR | psr::V);
  core.set_reg(13, 0x8000);
  run(1);
  EXPECT_EQ(core.cpsr(), USR | psr::V);
  EXPECT_EQ(core.reg(15), 0x200u);
  EXPECT_EQ(core.banked(Mode::svc, 13), 0x8004u);
}

TEST_F(Iss, StmWithCaretStoresTheUserRegisters) {
  memory.program(0x100, {0xe8c06000});  // stmia r0, {sp, lr}^
  start(0x100, SYS);
  core.set_reg(13, 0x1313);
  core.set_reg(14, 0x1414);
  core.set_cpsr(static_cast<uint32_t>(Mode::irq));
  core.set_reg(0, 0x8000);
  core.set_reg(13, 0xaaaa);
  core.set_reg(14, 0xbbbb);
  core.set_reg(15, 0x100);
  run(1);
  EXPECT_EQ(memory.word(0x8000), 0x1313u);
  EXPECT_EQ(memory.word(0x8004), 0x1414u);
}

TEST_F(Iss, BxEntersAndLeavesThumbStateAndPopPcStaysInThumb) {
  memory.program(0x100, {0xe12fff10});  // bx r0
  memory.write(0x200, 2, 0xbd00);       // pop {pc}
  memory.write(0x240, 2, 0x4708);       // bx r1
  start(0x100, SYS);
  core.set_reg(0, 0x201);
  core.set_reg(1, 0x300);
  core.set_reg(13, 0x8000);
  memory.write(0x8000, 4, 0x241);  // ARMv4T: POP {pc} ignores bit 0 and stays in Thumb
  run(1);
  EXPECT_TRUE(core.thumb());
  EXPECT_EQ(core.reg(15), 0x200u);
  run(1);
  EXPECT_TRUE(core.thumb());
  EXPECT_EQ(core.reg(15), 0x240u);
  EXPECT_EQ(core.reg(13), 0x8004u);
  run(1);
  EXPECT_FALSE(core.thumb());
  EXPECT_EQ(core.reg(15), 0x300u);
}

TEST_F(Iss, ThumbSwiAndUndefinedReturnToTheNextHalfwordInArmState) {
  memory.write(0x200, 2, 0xdf05);  // swi 5
  memory.write(0x202, 2, 0xde00);  // an undefined encoding (B with condition AL)
  start(0x200, SYS | psr::T);
  run(1);
  EXPECT_EQ(core.mode(), Mode::svc);
  EXPECT_FALSE(core.thumb());
  EXPECT_EQ(core.reg(14), 0x202u);
  EXPECT_EQ(core.spsr(), SYS | psr::T);
  start(0x202, SYS | psr::T);
  run(1);
  EXPECT_EQ(core.mode(), Mode::und);
  EXPECT_EQ(core.reg(14), 0x204u);
  EXPECT_EQ(core.reg(15), 0x04u);
}

TEST_F(Iss, AnEmptyRegisterListIsAClearErrorNotASilentSkip) {
  memory.program(0x100, {0xe8900000});  // ldmia r0, {}
  start(0x100, SYS);
  try {
    core.step();
    FAIL() << "no error";
  } catch (const IssError& error) {
    EXPECT_NE(std::string(error.what()).find("empty register list at 0x00000100"), std::string::npos) << error.what();
  }
}

// MRC/MCR p15, 0, Rd, CRn, CRm, op2
constexpr uint32_t mrc(unsigned rd, unsigned crn, unsigned crm, unsigned op2) {
  return 0xee100f10u | (crn << 16) | (rd << 12) | (op2 << 5) | crm;
}
constexpr uint32_t mcr(unsigned rd, unsigned crn, unsigned crm, unsigned op2) {
  return 0xee000f10u | (crn << 16) | (rd << 12) | (op2 << 5) | crm;
}

struct Recorder : CacheMaintenance {
  std::vector<std::string> calls;
  void invalidate_instruction_cache() override { calls.push_back("invalidate I"); }
  void invalidate_data_line(uint32_t address) override { calls.push_back("invalidate D " + std::to_string(address)); }
  void clean_data_line(uint32_t address, bool invalidate) override {
    calls.push_back(std::string(invalidate ? "clean+invalidate D " : "clean D ") + std::to_string(address));
  }
  void drain_write_buffer() override { calls.push_back("drain"); }
  void invalidate_data_cache() override { calls.push_back("invalidate D"); }
  void clean_data_index(uint32_t index, bool invalidate) override {
    calls.push_back(std::string(invalidate ? "clean+invalidate D index " : "clean D index ") + std::to_string(index));
  }
  void control_written(uint32_t control) override { calls.push_back("control " + std::to_string(control)); }
};

TEST_F(Iss, Cp15IdentifiesAnArm922tWithTwo8KbCaches) {
  Cp15 cp15(core);
  core.set_coprocessors(&cp15);
  ArmCore& cpu = core;
  memory.program(0x100, {mrc(0, 0, 0, 0), mrc(1, 0, 0, 1)});
  cpu.set_cpsr(SYS);
  cpu.set_reg(15, 0x100);
  cpu.step();
  cpu.step();
  const uint32_t id = cpu.reg(0), type = cpu.reg(1);
  EXPECT_EQ(id >> 24, 0x41u);        // ARM
  EXPECT_EQ((id >> 16) & 0xfu, 2u);  // ARMv4T
  EXPECT_EQ((id >> 4) & 0xfffu, 0x922u);
  EXPECT_EQ((type >> 24) & 1u, 1u);                 // separate I and D caches
  for (const uint32_t side : {type >> 12, type}) {  // D, then I
    const uint32_t size = (side >> 6) & 7u, assoc = (side >> 3) & 7u, m = (side >> 2) & 1u, len = side & 3u;
    EXPECT_EQ(m, 0u);
    EXPECT_EQ(512u << size, 8192u);  // bytes (M = 0)
    EXPECT_EQ(1u << assoc, 64u);     // ways
    EXPECT_EQ(8u << len, 32u);       // bytes per line: 8 words
  }
}

TEST_F(Iss, Cp15ControlRegisterKeepsWritableBitsAndMovesTheVectors) {
  Cp15 cp15(core);
  core.set_coprocessors(&cp15);
  ArmCore& cpu = core;
  memory.program(0x100, {mrc(2, 1, 0, 0), mcr(0, 1, 0, 0), mrc(3, 1, 0, 0), 0xef000000});  // ..., swi 0
  cpu.set_cpsr(SYS);
  cpu.set_reg(0, 0xffffffffu);
  cpu.set_reg(15, 0x100);
  for (int i = 0; i < 4; ++i) cpu.step();
  EXPECT_EQ(cpu.reg(2), 0x00000078u);  // bits 6:3 should-be-one, everything off
  // M A C, SBO 6:3, S R, I V RR, nF iA: not B (little-endian only)
  EXPECT_EQ(cpu.reg(3), 0x7u | 0x78u | 0x300u | 0x7000u | 0xc0000000u);
  EXPECT_TRUE(cp15.instruction_cache_enabled());
  EXPECT_TRUE(cp15.data_cache_enabled());
  EXPECT_EQ(cpu.reg(15), 0xffff0008u);  // SWI through the high vectors
}

TEST_F(Iss, Cp15CacheOperationsReachTheCachesAndUserModeIsRefused) {
  Recorder recorder;
  Cp15 cp15(core, &recorder);
  core.set_coprocessors(&cp15);
  ArmCore& cpu = core;
  memory.program(0x100, {mcr(0, 7, 5, 0),    // invalidate the I-cache
                         mcr(1, 7, 6, 1),    // invalidate the D line of r1
                         mcr(1, 7, 10, 1),   // clean the D line of r1
                         mcr(1, 7, 14, 1),   // clean and invalidate it
                         mcr(0, 7, 10, 4),   // drain the write buffer
                         mcr(0, 7, 6, 0),    // invalidate the D-cache
                         mcr(2, 7, 10, 2),   // clean the D entry of index r2
                         mcr(2, 7, 14, 2),   // clean and invalidate it
                         mcr(0, 7, 7, 0),    // invalidate both caches
                         mcr(3, 1, 0, 0)});  // the control register: C and RR
  cpu.set_cpsr(SYS);
  cpu.set_reg(1, 0x8020);
  cpu.set_reg(2, (5u << 26) | (3u << 5));  // way 5, set 3
  cpu.set_reg(3, Cp15::CONTROL_C | Cp15::CONTROL_RR);
  cpu.set_reg(15, 0x100);
  for (int i = 0; i < 10; ++i) cpu.step();
  EXPECT_EQ(recorder.calls,
            (std::vector<std::string>{"invalidate I", "invalidate D 32800", "clean D 32800", "clean+invalidate D 32800",
                                      "drain", "invalidate D", "clean D index 335544416",
                                      "clean+invalidate D index 335544416", "invalidate I", "invalidate D",
                                      "control " + std::to_string(0x78u | Cp15::CONTROL_C | Cp15::CONTROL_RR)}));
  cpu.set_cpsr(USR);
  cpu.set_reg(15, 0x100);
  cpu.step();
  EXPECT_EQ(cpu.mode(), Mode::und);
  EXPECT_EQ(recorder.calls.size(), 11u);
}

// The decode cache (README.md, "The decode cache"): an instruction the
// program stores over one it has run is the one that runs next time, with
// or without the c7 invalidation the ARM922T would need (the model's memory
// is coherent: its caches are tag models that only cost time); a store
// into a code page beside the instructions decodes nothing again. The
// core runs under the timing layer, as in iss_run --timing, so that c7
// reaches an instruction cache.
struct DecodeCache : ::testing::Test {
  Memory memory;
  Arm922tTiming timing;
  tessera::iss::TimedFetch<Memory> port{memory, &timing};
  ArmCore core{port};
  Cp15 cp15{core, &timing};
  void SetUp() override {
    core.set_coprocessors(&cp15);
    timing.attach(&cp15);
    cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() | Cp15::CONTROL_I);
  }
  // Steps until the PC is `end` (at most 100 steps); the steps taken.
  int run_to(uint32_t end) {
    int steps = 0;
    while (core.reg(15) != end && steps < 100) {
      core.step();
      timing.step(core.last_step());
      ++steps;
    }
    return steps;
  }
  // Stores its new instruction over the one at 0x100 and runs it: r0 is 1
  // after the old instruction, 2 after the new one.
  void self_modifying(uint32_t between_store_and_branch) {
    memory.program(0x100, {0xe3a00001,                // mov r0, #1      @ replaced by mov r0, #2
                           0xe3500002,                // cmp r0, #2
                           0x0a000004,                // beq 0x120
                           0xe59f1010,                // ldr r1, [pc, #16]   @ the word at 0x124
                           0xe3a02c01,                // mov r2, #0x100
                           0xe5821000,                // str r1, [r2]
                           between_store_and_branch,  //
                           0xeafffff7,                // b 0x100
                           0xe1a00000,                // nop             @ 0x120: done
                           0xe3a00002});              // .word: mov r0, #2
    core.set_cpsr(SYS);
    core.set_reg(15, 0x100);
  }
};

TEST_F(DecodeCache, AnInstructionStoredOverOneThatRanIsExecutedWithoutAnInvalidation) {
  self_modifying(0xe1a00000);    // nop
  EXPECT_EQ(run_to(0x120), 11);  // 8 instructions, then the new one, cmp and beq
  EXPECT_EQ(memory.word(0x100), 0xe3a00002u);
  EXPECT_EQ(core.reg(0), 2u);
  EXPECT_EQ(core.decodes(), 9u);  // the 8 instructions and the new one
  // One line fetched (0x100..0x11f), missed once: the I-cache still holds
  // it with the old instruction (its data are the model's memory, always current).
  EXPECT_EQ(timing.icache().misses(), 1u);
}

TEST_F(DecodeCache, AnInstructionStoredOverOneThatRanIsExecutedAfterAnInvalidation) {
  self_modifying(mcr(2, 7, 5, 1));  // invalidate the I-cache line of r2 (0x100)
  EXPECT_EQ(run_to(0x120), 11);
  EXPECT_EQ(core.reg(0), 2u);
  EXPECT_EQ(core.decodes(), 9u);
  // The line invalidated under the branch at 0x11c: it misses again there.
  EXPECT_EQ(timing.icache().misses(), 2u);
}

TEST_F(DecodeCache, AThumbInstructionStoredOverOneThatRanIsExecuted) {
  // Halfwords, two to a word, the first in the low half.
  memory.program(0x200, {0x28022001,    // 0x200: movs r0, #1 (replaced by movs r0, #2); cmp r0, #2
                         0x4a03d004,    // 0x204: beq 0x210; ldr r2, [pc, #12] (the word at 0x214)
                         0x801a4b03,    // 0x208: ldr r3, [pc, #12] (the word at 0x218); strh r2, [r3]
                         0x46c0e7f8,    // 0x20c: b 0x200; nop
                         0x46c046c0,    // 0x210: nop (done); nop
                         0x00002002,    // 0x214: .word: movs r0, #2
                         0x00000200});  // 0x218: .word: 0x200
  core.set_cpsr(SYS | psr::T);
  core.set_reg(15, 0x200);
  EXPECT_EQ(run_to(0x210), 10);  // 7 instructions, then the new one, cmp and beq
  EXPECT_EQ(core.reg(0), 2u);
  EXPECT_EQ(core.decodes(), 8u);
}

TEST_F(DecodeCache, AStoreIntoACodePageBesideTheInstructionsDecodesNothingAgain) {
  memory.program(0x100, {0xe3a00000,    // mov r0, #0
                         0xe2800001,    // add r0, r0, #1
                         0xe58f0008,    // str r0, [pc, #8]   @ the word at 0x118: same page, same line
                         0xe350000a,    // cmp r0, #10
                         0x1afffffb,    // bne 0x104
                         0xe1a00000,    // nop                @ 0x114: done
                         0x00000000});  // .word
  core.set_cpsr(SYS);
  core.set_reg(15, 0x100);
  EXPECT_EQ(run_to(0x114), 41);
  EXPECT_EQ(core.reg(0), 10u);
  EXPECT_EQ(memory.word(0x118), 10u);
  EXPECT_EQ(core.decodes(), 5u);  // each of the 5 instructions once, for 41 executed
  EXPECT_EQ(timing.icache().misses(), 1u);
}

TEST_F(DecodeCache, TheSameWordIsDecodedApartInArmAndThumbState) {
  memory.program(0x300, {0x00002001});  // ARM: andeq r2, r0, r1; Thumb: movs r0, #1 (and a 0)
  core.set_cpsr(SYS | psr::Z);
  core.set_reg(0, 0x10);
  core.set_reg(1, 0x30);
  core.set_reg(15, 0x300);
  core.step();
  EXPECT_EQ(core.reg(2), 0x10u);
  core.set_cpsr(SYS | psr::T);
  core.set_reg(15, 0x300);
  core.step();
  EXPECT_EQ(core.reg(0), 1u);
  EXPECT_EQ(core.decodes(), 2u);
}

// Every word fetched is a branch to the same place in the next 4 KB page.
struct PageHopper : IssMemory {
  bool read(uint32_t, unsigned, uint32_t& value) override {
    value = 0xea0003feu;  // b . + 4096
    return true;
  }
  bool write(uint32_t, unsigned, uint32_t) override { return true; }
};

TEST(DecodeCachePages, ProgramsRunningThroughMorePagesThanKeptRunOn) {
  PageHopper memory;
  ArmCore core(memory);
  core.set_cpsr(SYS);
  core.set_reg(15, 0x10000000u);
  for (int i = 0; i < 600; ++i) core.step();  // past the 256 pages kept, twice
  EXPECT_EQ(core.reg(15), 0x10000000u + 600u * 4096u);
  EXPECT_EQ(core.decodes(), 600u);
  core.set_reg(15, 0x10000000u);  // the first pages again: dropped, so decoded again
  for (int i = 0; i < 10; ++i) core.step();
  EXPECT_EQ(core.reg(15), 0x10000000u + 10u * 4096u);
  EXPECT_EQ(core.decodes(), 610u);
}

// Blocks (README.md, "Blocks"): ArmCore::run goes on within a resident line
// without the port or the decode cache's look-up, and must still see a
// store into the line and an interrupt raised between two instructions.
// The port grants every line it fetches from, as the bare machine does.
struct LineMemory : Memory {
  tessera::iss::ResidentLines resident;
  uint64_t line_fetches = 0, port_fetches = 0;
  bool fetch(uint32_t address, unsigned size, uint32_t& value) override {
    ++port_fetches;
    if (!read(address, size, value)) return false;
    const uint32_t line = tessera::iss::ResidentLines::line_of(address);
    resident.grant(line, &bytes[line], &line_fetches);
    return true;
  }
  tessera::iss::ResidentLines* resident_lines() override { return &resident; }
};

struct Blocks : ::testing::Test {
  LineMemory memory;
  ArmCore core{memory};
};

TEST_F(Blocks, AStoreIntoTheBlockAheadIsExecuted) {
  // One line, run twice; on the second pass the store replaces the
  // instruction at 0x10c, decoded on the first, two instructions ahead.
  memory.program(0x100, {0xe3530000,    // 0x100: cmp r3, #0
                         0x158f1000,    // 0x104: strne r1, [pc]   @ to 0x10c
                         0xe1a00000,    // 0x108: nop
                         0xe3a00001,    // 0x10c: mov r0, #1       @ replaced by r1: mov r0, #2
                         0xe2833001,    // 0x110: add r3, r3, #1
                         0xe3530002,    // 0x114: cmp r3, #2
                         0x1afffff8,    // 0x118: bne 0x100
                         0xe1a00000});  // 0x11c: nop (done)
  core.set_cpsr(SYS);
  core.set_reg(1, 0xe3a00002);
  core.set_reg(15, 0x100);
  int steps = 0;
  core.run([&] {
    ++steps;
    if (steps == 4) {
      EXPECT_EQ(core.reg(0), 1u);  // the first pass: the old instruction
    }
    return core.reg(15) != 0x11c;
  });
  EXPECT_EQ(steps, 14);
  EXPECT_EQ(core.reg(0), 2u);
  EXPECT_EQ(memory.word(0x10c), 0xe3a00002u);
  EXPECT_EQ(core.decodes(), 8u);  // the 7 instructions and the new one
  // One fetch through the port (the first), the other 13 from the line.
  EXPECT_EQ(memory.port_fetches, 1u);
  EXPECT_EQ(memory.line_fetches, 13u);
}

TEST_F(Blocks, AnInterruptRaisedAfterAnInstructionIsTakenBeforeTheNext) {
  memory.program(0x100, {0xe3a00001,    // 0x100: mov r0, #1
                         0xe3a01002,    // 0x104: mov r1, #2
                         0xe3a02003,    // 0x108: mov r2, #3   @ not run: the IRQ comes first
                         0xe1a00000});  // 0x10c: nop
  core.set_cpsr(SYS);                   // IRQ not masked
  core.set_reg(15, 0x100);
  int steps = 0;
  core.run([&] {
    if (++steps == 2) core.set_irq(true);
    return steps < 3;
  });
  EXPECT_EQ(core.reg(1), 2u);
  EXPECT_EQ(core.reg(2), 0u);
  EXPECT_EQ(core.mode(), Mode::irq);
  EXPECT_EQ(core.reg(14), 0x10cu);  // the instruction that would have run, + 4
  EXPECT_EQ(core.reg(15), 0x18u);   // the IRQ vector
  EXPECT_EQ(core.instructions(), 2u);
}

}  // namespace
