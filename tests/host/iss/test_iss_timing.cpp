// The ARM922T timing layer (Arm922tTiming): each rule on a hand-encoded
// sequence, the assembly beside it and the expected count worked out from
// the ARM9TDMI Technical Reference Manual (ARM DDI 0145B, chapter 7
// "Instruction Cycle Summary and Interlocks") and the ARM922T TRM's cache
// chapters, as tlm/host/iss/README.md ("Timing") lists them. The core's
// cycles and the instruction fetch stalls are checked apart.
#include <vector>

#include <gtest/gtest.h>

#include "host/iss/arm922t_timing.h"
#include "host/iss/arm_core.h"
#include "host/iss/cp15.h"

namespace {

using tessera::iss::Arm922tTiming;
using tessera::iss::ArmCore;
using tessera::iss::Cp15;
using tessera::iss::InstructionCache;
using tessera::iss::IssMemory;
using tessera::iss::TimedFetch;
namespace psr = tessera::iss::psr;

class Memory : public IssMemory {
 public:
  std::vector<uint8_t> bytes = std::vector<uint8_t>(0x10000);
  bool read(uint32_t address, unsigned size, uint32_t& value) override {
    if (address + size > bytes.size()) return false;
    value = 0;
    for (unsigned i = 0; i < size; ++i) value |= uint32_t{bytes[address + i]} << (8 * i);
    return true;
  }
  bool write(uint32_t address, unsigned size, uint32_t value) override {
    if (address + size > bytes.size()) return false;
    for (unsigned i = 0; i < size; ++i) bytes[address + i] = static_cast<uint8_t>(value >> (8 * i));
    return true;
  }
  void program(uint32_t address, std::initializer_list<uint32_t> words) {
    for (uint32_t w : words) {
      write(address, 4, w);
      address += 4;
    }
  }
  void thumb(uint32_t address, std::initializer_list<uint16_t> halves) {
    for (uint16_t h : halves) {
      write(address, 2, h);
      address += 2;
    }
  }
};

constexpr uint32_t SYS = 0x1f;
constexpr uint32_t CODE = 0x1000;  // 32-byte aligned: a line starts here

struct Timing : ::testing::Test {
  Memory memory;
  Arm922tTiming timing;
  TimedFetch<Memory> port{memory, &timing};
  ArmCore core{port};
  Cp15 cp15{core, &timing};

  Timing() {
    core.set_coprocessors(&cp15);
    timing.attach(&cp15);
    cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() | Cp15::CONTROL_I);
    core.set_cpsr(SYS);
    core.set_reg(15, CODE);
  }
  // Each step's core cycles (interlocks included, fetch stalls apart).
  std::vector<unsigned> run(int steps) {
    std::vector<unsigned> cycles;
    for (int i = 0; i < steps; ++i) {
      core.step();
      cycles.push_back(timing.step(core.last_step()));
    }
    return cycles;
  }
  using Cycles = std::vector<unsigned>;
};

// ARM encodings used below (condition AL unless named).
constexpr uint32_t ADD_R0_R1_R2 = 0xe0810002u;       // add r0, r1, r2
constexpr uint32_t ADD_R2_R0_R3 = 0xe0802003u;       // add r2, r0, r3   (uses r0)
constexpr uint32_t ADD_R5_R4_R3 = 0xe0845003u;       // add r5, r4, r3   (does not)
constexpr uint32_t LDR_R0_R1 = 0xe5910000u;          // ldr r0, [r1]
constexpr uint32_t LDRB_R0_R1 = 0xe5d10000u;         // ldrb r0, [r1]
constexpr uint32_t MUL_R0_R1_R2 = 0xe0000291u;       // mul r0, r1, r2   (multiplier r2)
constexpr uint32_t UMULL_R0_R1_R2_R3 = 0xe0810392u;  // umull r0, r1, r2, r3 (multiplier r3)

TEST_F(Timing, DataProcessingTakesOneCycle) {
  // TRM 7.1: data operation, normal case: 1 cycle.
  memory.program(CODE, {ADD_R0_R1_R2});
  EXPECT_EQ(run(1), Cycles{1});
}

