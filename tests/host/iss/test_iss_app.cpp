// The SoC launcher of ARM executables (tools/soc_sim/launch/iss_launcher.cpp) over a
// recording host: what the program's instruction fetches see when another
// bus master writes its code, and when its console output is printed.
// (Its cycle accounting is test_iss_app_timing's; in the SoC with the real
// DMA, soc_sim_iss_dma_code.)
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/recording_core.h"
#include "host/recording_host.h"
#include "launch/iss_launcher.h"

namespace {

using tessera::test::RecordingCore;
using tessera::test::RecordingHost;

std::string g_dma_code_elf, g_console_elf, g_long_line_elf;

constexpr uint32_t MEMORY_BYTES = 1u << 20;
constexpr uint32_t DMA_STATUS = 0x52000124;  // channel 0's STATUS (contract/dma/dma_regs.def)
constexpr uint32_t STATUS_DONE = 2;

// std::cout into a string while it lives.
class CapturedOutput {
 public:
  CapturedOutput() : m_saved(std::cout.rdbuf(m_text.rdbuf())) {}
  ~CapturedOutput() { std::cout.rdbuf(m_saved); }
  CapturedOutput(const CapturedOutput&) = delete;
  CapturedOutput& operator=(const CapturedOutput&) = delete;
  std::string text() const { return m_text.str(); }

 private:
  std::ostringstream m_text;
  std::streambuf* m_saved;
};

// The program has the DMA copy `mov r0, #2` over a function it
// has run, waits for it, invalidates the instruction cache and calls the
// function again. Here the "DMA" is the recording host writing its memory
// when the program reads the channel's status: a write by a master other
// than the CPU, which the launcher does not see happen. Its exit status is
// 0 when the second call ran the new instruction (11 when it ran the old).
int run_dma_code(bool direct) {
  RecordingHost host(MEMORY_BYTES);
  RecordingCore core(host, direct ? MEMORY_BYTES : 0);
  unsigned status_reads = 0;
  uint64_t asked_before = 0;
  host.read_register = [&](uint32_t address) -> uint32_t {
    EXPECT_EQ(address, DMA_STATUS);
    if (status_reads++ == 0) {
      // The channel's source and destination, as the program wrote them.
      uint32_t source = 0, destination = 0;
      for (const auto& access : host.log()) {
        if (access.kind != RecordingHost::Access::Kind::write) continue;
        if (access.address == 0x52000104) source = access.value;
        if (access.address == 0x52000108) destination = access.value;
      }
      EXPECT_NE(destination, 0u);
      std::memcpy(host.memory(destination, 4), host.memory(source, 4), 4);
      // The memory withdraws its direct access meanwhile: the launcher must ask again.
      asked_before = core.direct_memory_asked;
      core.invalidate_direct_memory();
    }
    return STATUS_DONE;
  };
  tessera::AppEnvironment env;
  env.host = &host;
  env.memory_bytes = MEMORY_BYTES;
  const int status = tessera::run_elf_app(env, {core}, g_dma_code_elf);
  EXPECT_EQ(status_reads, 1u);
  if (direct) {
    EXPECT_GE(asked_before, 1u) << "fetches did not use direct memory";
    EXPECT_EQ(core.direct_memory_asked, asked_before + 1) << "asked again once after the invalidation";
  }
  return status;
}

TEST(IssApp, CodeWrittenByAnotherBusMasterIsExecuted) {
  EXPECT_EQ(run_dma_code(true), 0) << "fetches through direct memory (the SoC's DMI)";
  EXPECT_EQ(run_dma_code(false), 0) << "fetches by debug access (no DMI)";
}

// Console output without a newline was once kept until one came,
// without bound. The program writes 10,000 bytes without a newline and then
// reads a device register: by then all but the last part (less than the
// launcher's 4,096-byte chunk) must have been printed, and all of it at the end.
TEST(IssApp, ConsoleOutputWithoutANewlineIsPrintedInBoundedChunks) {
  RecordingHost host(MEMORY_BYTES);
  RecordingCore core(host, MEMORY_BYTES);
  std::string printed_at_mark = "unread";
  int status = -1;
  std::string printed;
  {
    CapturedOutput output;
    host.read_register = [&](uint32_t address) -> uint32_t {
      EXPECT_EQ(address, DMA_STATUS);
      printed_at_mark = output.text();
      return 0;
    };
    tessera::AppEnvironment env;
    env.host = &host;
    env.memory_bytes = MEMORY_BYTES;
    status = tessera::run_elf_app(env, {core}, g_console_elf);
    printed = output.text();
  }
  EXPECT_EQ(status, 0);
  EXPECT_EQ(printed.size(), 10'000u);
  EXPECT_TRUE(printed == std::string(10'000, 'x'));
  EXPECT_GT(printed_at_mark.size(), 10'000u - 4096u);
  EXPECT_TRUE(printed_at_mark == std::string(printed_at_mark.size(), 'x'));
}

// A line without an end written to the driver's warnings file (100,000
// bytes): handed on in pieces of at most 64 KiB while the program runs,
// not kept whole (once kept without bound until a newline came).
TEST(IssApp, ASemihostingLineWithoutAnEndIsHandedOnInBoundedPieces) {
  RecordingHost host(MEMORY_BYTES);
  RecordingCore core(host, MEMORY_BYTES);
  std::vector<size_t> pieces;
  tessera::AppEnvironment env;
  env.host = &host;
  env.memory_bytes = MEMORY_BYTES;
  env.warn = [&](const std::string& source, const std::string& message) {
    EXPECT_EQ(source, "driver");
    pieces.push_back(message.size());
  };
  EXPECT_EQ(tessera::run_elf_app(env, {core}, g_long_line_elf), 0) << "SYS_WRITE wrote all 100,000 bytes";
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0], 65'536u);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s DMA_CODE.elf CONSOLE.elf LONG_LINE.elf\n", argv[0]);
    return 2;
  }
  g_dma_code_elf = argv[1];
  g_console_elf = argv[2];
  g_long_line_elf = argv[3];
  return RUN_ALL_TESTS();
}
