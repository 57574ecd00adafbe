// The SoC launcher of ARM executables (tools/soc_sim/launch/iss_launcher.cpp) charges
// the host exactly the timing layer's cycles: for the test programs, the
// cycles it passes to compute() plus the issue cycle the host charges for
// each word it reads or writes (LDM and STM are one read_words or
// write_words) equal what Arm922tTiming counts for the
// same program on the bare machine, less the instruction cache's fill
// stalls; those are the host's own instruction-side bus reads instead
// (HostCore::fetch), one per miss of the bare machine's instruction cache.
// (Instruction cache on, data memory without wait states: the same
// instruction cycles; the host adds its data cache's and bus's stalls on
// top.) The image is loaded by debug writes, which charge nothing. The
// timing rules themselves are checked on hand-computed sequences in
// test_iss_timing.cpp; this checks the accounting around them.
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "config/config.h"
#include "host/host_core.h"
#include "host/iss/arm922t_timing.h"
#include "host/iss/bare_machine.h"
#include "host/iss/cp15.h"
#include "host/iss/elf_image.h"
#include "host/recording_core.h"
#include "host/recording_host.h"
#include "launch/iss_launcher.h"

namespace {

using tessera::iss::Arm922tTiming;
using tessera::iss::ArmCore;
using tessera::iss::Cp15;
using tessera::test::issue_cycles;
using tessera::test::RecordingCore;
using tessera::test::RecordingHost;

std::string g_arm_elf, g_thumb_elf;

struct BareFigures {
  uint64_t cycles_without_fills;
  uint64_t fills;
};

// The timing layer's figures for the program on the bare machine.
BareFigures bare_figures(const std::string& path) {
  tessera::iss::BareMachine machine;
  Arm922tTiming timing;
  tessera::iss::TimedFetch port(machine, &timing);
  ArmCore core(port);
  Cp15 cp15(core, &timing);
  core.set_coprocessors(&cp15);
  timing.attach(&cp15);
  cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() | Cp15::CONTROL_I);
  machine.load(tessera::iss::read_elf(path), core);
  for (int i = 0; i < 50'000'000 && !machine.exited(); ++i) {
    core.step();
    timing.step(core.last_step());
  }
  EXPECT_TRUE(machine.exited()) << path;
  return {timing.cycles() - timing.fetch_stall_cycles(), timing.icache().misses()};
}

struct LauncherFigures {
  uint64_t cycles;
  uint64_t fetches;
};

// What the launcher charged the host for the program, and the fills it asked for.
// `instruction_limit` (0: none) makes the launcher run its loop with the
// checks that are off unless asked for (iss_launcher.cpp, `watched`).
LauncherFigures launcher_figures(const std::string& path, uint64_t instruction_limit = 0) {
  RecordingHost host(1u << 20);
  RecordingCore core(host, 1u << 20);  // fetches read the memory directly, as in the SoC
  tessera::AppEnvironment env;
  env.host = &host;
  env.memory_bytes = 1u << 20;
  tessera::Config config({{"test",
                           {tessera::param::integer("host.iss_instruction_limit", 0, 0, 1e18, "instructions",
                                                    "instructions after which a program is stopped")},
                           {}}});
  if (instruction_limit != 0) {
    config.set("host.iss_instruction_limit", instruction_limit, "test");
    env.config = &config;
  }
  EXPECT_EQ(tessera::run_elf_app(env, {core}, path), 0) << path;
  uint64_t computed = 0;
  for (int op = 0; op < static_cast<int>(tessera::Op::count_); ++op)
    computed += host.operations(static_cast<tessera::Op>(op));
  computed += host.measured_cycles();
  return {computed + issue_cycles(host), core.fetches};
}

TEST(IssAppTiming, ArmProgramIsChargedTheTimingLayersCycles) {
  const BareFigures expected = bare_figures(g_arm_elf);
  EXPECT_GT(expected.cycles_without_fills, 400'000u);
  EXPECT_GT(expected.fills, 50u);
  const LauncherFigures charged = launcher_figures(g_arm_elf);
  EXPECT_EQ(charged.cycles, expected.cycles_without_fills);
  EXPECT_EQ(charged.fetches, expected.fills);
}

TEST(IssAppTiming, ThumbProgramIsChargedTheTimingLayersCycles) {
  const BareFigures expected = bare_figures(g_thumb_elf);
  EXPECT_GT(expected.cycles_without_fills, 500'000u);
  EXPECT_GT(expected.fills, 50u);
  const LauncherFigures charged = launcher_figures(g_thumb_elf);
  EXPECT_EQ(charged.cycles, expected.cycles_without_fills);
  EXPECT_EQ(charged.fetches, expected.fills);
}

// The loop with the instruction limit's check (a limit the program stays
// below) charges the same cycles as the one without it.
TEST(IssAppTiming, CheckedLoopIsChargedTheSameCycles) {
  for (const std::string* path : {&g_arm_elf, &g_thumb_elf}) {
    const BareFigures expected = bare_figures(*path);
    const LauncherFigures charged = launcher_figures(*path, 1'000'000'000);
    EXPECT_EQ(charged.cycles, expected.cycles_without_fills) << *path;
    EXPECT_EQ(charged.fetches, expected.fills) << *path;
  }
}

// A limit the program reaches stops it with an error naming the limit.
TEST(IssAppTiming, CheckedLoopStopsAtTheLimit) {
  try {
    launcher_figures(g_arm_elf, 5000);
    FAIL() << "the program ran past host.iss_instruction_limit=5000";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("host.iss_instruction_limit=5000"), std::string::npos) << error.what();
  }
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s ARM.elf THUMB.elf\n", argv[0]);
    return 2;
  }
  g_arm_elf = argv[1];
  g_thumb_elf = argv[2];
  return RUN_ALL_TESTS();
}
