// ap_asm (tools/ap_asm) as a user runs it: exit statuses, messages that
// name file:line, and the files it writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "array/isa/ap_isa.h"
#include "fixtures/soc_sim_test.h"
#include "process/child_process.h"

namespace {

namespace fs = std::filesystem;
using tessera::test::contains;
using tessera::test::describe;
using tessera::test::read_file;

std::string g_ap_asm;

class ApAsm : public tessera::test::ScratchFolderTest {
 protected:
  // ap_asm in m_dir, its stdout and stderr in files there.
  tessera::test::ChildResult run(const std::vector<std::string>& args) {
    tessera::test::ChildCommand command;
    command.argv = {g_ap_asm};
    command.argv.insert(command.argv.end(), args.begin(), args.end());
    command.working_dir = m_dir;
    command.stdout_file = m_dir / "ap_asm.stdout";
    command.stderr_to = tessera::test::ChildCommand::Stderr::file;
    command.stderr_file = m_dir / "ap_asm.stderr";
    return tessera::test::run_child(command);
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(m_dir / name) << text; }
};

const char* const GOOD = R"(.var v 4
main:
  mov r0, [v]
  halt
)";

TEST_F(ApAsm, AssemblesAndWritesTheImage) {
  write("good.s", GOOD);
  const auto result = run({"good.s", "-o", "good.bin"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_EQ(result.out, "good.s: 2 words, 1 entry (main), 1 variables, 0 constants\n");
  const std::string image = read_file(m_dir / "good.bin");
  ASSERT_EQ(image.size(), 16u);
  // mov r0, [0]: opcode 0x0a, a in CMEM (bit 10), little-endian; then halt.
  EXPECT_EQ(image, std::string("\x0a\x04\0\0\0\0\0\0\x01\0\0\0\0\0\0\0", 16));
}

TEST_F(ApAsm, Disassembles) {
  write("good.s", GOOD);
  const auto result = run({"--disassemble", "good.s"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_TRUE(contains(result.out, "main:\n  mov r0, [0]\n  halt\n")) << result.out;
}

TEST_F(ApAsm, EmitsCppAndHeader) {
  write("good.s", GOOD);
  const auto result = run({"--emit-cpp", "good", "good.s", "-o", "good.cpp", "--header", "good.h"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_TRUE(contains(read_file(m_dir / "good.cpp"), "const Program& good() {"));
  EXPECT_TRUE(contains(read_file(m_dir / "good.h"), "const Program& good();"));
}

TEST_F(ApAsm, PrintsTheIsaTable) {
  const auto result = run({"--isa-table"});
  ASSERT_EQ(result.status, 0) << describe(result);
  for (const auto& op : tessera::ap::all_ops())
    EXPECT_TRUE(contains(result.out, "| `" + std::string(op.mnemonic) + "` |")) << op.mnemonic;
}

TEST_F(ApAsm, AssemblyErrorNamesFileAndLine) {
  write("bad.s", "main:\n  nop\n  frob r1\n  halt\n");
  const auto result = run({"bad.s"});
  EXPECT_EQ(result.status, 1) << describe(result);
  EXPECT_EQ(result.err, "ap_asm: bad.s:3: unknown mnemonic 'frob'\n");
  EXPECT_FALSE(fs::exists(m_dir / "bad.bin"));
}

TEST_F(ApAsm, LimitsComeFromTheOptions) {
  write("regs.s", "main:\n  mov r5, r0\n  halt\n");
  EXPECT_EQ(run({"regs.s"}).status, 0);
  const auto result = run({"--registers", "4", "regs.s"});
  EXPECT_EQ(result.status, 1) << describe(result);
  EXPECT_TRUE(contains(result.err, "regs.s:2: register r5 is beyond r3")) << result.err;
}

TEST_F(ApAsm, DefinesConstantsForIf) {
  write("variant.s", "main:\n.if TABLE\n  nop\n.endif\n  halt\n");
  auto result = run({"-D", "TABLE=1", "variant.s"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_EQ(result.out, "variant.s: 2 words, 1 entry (main), 0 variables, 1 constants\n");
  result = run({"--define", "TABLE=0x0", "variant.s"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_EQ(result.out, "variant.s: 1 words, 1 entry (main), 0 variables, 1 constants\n");
  result = run({"variant.s"});
  EXPECT_EQ(result.status, 1) << describe(result);
  EXPECT_TRUE(contains(result.err, "variant.s:2: undefined name 'TABLE' in the condition of .if")) << result.err;
  for (const std::string bad : {"TABLE", "TABLE=", "=1", "TABLE=one", "TABLE=99999999999", "3D=1"}) {
    result = run({"-D", bad, "variant.s"});
    EXPECT_EQ(result.status, 1) << bad << describe(result);
    EXPECT_FALSE(result.err.empty()) << bad;
  }
  result = run({"-D", "TABLE=1", "-D", "TABLE=0", "variant.s"});
  EXPECT_TRUE(contains(result.err, "-D TABLE is given twice")) << result.err;
}

TEST_F(ApAsm, RejectsBadOptions) {
  write("good.s", GOOD);
  const std::vector<std::vector<std::string>> cases = {
      {"--bogus", "good.s"},
      {"--registers", "17", "good.s"},
      {"--cmem-bytes", "0", "good.s"},
      {"--program-words", "many", "good.s"},
      {},
      {"--disassemble", "--isa-table"},
      {"--emit-cpp", "good", "good.s"},
      {"--emit-cpp", "3rd", "good.s", "-o", "x.cpp"},
      {"--header", "x.h", "good.s"},
      {"--isa-table", "good.s"},
      {"missing.s"},
  };
  for (const auto& args : cases) {
    std::string line;
    for (const auto& arg : args) line += arg + " ";
    const auto result = run(args);
    EXPECT_NE(result.status, 0) << line << describe(result);
    EXPECT_FALSE(result.err.empty()) << line;
  }
  EXPECT_TRUE(contains(run({"missing.s"}).err, "missing.s: cannot read the file"));
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc >= 2) g_ap_asm = fs::absolute(argv[1]).string();
  return RUN_ALL_TESTS();
}