TEST_F(Timing, ShiftByARegisterAddsACycle) {
  // TRM 7.1: data operation with a register-controlled shift: 2 cycles
  // (the shift amount is read in a cycle of its own).
  memory.program(CODE, {0xe0810312u});  // add r0, r1, r2, lsl r3
  EXPECT_EQ(run(1), Cycles{2});
}

TEST_F(Timing, WritingThePcAddsThePipelineRefill) {
  // TRM 7.1: data operation with the PC as destination: 3 cycles (1 + the
  // two fetches of the refill); with a register shift as well: 4.
  memory.program(CODE, {0xe1a0f004u});          // mov pc, r4
  memory.program(CODE + 0x100, {0xe1a0f514u});  // mov pc, r4, lsl r5
  core.set_reg(4, CODE + 0x100);
  core.set_reg(5, 0);
  EXPECT_EQ(run(1), Cycles{3});
  core.set_reg(4, CODE + 0x200);
  EXPECT_EQ(run(1), Cycles{4});
}

TEST_F(Timing, LoadFollowedByAUseInterlocksOneCycle) {
  // TRM 7.2 example 1: ldr r0, [r1]; add r2, r0, r1: the add waits one
  // cycle for the loaded word: 1 + (1 + 1).
  memory.program(CODE, {LDR_R0_R1, ADD_R2_R0_R3});
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(2), (Cycles{1, 2}));
  EXPECT_EQ(timing.interlock_cycles(), 1u);
}

TEST_F(Timing, LoadNotFollowedByAUseDoesNotInterlock) {
  // TRM 7.1: LDR, normal case: 1 cycle; the next instruction does not read r0: 1.
  memory.program(CODE, {LDR_R0_R1, ADD_R5_R4_R3, ADD_R2_R0_R3});
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(3), (Cycles{1, 1, 1}));
  EXPECT_EQ(timing.interlock_cycles(), 0u);
}

TEST_F(Timing, ByteLoadInterlocksTwoCyclesOrOneOnTheInstructionAfterNext) {
  // TRM 7.1/7.2 example 2: a byte (halfword, unaligned word) is rotated in
  // the Write stage: the next instruction using it waits two cycles (1 + 2);
  // the one after next, behind a single-cycle instruction, waits one.
  memory.program(CODE, {LDRB_R0_R1, ADD_R2_R0_R3, LDRB_R0_R1, ADD_R5_R4_R3, ADD_R2_R0_R3});
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(5), (Cycles{1, 3, 1, 1, 2}));
}

TEST_F(Timing, LoadToThePcTakesFiveCycles) {
  // TRM 7.1: LDR with the PC as destination: 5 cycles (no interlock after:
  // the pipeline is refilled).
  memory.program(CODE, {0xe591f000u, 0});  // ldr pc, [r1]
  memory.write(0x8000, 4, CODE + 0x100);
  memory.program(CODE + 0x100, {ADD_R0_R1_R2});
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(2), (Cycles{5, 1}));
  EXPECT_EQ(core.reg(15), CODE + 0x104);
}

TEST_F(Timing, LoadMultipleOfOneAndOfFourRegisters) {
  // TRM 7.1: LDM of one register (not the PC): 2 cycles; of n > 1: n.
  memory.program(CODE, {0xe8910001u,    // ldmia r1, {r0}
                        0xe891001du});  // ldmia r1, {r0, r2, r3, r4}
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(2), (Cycles{2, 4}));
}

TEST_F(Timing, LoadMultipleWithThePcAddsTheRefill) {
  // TRM 7.1: LDM of n registers including the PC: n + 4 cycles: 2 + 4.
  memory.program(CODE, {0xe8918001u});  // ldmia r1, {r0, pc}
  memory.write(0x8004, 4, CODE + 0x100);
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(1), Cycles{6});
  EXPECT_EQ(core.reg(15), CODE + 0x100);
}

