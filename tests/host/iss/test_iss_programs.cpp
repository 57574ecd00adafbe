// C programs compiled by GCC for the ARM922T (ARM and Thumb state, soft
// float, newlib's memcpy/memset, libgcc's division) run on the ISS; their
// console output must equal the same source compiled natively and run on
// this machine. Also: what a malformed or misplaced ELF gets.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/iss/arm_core.h"
#include "host/iss/bare_machine.h"
#include "host/iss/elf_image.h"
#include "process/child_process.h"
#include "process/scratch_folder.h"

namespace {

using tessera::iss::ArmCore;
using tessera::iss::ElfError;

std::string g_arm_elf, g_thumb_elf, g_native;

struct IssRun {
  std::string console;
  uint32_t status;
  uint64_t instructions;
};

IssRun run_on_iss(const std::string& path) {
  tessera::iss::BareMachine machine;
  ArmCore core(machine);
  machine.load(tessera::iss::read_elf(path), core);
  EXPECT_TRUE(machine.run(core, 50'000'000))
      << path << ": no exit after " << core.instructions() << " instructions, pc " << core.reg(15);
  return {machine.console(), machine.status(), core.instructions()};
}

std::string run_natively(const std::string& path) {
  const tessera::test::ScratchFolder folder("tessera_iss_programs");
  tessera::test::ChildCommand command;
  command.argv = {path};
  command.stdout_file = folder.path() / "native.stdout";
  const tessera::test::ChildResult result = tessera::test::run_child(command);
  EXPECT_TRUE(result.started) << result.start_error;
  return result.out;
}

TEST(IssPrograms, ArmAndThumbBuildsPrintWhatTheNativeBuildPrints) {
  const std::string native = run_natively(g_native);
  ASSERT_GT(native.size(), 200u) << "the native run printed too little";
  for (const std::string& elf : {g_arm_elf, g_thumb_elf}) {
    const IssRun run = run_on_iss(elf);
    EXPECT_EQ(run.console, native) << elf;
    EXPECT_EQ(run.status, 0u) << elf;
    EXPECT_GT(run.instructions, 100'000u) << elf;
    std::printf("%s: %llu instructions\n", elf.c_str(), static_cast<unsigned long long>(run.instructions));
  }
}

std::string write_file(const std::string& name, const std::vector<uint8_t>& bytes) {
  std::string path = ::testing::TempDir() + name;
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

std::vector<uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_error(const std::string& path, const std::string& fragment) {
  try {
    tessera::iss::read_elf(path);
    ADD_FAILURE() << path << ": no error";
  } catch (const ElfError& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find(path), std::string::npos) << text;
    EXPECT_NE(text.find(fragment), std::string::npos) << text;
  }
}

TEST(IssPrograms, MalformedExecutablesAreClearErrorsNamingTheFile) {
  expect_error("/nonexistent/app.elf", "cannot open");
  expect_error(write_file("empty.elf", {}), "no ELF header");
  expect_error(g_native, "not a 32-bit ELF");  // this machine's own x86-64 executable
  std::vector<uint8_t> elf = read_file(g_arm_elf);
  ASSERT_GT(elf.size(), 52u);
  std::vector<uint8_t> truncated(elf.begin(), elf.begin() + 60);
  expect_error(write_file("truncated.elf", truncated), "outside the file");
  std::vector<uint8_t> big_endian = elf;
  big_endian[5] = 2;
  expect_error(write_file("big_endian.elf", big_endian), "not little-endian");
  std::vector<uint8_t> x86 = elf;
  x86[18] = 3;  // e_machine EM_386
  expect_error(write_file("x86.elf", x86), "machine 3, not ARM (40)");
  std::vector<uint8_t> entry = elf;
  entry[24] = entry[25] = entry[26] = 0xff;
  entry[27] = 0x7f;  // e_entry 0x7fffffff: in no segment
  expect_error(write_file("entry.elf", entry), "entry point 0x7fffffff is not in an executable segment");
}

// A minimal ARM executable: the ELF header, one program header per
// segment (address, file bytes, memory bytes; the first executable), the
// entry at the first segment's address. The file bytes are zeros.
struct Segment {
  uint32_t address, file_bytes, memory_bytes;
};
std::vector<uint8_t> make_elf(const std::vector<Segment>& segments) {
  const uint32_t headers = 52, data = headers + 32 * static_cast<uint32_t>(segments.size());
  uint32_t file_bytes = 0;
  for (const Segment& s : segments) file_bytes = std::max(file_bytes, s.file_bytes);
  std::vector<uint8_t> elf(data + file_bytes, 0);
  const auto put16 = [&](uint32_t at, uint32_t v) {
    elf[at] = static_cast<uint8_t>(v);
    elf[at + 1] = static_cast<uint8_t>(v >> 8);
  };
  const auto put32 = [&](uint32_t at, uint32_t v) {
    put16(at, v & 0xffff);
    put16(at + 2, v >> 16);
  };
  const uint8_t ident[] = {0x7f, 'E', 'L', 'F', 1, 1, 1};
  std::copy(std::begin(ident), std::end(ident), elf.begin());
  put16(16, 2);   // ET_EXEC
  put16(18, 40);  // EM_ARM
  put32(20, 1);
  put32(24, segments.front().address);  // e_entry
  put32(28, headers);                   // e_phoff
  put16(40, 52);
  put16(42, 32);
  put16(44, static_cast<uint32_t>(segments.size()));
  for (size_t i = 0; i < segments.size(); ++i) {
    const uint32_t at = headers + 32 * static_cast<uint32_t>(i);
    put32(at, 1);  // PT_LOAD
    put32(at + 4, data);
    put32(at + 8, segments[i].address);
    put32(at + 12, segments[i].address);
    put32(at + 16, segments[i].file_bytes);
    put32(at + 20, segments[i].memory_bytes);
    put32(at + 24, i == 0 ? 5 : 6);  // R+X, then R+W
  }
  return elf;
}

TEST(IssPrograms, WellFormedSegmentsAreRead) {
  const auto image =
      tessera::iss::read_elf(write_file("two_segments.elf", make_elf({{0x1000, 16, 64}, {0x2000, 8, 0x10000}})));
  ASSERT_EQ(image.segments.size(), 2u);
  EXPECT_EQ(image.segments[1].address, 0x2000u);
  EXPECT_EQ(image.segments[1].bytes.size(), 0x10000u);
  EXPECT_EQ(image.entry, 0x1000u);
}

// The limit is on the file's segments together, checked before
// anything is allocated (24 segments of 64 MiB each took 1.5 GB, more
// ended in std::bad_alloc with no file named).
TEST(IssPrograms, SegmentsTogetherLargerThanTheLimitAreRefusedBeforeAllocation) {
  const uint32_t mib = 1u << 20;
  expect_error(write_file("two_large.elf", make_elf({{0, 16, 40 * mib}, {64 * mib, 16, 40 * mib}})),
               "more than an executable for the SoC can (67108864)");
  std::vector<Segment> many;
  for (uint32_t i = 0; i < 60; ++i) many.push_back({i * 64 * mib, 16, 64 * mib});
  expect_error(write_file("many_large.elf", make_elf(many)), "more than an executable for the SoC can");
  // Exactly the limit is an executable still.
  EXPECT_NO_THROW(
      tessera::iss::read_elf(write_file("at_limit.elf", make_elf({{0, 16, 32 * mib}, {32 * mib, 16, 32 * mib}}))));
}

// Overlapping segments once left the ISS running one copy while
// memory and GDB showed another.
TEST(IssPrograms, OverlappingSegmentsAreRefusedNamingBoth) {
  expect_error(write_file("overlap.elf", make_elf({{0x1000, 16, 0x100}, {0x10f0, 16, 0x100}})),
               "segments 0 (0x00001000..0x00001100) and 1 (0x000010f0..0x000011f0) overlap");
  expect_error(write_file("inside.elf", make_elf({{0x1000, 16, 0x1000}, {0x0800, 16, 0x100}, {0x1800, 4, 4}})),
               "segments 0 (0x00001000..0x00002000) and 2 (0x00001800..0x00001804) overlap");
  // Touching is not overlapping.
  EXPECT_NO_THROW(tessera::iss::read_elf(write_file("adjacent.elf", make_elf({{0x1000, 16, 0x100}, {0x1100, 4, 4}}))));
}

// Console output without a newline, streamed (as iss_run prints it):
// handed on in pieces of at most 4 KiB while the program runs, the rest at
// the flush, never kept whole.
TEST(IssPrograms, StreamedConsoleOutputWithoutANewlineComesInBoundedPieces) {
  tessera::iss::BareMachine machine;
  ArmCore core(machine);
  const uint32_t program[] = {
      0xe3a0020f,  //       mov  r0, #0xf0000000  @ the console register
      0xe3a01078,  //       mov  r1, #'x'
      0xe3a02c27,  //       mov  r2, #0x2700
      0xe2822010,  //       add  r2, r2, #0x10    @ 10,000
      0xe5801000,  // 1:    str  r1, [r0]
      0xe2522001,  //       subs r2, r2, #1
      0x1afffffc,  //       bne  1b
      0xe3a01000,  //       mov  r1, #0
      0xe5801004,  //       str  r1, [r0, #4]     @ the exit register
  };
  ASSERT_TRUE(machine.debug_write(0, reinterpret_cast<const uint8_t*>(program), sizeof program));
  std::vector<size_t> pieces;
  size_t total = 0;
  machine.stream_console([&](const std::string& text) {
    pieces.push_back(text.size());
    total += text.size();
    EXPECT_EQ(text, std::string(text.size(), 'x'));
  });
  core.reset();
  core.set_reg(15, 0);
  EXPECT_TRUE(machine.run(core, 100'000));
  EXPECT_GT(total, 10'000u - tessera::iss::BareMachine::CONSOLE_CHUNK);
  for (size_t piece : pieces) EXPECT_LE(piece, tessera::iss::BareMachine::CONSOLE_CHUNK);
  EXPECT_LT(machine.console().size(), tessera::iss::BareMachine::CONSOLE_CHUNK);
  machine.flush_console();
  EXPECT_EQ(total, 10'000u);
  EXPECT_EQ(machine.console(), "");
}

TEST(IssPrograms, AnExecutableOutsideMemoryIsAClearError) {
  const auto image = tessera::iss::read_elf(g_arm_elf);
  try {
    image.check_fits(0x1000, 0x1000, "system memory");
    FAIL() << "no error";
  } catch (const ElfError& error) {
    EXPECT_NE(std::string(error.what()).find("falls outside system memory"), std::string::npos) << error.what();
  }
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s ARM.elf THUMB.elf NATIVE\n", argv[0]);
    return 2;
  }
  g_arm_elf = argv[1];
  g_thumb_elf = argv[2];
  g_native = argv[3];
  return RUN_ALL_TESTS();
}
