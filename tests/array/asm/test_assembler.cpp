// The assembler and the disassembler (tlm/array/asm): encodings checked by
// hand against the bit layout of ap_isa.h, every static check with the line
// it names, and the disassembler's round trip over every opcode.
#include "array/asm/assembler.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "array/asm/disassembler.h"
#include "array/isa/ap_isa.h"

namespace tessera::ap {
namespace {

Program assemble_text(const std::string& source, const AsmLimits& limits = {}) {
  return assemble(source, "test.s", limits);
}

// Assembles `source`, which must fail at `line` with a message containing
// `part`; the message is "test.s:<line>: <problem>".
void expect_error(const std::string& source, unsigned line, const std::string& part, const AsmLimits& limits = {}) {
  SCOPED_TRACE(source);
  try {
    assemble_text(source, limits);
    ADD_FAILURE() << "assembled without error; expected '" << part << "' at line " << line;
  } catch (const AsmError& error) {
    EXPECT_EQ(error.line(), line) << error.what();
    EXPECT_EQ(error.file(), "test.s");
    const std::string prefix = "test.s:" + std::to_string(line) + ": ";
    EXPECT_EQ(std::string(error.what()).rfind(prefix, 0), 0u) << error.what();
    EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
  }
}

// The words of one entry `main` holding `body` and then halt.
std::vector<uint64_t> words_of(const std::string& body, const AsmLimits& limits = {}) {
  return assemble_text("main:\n" + body + "\nhalt\n", limits).words;
}

// Expected words are written out from the layout in ap_isa.h: opcode [5:0],
// stage [8:6], CMEM flags of d, a, b at 9, 10, 11, fields d, a, b at 12, 28
// and 44; a CMEM field is the address [13:0] and the loop selector [15:14].
TEST(Encoding, RegisterForms) {
  // add: opcode 2, d = 1 << 12, a = 2 << 28, b = 3 << 44.
  EXPECT_EQ(words_of("add r1, r2, r3")[0], 0x0000'3000'2000'1002u);
  // mul: opcode 0x12, d = 3, a = 0, b = 2.
  EXPECT_EQ(words_of("mul r3, r0, r2")[0], 0x0000'2000'0000'3012u);
  // halt is opcode 1 and nothing else.
  EXPECT_EQ(words_of("nop")[1], 0x1u);
}

TEST(Encoding, CmemForms) {
  // mov: opcode 0x0a, d in CMEM (bit 9) at 0x123, a = r5.
  EXPECT_EQ(words_of("mov [0x123], r5")[0], 0x0000'0000'5012'320au);
  // nget: opcode 0x14, a in CMEM (bit 10) at 7, d = r2, direction up = 2 in b.
  EXPECT_EQ(words_of("nget r2, up, [7]")[0], 0x0000'2000'7000'2414u);
  // mand: opcode 0x19, condition nc = 1 in a.
  EXPECT_EQ(words_of("mand nc")[0], 0x0000'0000'1000'0019u);
}

TEST(Encoding, LoopsAndStages) {
  const Program program = assemble_text(
      "main:\n"
      ".stage depth\n"
      "loop y, 10, 1\n"
      "  add [100 + y], r0, [200]\n"
      "endloop\n"
      "halt\n");
  ASSERT_EQ(program.words.size(), 4u);
  // loop: opcode 0x1b, stage depth 3 << 6, level 0 in d, start 10 in a, step 1 in b.
  EXPECT_EQ(program.words[0], 0x0000'1000'a000'00dbu);
  // add: opcode 2 | 3 << 6; d and b in CMEM (bits 9 and 11); d = 100 with
  // loop selector 1 (level 0) = 0x4064; b = 200.
  EXPECT_EQ(program.words[1], 0x000c'8000'0406'4ac2u);
  EXPECT_EQ(program.words[2], 0x1cu | 3u << 6);
  EXPECT_EQ(program.words[3], 0x01u | 3u << 6);
  EXPECT_EQ(program.lines, (std::vector<unsigned>{3, 4, 5, 6}));
}

TEST(Encoding, NestedLoopVariables) {
  const Program program = assemble_text(
      "main:\n"
      "loop x, 1, 1\n"
      " loop y, 2, 1\n"
      "  loop z, 3, 1\n"
      "   mov [5 + z], [y + 6]\n"
      "   mov [x], r0\n"
      "  endloop\n"
      " endloop\n"
      "endloop\n"
      "halt\n");
  // Level 2 loop: d = 2.
  EXPECT_EQ(program.words[2], 0x0000'1000'3000'201bu);
  // mov: opcode 0x0a, d and a in CMEM; d = 5 | 3 << 14 = 0xc005, a = 6 | 2 << 14 = 0x8006.
  EXPECT_EQ(program.words[3], 0x0000'0800'6c00'560au);
  // d = 0 | 1 << 14 = 0x4000.
  EXPECT_EQ(program.words[4], 0x0000'0000'0400'020au);
}

TEST(Names, ConstantsAndVariables) {
  const Program program = assemble_text(
      ".const N 4\n"
      ".const BACK N - 6 + 0x10  ; 14\n"
      ".const NEG -3\n"
      ".var fixed 4 @ 2\n"
      ".var first N\n"
      ".var second 1\n"
      ".var far N + N @ 0x100\n"
      "main:\n"
      "mov r0, [second + BACK + NEG]\n"
      "halt\n");
  EXPECT_EQ(program.constants.at("N"), 4);
  EXPECT_EQ(program.constants.at("BACK"), 14);
  EXPECT_EQ(program.constants.at("NEG"), -3);
  EXPECT_EQ(program.variables.at("fixed"), (Variable{2, 4}));
  // The next free place steps over `fixed` (bytes 2..5).
  EXPECT_EQ(program.variables.at("first"), (Variable{6, 4}));
  EXPECT_EQ(program.variables.at("second"), (Variable{10, 1}));
  EXPECT_EQ(program.variables.at("far"), (Variable{0x100, 8}));
  EXPECT_EQ(decode(program.words[0]).instruction.a.value, 10 + 14 - 3);
}

TEST(Names, EntriesAndStages) {
  const Program program = assemble_text(
      "; two entry points; the first runs on into the second\n"
      "first:\n"
      ".stage fill\n"
      "  mset\n"
      "second:\n"
      "also_second:\n"
      "  mclr   // stage back to other at a label\n"
      ".stage transfer\n"
      "  halt\n"
      "third:\n"
      "  halt\n");
  EXPECT_EQ(program.entries,
            (std::map<std::string, unsigned>{{"first", 0}, {"second", 1}, {"also_second", 1}, {"third", 3}}));
  EXPECT_EQ(decode(program.words[0]).instruction.stage, Stage::fill);
  EXPECT_EQ(decode(program.words[1]).instruction.stage, Stage::other);
  EXPECT_EQ(decode(program.words[2]).instruction.stage, Stage::transfer);
  EXPECT_EQ(decode(program.words[3]).instruction.stage, Stage::other);
  EXPECT_EQ(program.lines, (std::vector<unsigned>{4, 7, 9, 11}));
  EXPECT_EQ(program.source_name, "test.s");
}

TEST(Names, LoopVariableNamesAreReusedAfterTheirLoop) {
  const Program program = assemble_text(
      "main:\n"
      "loop i0, 3, 1\n"
      "  mov [i0], r0\n"
      "endloop\n"
      "loop i0, 5, 2\n"
      "  mov [10 + i0], r0\n"
      "endloop\n"
      "halt\n");
  EXPECT_EQ(program.words.size(), 7u);
}

TEST(Errors, Syntax) {
  expect_error("main:\nhalt\nfoo r1\n", 3, "unknown mnemonic 'foo'");
  expect_error(".bar 3\n", 1, "unknown directive '.bar'");
  expect_error("\n.stage bogus\n", 2, "unknown stage 'bogus'");
  expect_error("main:\nmand zz\nhalt\n", 2, "unknown condition 'zz'");
  expect_error("main:\nnget r0, north, r1\nhalt\n", 2, "unknown direction 'north'");
  expect_error("main: halt\n", 1, "nothing may follow the label 'main'");
  expect_error(".const X 0xg\n", 1, "'0xg' is not a number");
  expect_error(".const X 3 $ 4\n", 1, "unexpected character '$'");
  expect_error(".const X 3 +\n", 1, "ends with an operator");
  expect_error(".const X 99999999999\n", 1, "beyond");
}

TEST(Errors, Operands) {
  expect_error("main:\nadd r1, r2\nhalt\n", 2, "add takes 3 operands (d, a, b), not 2");
  expect_error("main:\nhalt r1\n", 2, "halt takes 0 operands, not 1");
  expect_error("main:\nadd r1, , r2\nhalt\n", 2, "operand a of add is missing");
  expect_error("main:\nmul [0], r0, r1\nhalt\n", 2, "operand d of mul must be a register");
  expect_error("main:\nmulm r0, [3], [5]\nhalt\n", 2, "operand d of mulm must be a CMEM address");
  expect_error("main:\nadd 5, r1, r2\nhalt\n", 2, "operand d of add must be a register r0..r15 or a CMEM address");
  expect_error("main:\nmov r0, [3]]\nhalt\n", 2, "expected + or -");
}

TEST(Errors, UndefinedNames) {
  expect_error("main:\nmov r0, [nothing]\nhalt\n", 2, "undefined name 'nothing'");
  expect_error("main:\nmov r0, [main]\nhalt\n", 2, "'main' is a label");
  expect_error("main:\nloop y, 2, 1\nendloop\nmov r0, [y]\nhalt\n", 4, "loop variable 'y' used outside its loop");
  expect_error(".const A UNDEFINED\n", 1, "undefined name 'UNDEFINED'");
  expect_error(".const A r3\n", 1, "register r3");
}

TEST(Errors, DuplicateNames) {
  expect_error(".const A 1\n.const A 2\n", 2, "duplicate name 'A': already a constant (line 1)");
  expect_error(".var v 1\n.const v 2\n", 2, "duplicate name 'v': already a variable (line 1)");
  expect_error("main:\nhalt\nmain:\nhalt\n", 3, "duplicate label 'main' (first at line 1)");
  expect_error("main:\nloop y, 2, 1\nloop y, 2, 1\n", 3, "already the variable of the enclosing loop (line 2)");
  expect_error(".var k 4\nmain:\nloop k, 2, 1\n", 3, "duplicate name 'k': already a variable");
  expect_error(".const r2 1\n", 1, "'r2' is a register");
}

TEST(Errors, LoopVariablesOnlyAddToAddresses) {
  expect_error("main:\nloop y, 3, 1\nmov r0, [10 - y]\n", 3, "subtracted");
  expect_error("main:\nloop y, 3, 1\nloop z, 3, 1\nmov r0, [y + z]\n", 4, "two loop variables");
  expect_error("main:\nloop y, 3, 1\nloop z, y, 1\n", 3, "only added to CMEM addresses");
  expect_error("main:\nloop y, 3, 1\n.const C y\n", 3, "only added to CMEM addresses");
}

TEST(Errors, Registers) {
  expect_error("main:\nmov r8, r0\nhalt\n", 2, "register r8 is beyond r7, the last of 8 registers");
  expect_error("main:\nmov r0, r16\nhalt\n", 2, "'r16' is not a register (r0..r15)", {16, 4096, 4096});
  expect_error("main:\nmov r0, r123456789012\nhalt\n", 2, "'r123456789012' is not a register");
  expect_error("main:\nmul r6, r0, r1\nhalt\n", 2, "operand d of mul covers r6..r8, beyond r7");
  expect_error("main:\nmul r0, r7, r3\nhalt\n", 2, "operand a of mul covers r7..r8, beyond r7");
  expect_error("main:\nmov r3, r0\nhalt\n", 2, "beyond r2, the last of 3 registers", {3, 4096, 4096});
}

TEST(Errors, CmemAddresses) {
  expect_error("main:\nmov r0, [4096]\nhalt\n", 2, "reaches byte 4096, beyond the 4096 bytes of CMEM");
  expect_error("main:\nmov r0, [0 - 1]\nhalt\n", 2, "CMEM address -1 is negative");
  // The loop variable's largest value is its start.
  expect_error("main:\nloop y, 10, 3\nmov [4086 + y], r0\n", 3, "4086 + y (up to 10) reaches byte 4096");
  expect_error("main:\nmulm [4094], [0], [2]\nhalt\n", 2, "and the 2 bytes after it reaches byte 4096");
  expect_error("main:\nmov r0, [100]\nhalt\n", 2, "beyond the 100 bytes", {8, 100, 4096});
  expect_error(".var v 5 @ 4092\n", 1, "does not fit the 4096 bytes of CMEM");
  expect_error(".var v 0\n", 1, "has size 0");
  expect_error(".var a 4\n.var b 2 @ 3\n", 2, "overlaps variable 'a' (bytes 0..3)");
  expect_error(".var a 4 @ -1\n", 1, "negative address");
}

TEST(Errors, LoopStructure) {
  expect_error("main:\nloop a, 1, 1\nloop b, 1, 1\nloop c, 1, 1\nloop d, 1, 1\n", 5,
               "nests 4 deep: the AC runs at most 3 nested loops");
  expect_error("main:\nendloop\nhalt\n", 2, "endloop without a loop");
  expect_error("main:\nloop y, 1, 1\ninner:\n", 3, "label 'inner' inside the body of loop 'y' (line 2)");
  expect_error("main:\nloop y, 1, 1\nnop\n", 2, "loop 'y' is not closed by endloop before the end of the file");
  expect_error("main:\nloop y, 1, 1\nhalt\n", 3, "halt inside the body of loop 'y'");
  expect_error("main:\nloop y, 16384, 1\n", 2, "starts at 16384, not 0..16383");
  expect_error("main:\nloop y, -1, 1\n", 2, "starts at -1");
  expect_error("main:\nloop y, 1, 0\n", 2, "has step 0, not 1..16383");
  expect_error("main:\nloop 3, 1, 1\n", 2, "expected the name of the loop variable");
}

TEST(Errors, EntriesAndHalt) {
  expect_error("main:\nnop\n\n", 1, "entry 'main' does not reach a halt before the end of the file");
  expect_error("main:\nhalt\nlast:\n", 3, "entry 'last' does not reach a halt");
  expect_error("nop\nmain:\nhalt\n", 1, "instruction before the first label");
  expect_error("main:\nhalt\nnop\n", 3, "instruction after halt with no label before it");
}

TEST(Errors, DecoderRefusals) {
  // The product r0..r2 overlaps the 16-bit source r1..r2.
  expect_error("main:\nmul r0, r1, r2\nhalt\n", 2, "mul: the product d..d+2 overlaps a source");
  expect_error("main:\nmulm [10], [20], [12]\nhalt\n", 2, "mulm: the product d..d+2 overlaps a source");
}

TEST(Limits, ProgramWords) {
  EXPECT_EQ(words_of("nop\nnop", {8, 4096, 3}).size(), 3u);
  expect_error("main:\nnop\nnop\nnop\nhalt\n", 5, "longer than the 3 words of program memory", {8, 4096, 3});
}

TEST(Limits, LargestArray) {
  const AsmLimits largest{MAX_REGISTERS, 1u << ADDRESS_BITS, 4096};
  const std::vector<uint64_t> words = words_of("mul r13, r0, r12\nmov [16383], r15", largest);
  EXPECT_EQ(decode(words[1]).instruction.d.value, 16383);
  EXPECT_THROW(assemble_text("", {0, 4096, 4096}), std::invalid_argument);
  EXPECT_THROW(assemble_text("", {17, 4096, 4096}), std::invalid_argument);
  EXPECT_THROW(assemble_text("", {8, 16385, 4096}), std::invalid_argument);
  EXPECT_THROW(assemble_text("", {8, 4096, 0}), std::invalid_argument);
}

TEST(Files, UnreadableFileIsNamed) {
  try {
    assemble_file("/nonexistent/program.s");
    ADD_FAILURE() << "no error";
  } catch (const AsmError& error) {
    EXPECT_EQ(std::string(error.what()), "/nonexistent/program.s: cannot read the file");
    EXPECT_EQ(error.line(), 0u);
  }
  try {
    assemble_file("/");
    ADD_FAILURE() << "no error";
  } catch (const AsmError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("/: cannot read the file", 0), 0u) << error.what();
  }
}

// Every opcode, each data operand as a register and as an address where
// the forms allow, with stages, nested loops and two entries.
const char* const EVERY_OPCODE = R"(
.const K 3
.var buffer 64
main:
  nop
.stage setup
  add r1, r2, r3
  add [1], r2, [2]
  adc r1, [K], r3
  sub [buffer + 4], [buffer + 5], [buffer + 6]
  sbc r0, r0, r0
  and r1, r2, [9]
  or [9], r2, r3
  xor r4, r5, r6
.stage fill
  not r1, [3]
  mov [3], [4]
  shl r1, r1
  shr [7], r7
  asr r2, r3
  rol [1], [1]
  ror r0, [0]
  cmp r1, [2]
  cmpc [2], r1
  mul r0, r3, r5
  mulm [20], [10], [12]
second:
.stage transfer
  nget r1, left, r2
  nget [3], right, [4]
  nget r0, up, [1]
  nget [2], down, r3
  getm r3
  getm [30]
  mset
  mclr
  mmov c
  mand ls
  mor hi
.stage shade
  loop y, 30, 3
    add [y], [1 + y], r2
    loop x, 2, 1
      mov [40 + x], [y]
      loop w, 1, 1
        mulm [100 + w], [200 + x], [300 + y]
      endloop
    endloop
  endloop
  halt
)";

TEST(Disassembler, RoundTripOfEveryOpcode) {
  const Program program = assemble_text(EVERY_OPCODE);
  std::set<Opcode> seen;
  for (const uint64_t word : program.words) seen.insert(decode(word).instruction.opcode);
  EXPECT_EQ(seen.size(), OPCODE_COUNT) << "the test program must use every opcode";

  const std::string text = disassemble(program);
  const Program again = assemble(text, "again.s", {});
  EXPECT_EQ(again.words, program.words) << text;
  EXPECT_EQ(again.entries, program.entries);
  EXPECT_EQ(again.variables, program.variables);
  EXPECT_EQ(again.constants, program.constants);
  // And the disassembly of the disassembly is the same text.
  const std::string text_again = disassemble(again);
  EXPECT_EQ(text_again.substr(text_again.find('\n')), text.substr(text.find('\n')));
}

TEST(Disassembler, Format) {
  const Program program = assemble_text(
      ".var v 2 @ 8\n"
      "main:\n"
      ".stage depth\n"
      "loop y, 4, 2\n"
      "  add [v + 1 + y], [v + y], r1\n"
      "endloop\n"
      "halt\n");
  EXPECT_EQ(disassemble(program),
            "; test.s, disassembled\n"
            ".var v 2 @ 8\n"
            "\n"
            "main:\n"
            "  .stage depth\n"
            "  loop i0, 4, 2\n"
            "    add [9 + i0], [8 + i0], r1\n"
            "  endloop\n"
            "  halt\n");
}

TEST(Disassembler, WordTheDecoderRefusesBecomesAComment) {
  Program program;
  program.source_name = "image";
  program.words = {0x3f};
  program.entries = {{"main", 0}};
  EXPECT_NE(disassemble(program).find("; word 0 0x000000000000003f: unknown opcode 63"), std::string::npos)
      << disassemble(program);
}

}  // namespace
}  // namespace tessera::ap