TEST_F(Timing, LoadMultipleInterlocksOnItsLastRegister) {
  // TRM 7.2: the last register an LDM loads is as late as an LDR's word: the
  // next instruction reading it waits a cycle (4 + (1 + 1)); reading an
  // earlier one, it does not.
  memory.program(CODE, {0xe891001du, 0xe0845004u,    // ldmia r1, {r0, r2, r3, r4}; add r5, r4, r4
                        0xe891001du, 0xe0825002u});  // ldmia r1, {r0, r2, r3, r4}; add r5, r2, r2
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(4), (Cycles{4, 2, 4, 1}));
}

TEST_F(Timing, StoresAndSwap) {
  // TRM 7.1: STR 1; STM of one register 2, of n > 1 n; SWP 2.
  memory.program(CODE, {0xe5810000u,    // str r0, [r1]
                        0xe8810001u,    // stmia r1, {r0}
                        0xe881000du,    // stmia r1, {r0, r2, r3}
                        0xe1014092u});  // swp r4, r2, [r1]
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(4), (Cycles{1, 2, 3, 2}));
}

TEST_F(Timing, MultiplyTerminatesEarlyOnASmallMultiplier) {
  // TRM 7.1: MUL takes 1 + m cycles, m = 1 when the multiplier's bits 31:8
  // are all zero or all one, 2 for bits 31:16, 3 for bits 31:24, 4 otherwise.
  memory.program(CODE, {MUL_R0_R1_R2, MUL_R0_R1_R2, MUL_R0_R1_R2, MUL_R0_R1_R2});
  core.set_reg(1, 7);
  core.set_reg(2, 5);  // m = 1: 2 cycles
  auto first = run(1);
  core.set_reg(2, 0xfffffff0u);  // -16: bits 31:8 all one, m = 1: 2
  auto second = run(1);
  core.set_reg(2, 0x00012345u);  // bits 31:24 zero, 23:16 not: m = 3: 4
  auto third = run(1);
  core.set_reg(2, 0x12345678u);  // m = 4: 5
  auto fourth = run(1);
  EXPECT_EQ(first, Cycles{2});
  EXPECT_EQ(second, Cycles{2});
  EXPECT_EQ(third, Cycles{4});
  EXPECT_EQ(fourth, Cycles{5});
}

TEST_F(Timing, LongMultiplyAndAccumulate) {
  // TRM 7.1: MLA 2 + m; UMULL 2 + m (unsigned: only leading zeros end it
  // early, so -16 is m = 4).
  memory.program(CODE, {0xe0204291u,  // mla r0, r1, r2, r4
                        UMULL_R0_R1_R2_R3, UMULL_R0_R1_R2_R3});
  core.set_reg(2, 3);
  core.set_reg(3, 0x40);
  auto first = run(2);
  core.set_reg(3, 0xfffffff0u);
  auto second = run(1);
  EXPECT_EQ(first, (Cycles{3, 3}));
  EXPECT_EQ(second, Cycles{6});
}

TEST_F(Timing, TakenBranchRefillsThePipelineNotTakenDoesNot) {
  // TRM 7.1: B, BL, BX: 3 cycles; a failed condition: 1.
  memory.program(CODE, {0x1a000002u,           // bne +16 (Z set: not taken)
                        0xea000002u});         // b +16 (to CODE + 0x14)
  memory.program(CODE + 0x14, {0xe12fff14u});  // bx r4
  core.set_reg(4, CODE + 0x40);
  core.set_cpsr(SYS | psr::Z);
  EXPECT_EQ(run(3), (Cycles{1, 3, 3}));
  EXPECT_EQ(core.reg(15), CODE + 0x40);
}

TEST_F(Timing, ConditionFailedInstructionTakesOneCycle) {
  // TRM 7.1: any instruction whose condition fails: 1 cycle, even one that
  // would write the PC or multiply.
  memory.program(CODE, {0x11a0f004u,    // movne pc, r4
                        0x10000291u,    // mulne r0, r1, r2
                        0x1891001du});  // ldmneia r1, {r0, r2, r3, r4}
  core.set_reg(2, 0x12345678u);
  core.set_cpsr(SYS | psr::Z);
  EXPECT_EQ(run(3), (Cycles{1, 1, 1}));
}

