// C programs compiled by GCC for the ARM922T (ARM and Thumb state, soft
// float, newlib's memcpy/memset, libgcc's division) run on the ISS; their
// console output must equal the same source compiled natively and run on
// this machine. Also: what a malformed or misplaced ELF gets.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/iss/arm_core.h"
#include "host/iss/bare_machine.h"
#include "host/iss/elf_image.h"

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
  std::string output;
  FILE* pipe = popen(path.c_str(), "r");
  if (pipe == nullptr) return output;
  char chunk[256];
  size_t n;
  while ((n = fread(chunk, 1, sizeof chunk, pipe)) > 0) output.append(chunk, n);
  pclose(pipe);
  return output;
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
