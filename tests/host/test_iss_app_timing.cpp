// The SoC launcher of ARM executables (sw_driver/apps/iss_app.cpp) charges
// the host exactly the timing layer's cycles: for the test programs, the
// cycles it passes to compute() plus the one issue cycle the host charges
// for each of its reads and writes (after the boot loader's copy) equal what
// Arm922tTiming counts for the same program on the bare machine (instruction
// cache on, data memory without wait states: the same instruction cycles and
// fetch stalls; the host adds its data cache's and bus's stalls on top).
// The timing rules themselves are checked on hand-computed sequences in
// test_iss_timing.cpp; this checks the accounting around them.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "apps/iss_app.h"
#include "host/iss/arm922t_timing.h"
#include "host/iss/bare_machine.h"
#include "host/iss/cp15.h"
#include "host/iss/elf_image.h"
#include "support/recording_host.h"

namespace {

using tessera::iss::Arm922tTiming;
using tessera::iss::ArmCore;
using tessera::iss::Cp15;
using tessera::test::RecordingHost;

std::string g_arm_elf, g_thumb_elf;

// The timing layer's cycles for the program on the bare machine.
uint64_t bare_cycles(const std::string& path) {
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
  return timing.cycles();
}

// What the launcher charged the host for the program (the boot loader's
// copy of the image, one access per word or tail byte, left out).
uint64_t launcher_cycles(const std::string& path) {
  RecordingHost host(1u << 20);
  tessera::AppEnvironment env;
  env.host = &host;
  env.memory_bytes = 1u << 20;
  EXPECT_EQ(tessera::run_elf_app(env, path), 0) << path;
  size_t loader_accesses = 0;
  for (const auto& segment : tessera::iss::read_elf(path).segments)
    loader_accesses += segment.bytes.size() / 4 + segment.bytes.size() % 4;
  size_t accesses = 0;
  for (const auto& access : host.log())
    if (access.kind == RecordingHost::Access::Kind::read || access.kind == RecordingHost::Access::Kind::write)
      ++accesses;
  EXPECT_GE(accesses, loader_accesses);
  uint64_t computed = 0;
  for (int op = 0; op < static_cast<int>(tessera::Op::count_); ++op)
    computed += host.operations(static_cast<tessera::Op>(op));
  return computed + (accesses - loader_accesses);
}

TEST(IssAppTiming, ArmProgramIsChargedTheTimingLayersCycles) {
  const uint64_t expected = bare_cycles(g_arm_elf);
  EXPECT_GT(expected, 400'000u);
  EXPECT_EQ(launcher_cycles(g_arm_elf), expected);
}

TEST(IssAppTiming, ThumbProgramIsChargedTheTimingLayersCycles) {
  const uint64_t expected = bare_cycles(g_thumb_elf);
  EXPECT_GT(expected, 500'000u);
  EXPECT_EQ(launcher_cycles(g_thumb_elf), expected);
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