TEST_F(Timing, SoftwareInterruptAndStatusTransfers) {
  // TRM 7.1: SWI 3 (the vector's refill); MRS 2; MSR of the flags 1, of the
  // control field (mode, I, F) 3.
  memory.program(CODE, {0xe10f0000u,    // mrs r0, cpsr
                        0xe128f000u,    // msr cpsr_f, r0
                        0xe121f000u,    // msr cpsr_c, r0
                        0xef000000u});  // swi 0
  EXPECT_EQ(run(4), (Cycles{2, 1, 3, 3}));
  EXPECT_EQ(core.reg(15), 8u);
}

TEST_F(Timing, ThumbInstructionsTakeTheirArmEquivalentsCycles) {
  // TRM 7.1 through the ARM instruction each stands for: add (1), lsl by a
  // register (2), ldr then a use (1, then 1 + 1), BL's halves (1, then the
  // branch's 3).
  core.set_cpsr(SYS | psr::T);
  memory.thumb(CODE, {0x1888,    // adds r0, r1, r2
                      0x4088,    // lsls r0, r1
                      0x6808,    // ldr r0, [r1]
                      0x1c02,    // adds r2, r0, #0
                      0xf000,    // bl (first half)
                      0xf808});  // bl (second half): to CODE + 0xc + 0x10
  core.set_reg(1, 0x8000);
  EXPECT_EQ(run(6), (Cycles{1, 2, 1, 2, 1, 3}));
  EXPECT_EQ(core.reg(15), CODE + 0x1c);
}

TEST_F(Timing, InstructionCacheMissFillsALineThenHits) {
  // ARM922T TRM, instruction cache: 8-word lines; a miss fills the line
  // (TimingParams::line_fill_cycles) and the next seven ARM instructions of
  // the line hit. The ninth is in the next line: a miss again.
  memory.program(CODE, {ADD_R0_R1_R2, ADD_R0_R1_R2, ADD_R0_R1_R2, ADD_R0_R1_R2, ADD_R0_R1_R2, ADD_R0_R1_R2,
                        ADD_R0_R1_R2, ADD_R0_R1_R2, ADD_R0_R1_R2});
  run(1);
  EXPECT_EQ(timing.fetch_stall_cycles(), 24u);
  run(7);
  EXPECT_EQ(timing.fetch_stall_cycles(), 24u);
  EXPECT_EQ(timing.icache().hits(), 7u);
  run(1);
  EXPECT_EQ(timing.icache().misses(), 2u);
  EXPECT_EQ(timing.cycles(), 9u + 2 * 24u);
}

TEST_F(Timing, LoopHitsOnItsSecondIteration) {
  // loop: subs r0, r0, #1; bne loop, twice: the first iteration misses once
  // (both instructions are in one line), the second hits throughout.
  // Cycles: 1 + 3 (taken) + 1 + 1 (not taken) and one fill.
  memory.program(CODE, {0xe2500001u, 0x1afffffdu});
  core.set_reg(0, 2);
  EXPECT_EQ(run(4), (Cycles{1, 3, 1, 1}));
  EXPECT_EQ(timing.icache().misses(), 1u);
  EXPECT_EQ(timing.icache().hits(), 3u);
  EXPECT_EQ(timing.cycles(), 6u + 24u);
}

TEST_F(Timing, InstructionCacheOffFetchesEveryInstructionFromMemory) {
  // CP15 c1's I bit clear: each fetch is a single access (TimingParams::uncached_fetch_cycles).
  cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() & ~Cp15::CONTROL_I);
  memory.program(CODE, {ADD_R0_R1_R2, ADD_R0_R1_R2});
  run(2);
  EXPECT_EQ(timing.fetch_stall_cycles(), 20u);
  EXPECT_EQ(timing.icache().misses() + timing.icache().hits(), 0u);
}

TEST_F(Timing, Cp15InvalidatesTheInstructionCache) {
  // mcr p15, 0, r0, c7, c5, 0: invalidate the instruction cache; the next
  // fetch, in the line fetched before, misses again.
  memory.program(CODE, {ADD_R0_R1_R2, 0xee070f15u, ADD_R0_R1_R2});  // add; mcr ...; add
  run(2);
  EXPECT_EQ(timing.icache().misses(), 1u);
  run(1);
  EXPECT_EQ(timing.icache().misses(), 2u);
}

TEST(InstructionCacheModel, SixtyFourWaysPerSetThenReplacement) {
  // 8 KB / (32-byte lines x 64 ways) = 4 sets: lines 128 bytes apart share a
  // set. 64 of them fit; the 65th replaces one (round-robin: the first).
  InstructionCache cache;
  EXPECT_EQ(InstructionCache::SETS, 4u);
  for (uint32_t i = 0; i < 64; ++i) EXPECT_FALSE(cache.access(i * 128, true));
  for (uint32_t i = 0; i < 64; ++i) EXPECT_TRUE(cache.access(i * 128, true));
  EXPECT_FALSE(cache.access(64 * 128, true));
  EXPECT_TRUE(cache.access(128, true));  // line 1 stays (the next victim)
  EXPECT_FALSE(cache.access(0, true));   // round-robin evicted line 0
  EXPECT_FALSE(cache.access(32, true));  // another set: still empty
}

// A memory whose bytes the core may read directly: TimedFetch grants the
// line of a fetch the instruction cache would hit again (ResidentLines).
class DirectMemory : public Memory {
 public:
  const uint8_t* code_line(uint32_t line) override {
    return uint64_t{line} + tessera::iss::ResidentLines::BYTES <= bytes.size() ? &bytes[line] : nullptr;
  }
};

// The counts of a run with resident lines granted and without: every
// figure must be the same, whatever changes the cache's answer between two
// steps (c7's invalidations, CP15's I bit by the program or from outside)
// and whatever writes the code.
struct Counts {
  uint64_t instructions, decodes, cycles, interlocks, stalls, hits, misses;
  uint32_t r0, pc;
  bool operator==(const Counts& o) const {
    return instructions == o.instructions && decodes == o.decodes && cycles == o.cycles && interlocks == o.interlocks &&
           stalls == o.stalls && hits == o.hits && misses == o.misses && r0 == o.r0 && pc == o.pc;
  }
};

// A core with ARM922T timing and CP15 on a memory of type MemoryType, the
// instruction cache on (round-robin if asked), stepped as the run loops do.
template <typename MemoryType>
struct TimedSystem {
  MemoryType memory;
  Arm922tTiming timing;
  TimedFetch<MemoryType> port{memory, &timing};
  ArmCore core{port};
  Cp15 cp15{core, &timing};
  explicit TimedSystem(bool round_robin = false) {
    core.set_coprocessors(&cp15);
    timing.attach(&cp15);
    cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() | Cp15::CONTROL_I | (round_robin ? Cp15::CONTROL_RR : 0));
  }
  void step() {
    core.step();
    timing.step(core.last_step());
  }
  Counts counts() const {
    return {core.instructions(),
            core.decodes(),
            timing.cycles(),
            timing.interlock_cycles(),
            timing.fetch_stall_cycles(),
            timing.icache().hits(),
            timing.icache().misses(),
            core.reg(0),
            core.reg(15)};
  }
};

template <typename MemoryType>
Counts run_with_disturbances() {
  TimedSystem<MemoryType> system;
  auto& memory = system.memory;
  auto& timing = system.timing;
  auto& core = system.core;
  auto& cp15 = system.cp15;
  constexpr uint32_t NOP = 0xe1a00000u;          // mov r0, r0
  constexpr uint32_t ADD_R0_1 = 0xe2800001u;     // add r0, r0, #1
  constexpr uint32_t ADDS_R0_1 = 0xe2900001u;    // adds r0, r0, #1 (the same count, another decoding)
  constexpr uint32_t MCR_IC_LINE = 0xee075f35u;  // mcr p15, 0, r5, c7, c5, 1: invalidate the line at r5
  memory.program(CODE, {0xe3a00000u, ADD_R0_1, NOP, NOP, NOP, NOP, NOP, NOP,  // mov r0, #0; loop: add
                        0xe3500b01u, MCR_IC_LINE, 0x1afffff5u,                // cmp r0, #1024; mcr; bne loop
                        0xeafffffeu});                                        // b . (the end)
  core.set_cpsr(SYS);
  core.set_reg(5, CODE + 0x20);
  core.set_reg(15, CODE);
  uint32_t random = 1;
  for (int i = 0; i < 12000; ++i) {
    random = random * 1103515245u + 12345u;
    if ((random >> 16) % 29 == 0) {
      switch ((random >> 8) % 5) {
        case 0: timing.invalidate_instruction_cache(); break;
        case 1: timing.invalidate_instruction_line(CODE); break;
        case 2: cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() ^ Cp15::CONTROL_I); break;
        case 3: memory.program(CODE + 4, {(random >> 4) & 1 ? ADDS_R0_1 : ADD_R0_1}); break;
        default: cp15.mcr(15, 0, 7, 5, 0, true, 0); break;  // c7 from outside the program
      }
    }
    system.step();
  }
  return system.counts();
}

// A chain of branches through more lines of one set than it has ways, so
// that fills evict lines the port has granted: each line evicted must be
// fetched through the port again (a miss), not read from its old grant;
// and every line after the cache is invalidated.
template <typename MemoryType>
Counts run_through_evictions(bool round_robin) {
  TimedSystem<MemoryType> system(round_robin);
  auto& memory = system.memory;
  auto& timing = system.timing;
  auto& core = system.core;
  // Line k (k = 0 .. 69, 128 bytes apart: all in set 0): add r0, r0, #1,
  // then b to line k + 1; the last branches back to line 0. Lines 0 .. 3
  // also run a short loop of their own, so they hit while granted.
  constexpr unsigned LINES = InstructionCache::WAYS + 6;
  constexpr uint32_t ADD_R0_1 = 0xe2800001u;
  const auto branch = [](uint32_t from, uint32_t to) { return 0xea000000u | (((to - (from + 8)) >> 2) & 0x00ffffffu); };
  for (uint32_t k = 0; k < LINES; ++k) {
    const uint32_t at = CODE + 128 * k;
    const uint32_t next = k + 1 < LINES ? at + 128 : CODE;
    if (k < 4)  // subs r1, r1, #1; bne at + 4 (r1 = 3 each time: mov r1, #3 first)
      memory.program(at, {0xe3a01003u, ADD_R0_1, 0xe2511001u, (branch(at + 12, at + 4) & 0x0fffffffu) | 0x10000000u,
                          branch(at + 16, next)});
    else
      memory.program(at, {ADD_R0_1, branch(at + 4, next)});
  }
  core.set_cpsr(SYS);
  core.set_reg(15, CODE);
  for (int i = 0; i < 20000; ++i) {
    // Now and then the whole cache invalidated, with more lines granted
    // than the table keeps a list of (ResidentLines::revoke_all).
    if (i % 997 == 500) timing.invalidate_instruction_cache();
    system.step();
  }
  return system.counts();
}

TEST(ResidentLines, EvictedLinesAreFetchedAgain) {
  for (bool round_robin : {false, true}) {
    const Counts granted = run_through_evictions<DirectMemory>(round_robin);
    const Counts fetched = run_through_evictions<Memory>(round_robin);
    EXPECT_TRUE(granted == fetched) << (round_robin ? "round-robin" : "pseudo-random");
    EXPECT_GT(granted.misses, 1000u);  // lines were evicted and fetched again
    EXPECT_GT(granted.hits, 1000u);    // and granted lines hit in between
  }
}

TEST(ResidentLines, ChangeNoCount) {
  const Counts granted = run_with_disturbances<DirectMemory>();
  const Counts fetched = run_with_disturbances<Memory>();
  EXPECT_TRUE(granted == fetched);
  EXPECT_EQ(granted.r0, 1024u);  // the loop ran to its end
  EXPECT_GT(granted.misses, 100u);
  EXPECT_GT(granted.decodes, 20u);  // the code was written, and decoded again
}

}  // namespace
