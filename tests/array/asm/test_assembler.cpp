// The assembler and the disassembler (tlm/array/asm): encodings checked by
// hand against the bit layout of ap_isa.h, every static check with the line
// it names, products and parentheses in expressions, .rept blocks against
// the same program written out by hand, and the disassembler's round trip
// over every opcode.
#include "array/asm/assembler.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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
  expect_error("main:\nmov r0, [3]]\nhalt\n", 2, "expected +, - or * in the address of operand a of mov, not ']'");
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

TEST(Expressions, ProductsBindTighterThanSums) {
  const Program program = assemble_text(
      ".var buf 8 @ 16\n"
      ".const A 2 + 3 * 4\n"
      ".const B 2 * 3 + 4\n"
      ".const C 10 - 2 * 3\n"
      ".const D -2 * 3\n"
      ".const E 2 * -3\n"
      ".const F 3 * 4 * 5 - 0x10 * 2\n"
      ".const G buf * 2 + 1\n"
      ".const H A * B\n"
      ".const I 46340 * 46340\n"
      ".const J -2147483647 * 1\n");
  EXPECT_EQ(program.constants.at("A"), 14);
  EXPECT_EQ(program.constants.at("B"), 10);
  EXPECT_EQ(program.constants.at("C"), 4);
  EXPECT_EQ(program.constants.at("D"), -6);
  EXPECT_EQ(program.constants.at("E"), -6);
  EXPECT_EQ(program.constants.at("F"), 28);
  // A variable stands for its address, a number like any other.
  EXPECT_EQ(program.constants.at("G"), 33);
  EXPECT_EQ(program.constants.at("H"), 140);
  EXPECT_EQ(program.constants.at("I"), 2147395600);
  EXPECT_EQ(program.constants.at("J"), -2147483647);
}

TEST(Expressions, Parentheses) {
  const Program program = assemble_text(
      ".const P (2 + 3) * 4\n"
      ".const Q 2 * (10 - (3 + 4))\n"
      ".const R -(2 + 3)\n"
      ".const S 10 - (4 - 1)\n"
      ".const T ((7))\n");
  EXPECT_EQ(program.constants.at("P"), 20);
  EXPECT_EQ(program.constants.at("Q"), 6);
  EXPECT_EQ(program.constants.at("R"), -5);
  EXPECT_EQ(program.constants.at("S"), 7);
  EXPECT_EQ(program.constants.at("T"), 7);
}

TEST(Expressions, ScaledAddressPlusLoopVariable) {
  const std::string header =
      ".const X 2\n"
      ".var pad 3\n"
      ".var buf 256\n"
      "main:\n"
      "loop v, 35, 1\n";
  const Program scaled = assemble_text(header +
                                       "  mov r0, [buf + 36 * X + v]\n"
                                       "  mov [(buf + 1) * 2 + v], r1\n"
                                       "  mov [buf - (1 - v) + 1], r2\n"
                                       "endloop\nhalt\n");
  const Program by_hand = assemble_text(header +
                                        "  mov r0, [75 + v]\n"
                                        "  mov [8 + v], r1\n"
                                        "  mov [3 + v], r2\n"
                                        "endloop\nhalt\n");
  EXPECT_EQ(scaled.words, by_hand.words);
  const Instruction first = decode(scaled.words[1]).instruction;
  EXPECT_EQ(first.a.value, 3 + 36 * 2);
  EXPECT_EQ(first.a.loop, 1);
}

TEST(Errors, Products) {
  expect_error("main:\nloop v, 3, 1\nmov r0, [2 * v]\n", 3,
               "loop variable 'v' cannot be scaled: the AC adds it to the address of operand a of mov as it is");
  expect_error("main:\nloop v, 3, 1\nmov r0, [10 + v * 2]\n", 3, "loop variable 'v' cannot be scaled");
  expect_error("main:\nloop v, 3, 1\nmov r0, [2 * (v + 1)]\n", 3, "loop variable 'v' cannot be scaled");
  expect_error("main:\nloop v, 3, 1\nmov r0, [9 - (v + 1)]\n", 3, "loop variable 'v' subtracted");
  expect_error("main:\nloop v, 3, 1\n.const C 2 * v\n", 3, "only added to CMEM addresses");
  expect_error(".const A 65536 * 65536\n", 1,
               "the product 65536 * 65536 in the value of constant 'A' is beyond 2147483647 in magnitude");
  expect_error(".const A 46341 * 46341\n", 1, "is beyond 2147483647 in magnitude");
  expect_error(".const A -65536 * 65536\n", 1, "the product -65536 * 65536");
  // The factors of a product may be large sums; the check must not overflow.
  expect_error(".const A (2147483647 + 2147483647) * 2147483647\n", 1,
               "the product 4294967294 * 2147483647 in the value of constant 'A' is beyond");
  expect_error(".const A 2 * 1073741824 * 0\n", 1, "the product 2 * 1073741824");
  expect_error(".const A 2 *\n", 1, "ends with an operator");
  expect_error(".const A * 2\n", 1, "expected a number, a name or '(' in the value of constant 'A', not '*'");
  expect_error(".const A 2 3\n", 1, "expected +, - or * in the value of constant 'A', not '3'");
  expect_error(".const A (2 + 3\n", 1, "'(' without a matching ')' in the value of constant 'A'");
  expect_error(".const A 2 + 3)\n", 1, "')' without a matching '(' in the value of constant 'A'");
  expect_error(".const A ()\n", 1, "expected a number, a name or '(' in the value of constant 'A', not ')'");
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
  // A result pair overlapping a source pair by one register (the low pass
  // would write the high byte the second pass reads); the same pair is fine.
  expect_error("main:\nadd16 r1, r2, r4\nhalt\n", 2, "add16: the result pair d:d+1 overlaps a source pair");
  expect_error("main:\nsub16 r3, r0, r2\nhalt\n", 2, "sub16: the result pair d:d+1 overlaps a source pair");
  expect_error("main:\nmov16 r4, r3\nhalt\n", 2, "mov16: the result pair d:d+1 overlaps a source pair");
  EXPECT_EQ(words_of("add16 r2, r2, r2").size(), 2u);
  EXPECT_EQ(words_of("cmp16 r1, r2").size(), 2u);  // nothing written: sources may overlap
}

// The 16-bit operations: registers only, every operand a pair within the
// configured registers; endloopany closes a loop like endloop.
TEST(Errors, RegisterPairsAndTheWiredOrLoop) {
  expect_error("main:\nadd16 r6, r0, r7\nhalt\n", 2, "operand b of add16 covers r7..r8, beyond r7");
  expect_error("main:\nmov16 r7, r0\nhalt\n", 2, "operand d of mov16 covers r7..r8, beyond r7");
  expect_error("main:\ncmp16 r15, r0\nhalt\n", 2, "operand a of cmp16 covers r15..r16, beyond r15", {16, 4096, 4096});
  expect_error("main:\nadd16 r0, [2], r4\nhalt\n", 2, "operand a of add16 must be a register");
  expect_error("main:\nendloopany c\nhalt\n", 2, "endloopany without a loop");
  expect_error("main:\nloop y, 1, 1\nendloopany\nhalt\n", 3, "endloopany takes 1 operand (condition), not 0");
  expect_error("main:\nloop y, 1, 1\nendloopany q\nhalt\n", 3, "unknown condition 'q'");
  // add16 opcode 0x23, registers d = 0, a = 2, b = 4; endloopany 0x27 with
  // the condition in a (nz = 3).
  const std::vector<uint64_t> words = words_of("add16 r0, r2, r4\nloop y, 3, 1\nendloopany nz");
  EXPECT_EQ(words[0], 0x0000'4000'2000'0023u);
  EXPECT_EQ(words[2], 0x0000'0000'3000'0027u);
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

// The words of `with_rept` must be those of `by_hand`, the same program
// written out.
void expect_same_words(const std::string& with_rept, const std::string& by_hand) {
  SCOPED_TRACE(with_rept);
  const Program repeated = assemble_text(with_rept);
  const Program written = assemble_text(by_hand);
  EXPECT_FALSE(repeated.words.empty());
  EXPECT_EQ(repeated.words, written.words);
  EXPECT_EQ(repeated.entries, written.entries);
  EXPECT_EQ(repeated.variables, written.variables);
  EXPECT_EQ(repeated.constants, written.constants);
}

// Issue 14: input that must not knock the assembler over.
TEST(Limits, ParenthesesNestAtMost64Deep) {
  auto nested = [](size_t depth) {
    return ".const a " + std::string(depth, '(') + "1" + std::string(depth, ')') + "\nmain:\nhalt\n";
  };
  EXPECT_EQ(assemble_text(nested(64)).constants.at("a"), 1);
  expect_error(nested(65), 1, "parentheses nested more than 64 deep in the value of constant 'a'");
  // Used to overflow the stack.
  expect_error(nested(200000), 1, "parentheses nested more than 64 deep");
}

TEST(Limits, NulBytesAndControlCharactersAreNamed) {
  expect_error(std::string("main:\n  halt\0\n", 13), 2, "a NUL byte in column 7: not a text file");
  expect_error(std::string("main: ; \0\nhalt\n", 15), 1, "a NUL byte in column 9");
  expect_error("main:\n  ha\x01lt\n", 2, "unexpected character 0x01");
  expect_error("main:\n  halt \xff\n", 2, "unexpected character 0xFF");
}

TEST(Files, SizeIsLimited) {
  ASSERT_EQ(MAX_SOURCE_BYTES, 64u * 1024 * 1024);
  const std::string path = ::testing::TempDir() + "tessera_asm_big.s";
  std::ofstream(path) << "main:\nhalt\n";
  std::filesystem::resize_file(path, MAX_SOURCE_BYTES + 1);  // sparse: refused by its size, unread
  try {
    assemble_file(path);
    ADD_FAILURE() << "assembled a file over the limit";
  } catch (const AsmError& error) {
    EXPECT_EQ(std::string(error.what()), path + ": 67108865 bytes, more than the limit of 67108864");
  }
  std::filesystem::remove(path);
  // A device has no size; /dev/zero is refused at its first byte.
  if (std::filesystem::exists("/dev/zero")) {
    try {
      assemble_file("/dev/zero");
      ADD_FAILURE() << "assembled /dev/zero";
    } catch (const AsmError& error) {
      EXPECT_EQ(std::string(error.what()), "/dev/zero:1: a NUL byte in column 1: not a text file");
    }
  }
}

TEST(Rept, CountsUp) {
  expect_same_words(
      ".var buf 64\n"
      "main:\n"
      ".rept i, 0, 3\n"
      "  mov [buf + 2 * i], r0\n"
      "  add r1, [buf + 2 * i + 1], r1\n"
      ".endr\n"
      "halt\n",
      ".var buf 64\n"
      "main:\n"
      "mov [0], r0\nadd r1, [1], r1\n"
      "mov [2], r0\nadd r1, [3], r1\n"
      "mov [4], r0\nadd r1, [5], r1\n"
      "mov [6], r0\nadd r1, [7], r1\n"
      "halt\n");
}

TEST(Rept, CountsDownAndThroughZero) {
  expect_same_words(
      "main:\n"
      ".rept i, 3, 0\n"
      "  mov [10 * i], r0\n"
      ".endr\n"
      ".rept k, -1, 1\n"
      "  mov [5 + k], r1\n"
      ".endr\n"
      ".rept one, 7, 7\n"
      "  mov [one], r2\n"
      ".endr\n"
      "halt\n",
      "main:\n"
      "mov [30], r0\nmov [20], r0\nmov [10], r0\nmov [0], r0\n"
      "mov [4], r1\nmov [5], r1\nmov [6], r1\n"
      "mov [7], r2\n"
      "halt\n");
}

TEST(Rept, BoundsAreConstantExpressions) {
  expect_same_words(
      ".const N 3\n"
      ".var v 4 @ 100\n"
      "main:\n"
      ".rept i, N - 1, 2 * N - 2\n"
      "  mov [v + i], r0\n"
      ".endr\n"
      "halt\n",
      ".const N 3\n"
      ".var v 4 @ 100\n"
      "main:\n"
      "mov [102], r0\nmov [103], r0\nmov [104], r0\n"
      "halt\n");
}

TEST(Rept, NestsThreeDeepAndInnerBlocksSeeOuterNames) {
  // The inner bound uses the outer name: x runs 0..1 when y = 0, 0..2 when y = 1.
  const std::string with_rept =
      ".var tile 64 @ 0\n"
      "main:\n"
      ".rept y, 0, 1\n"
      "  .rept x, 0, y + 1\n"
      "    .rept c, 2, 0\n"
      "      mov [tile + 16 * y + 4 * x + c], r0\n"
      "    .endr\n"
      "  .endr\n"
      ".endr\n"
      "halt\n";
  std::string by_hand = ".var tile 64 @ 0\nmain:\n";
  for (const int address : {2, 1, 0, 6, 5, 4, 18, 17, 16, 22, 21, 20, 26, 25, 24})
    by_hand += "mov [" + std::to_string(address) + "], r0\n";
  by_hand += "halt\n";
  expect_same_words(with_rept, by_hand);
  // Every word keeps the line it came from.
  const Program program = assemble_text(with_rept);
  std::vector<unsigned> lines(15, 6);
  lines.push_back(10);
  EXPECT_EQ(program.lines, lines);
}

TEST(Rept, LoopsAndStagesInsideBodies) {
  // Sibling blocks reuse k; a loop opened in one block and closed in a
  // later one is checked on the expanded lines like any other.
  expect_same_words(
      "main:\n"
      ".stage depth\n"
      "loop v, 7, 1\n"
      ".rept k, 0, 2\n"
      "  add [16 * k + v], [64 + 16 * k + v], r1\n"
      ".endr\n"
      "endloop\n"
      ".rept k, 0, 1\n"
      "  .stage colour\n"
      "  loop w, 3, 1\n"
      "    mov [128 + 8 * k + w], r2\n"
      "  endloop\n"
      ".endr\n"
      ".rept k, 0, 0\n"
      "  loop u, 1, 1\n"
      ".endr\n"
      "mov [u], r3\n"
      ".rept k, 0, 0\n"
      "  endloop\n"
      ".endr\n"
      "halt\n",
      "main:\n"
      ".stage depth\n"
      "loop v, 7, 1\n"
      "  add [v], [64 + v], r1\n"
      "  add [16 + v], [80 + v], r1\n"
      "  add [32 + v], [96 + v], r1\n"
      "endloop\n"
      ".stage colour\n"
      "loop w, 3, 1\n  mov [128 + w], r2\nendloop\n"
      "loop w, 3, 1\n  mov [136 + w], r2\nendloop\n"
      "loop u, 1, 1\n"
      "mov [u], r3\n"
      "endloop\n"
      "halt\n");
}

TEST(Rept, NameIsFreeAfterEndrAndNeverAConstant) {
  const Program program = assemble_text(
      "main:\n"
      ".rept k, 0, 1\n"
      "  nop\n"
      ".endr\n"
      "halt\n"
      ".const k 9\n");
  EXPECT_EQ(program.constants, (std::map<std::string, int>{{"k", 9}}));
  EXPECT_EQ(program.words.size(), 3u);
}

TEST(Rept, EmptyBodyCostsNothing) {
  EXPECT_EQ(words_of(".rept x, 0, 2147483647\n.endr\n.rept y, -2147483647, 2147483647\n.endr").size(), 1u);
}

TEST(Rept, DisassemblyAssemblesToTheSameWords) {
  const Program program = assemble_text(
      ".var buf 32\n"
      "main:\n"
      ".rept i, 0, 3\n"
      "  loop v, 3, 1\n"
      "    add [buf + 4 * i + v], [buf + 16 + v], r0\n"
      "  endloop\n"
      ".endr\n"
      "halt\n");
  EXPECT_EQ(assemble(disassemble(program), "again.s", {}).words, program.words);
}

TEST(Errors, ReptNamesTheLineAndTheRepetition) {
  try {
    assemble_text("main:\n.rept x, 0, 3\nnop\nfoo\n.endr\nhalt\n");
    ADD_FAILURE() << "no error";
  } catch (const AsmError& error) {
    EXPECT_EQ(std::string(error.what()), "test.s:4: (in .rept x = 0) unknown mnemonic 'foo'");
    EXPECT_EQ(error.line(), 4u);
  }
  // Only the last repetition reaches beyond CMEM.
  expect_error("main:\n.rept x, 0, 3\nmov r0, [4093 + x]\n.endr\nhalt\n", 3,
               "(in .rept x = 3) operand a of mov: CMEM address 4096 reaches byte 4096");
  expect_error("main:\n.rept a, 0, 1\n.rept b, 0, 1\nmov r0, [4094 + a + b]\n.endr\n.endr\nhalt\n", 4,
               "(in .rept a = 1, b = 1) operand a of mov: CMEM address 4096");
  expect_error("main:\n.rept x, 0, 3\nnop\n.endr\nhalt\n", 3, "(in .rept x = 3) the program is longer than the 3 words",
               {8, 4096, 3});
  // The loop checks apply to the expanded lines.
  expect_error("main:\n.rept x, 0, 1\nloop v, 3, 1\n.endr\n", 3,
               "(in .rept x = 1) duplicate name 'v': already the variable of the enclosing loop (line 3)");
  expect_error("main:\nloop v, 1, 1\n.rept x, 0, 1\nendloop\n.endr\nhalt\n", 4,
               "(in .rept x = 1) endloop without a loop");
  // A syntax error is the line's whatever the repetition: it is found once, when the line is read.
  expect_error("main:\n.rept x, 0, 3\nnop $\n.endr\n", 3, "unexpected character '$'");
}

TEST(Errors, ReptStructure) {
  expect_error("main:\n.endr\nhalt\n", 2, ".endr without a .rept");
  expect_error("main:\n.rept x, 0, 1\nnop\n.endr x\nhalt\n", 4, "nothing may follow .endr on its line");
  expect_error("main:\n.rept x, 0, 1\nnop\n", 2, ".rept is not closed by .endr before the end of the file");
  expect_error("main:\n.rept x, 0, 1\n.rept y, 0, 1\nnop\n.endr\n", 2, ".rept is not closed by .endr");
  // The innermost open block is the one named.
  expect_error("main:\n.rept x, 0, 1\n.rept y, 0, 1\n.rept z, 0, 1\n.endr\nnop\n", 3, ".rept is not closed by .endr");
  expect_error("main:\n.rept x, 0\n", 2, ".rept takes 3 operands (name, first, last), not 2");
  expect_error("main:\n.rept x 0 1\n", 2, ".rept takes 3 operands (name, first, last), not 1");
  expect_error("main:\n.rept\n", 2, ".rept takes 3 operands (name, first, last), not 0");
  expect_error("main:\n.rept 3, 0, 1\n", 2, ".rept: expected the name of the .rept counter");
  expect_error("main:\n.rept x y, 0, 1\n", 2, ".rept: expected the name of the .rept counter, not 'x'");
  expect_error("main:\n.rept r1, 0, 1\n", 2, "'r1' is a register and cannot name a .rept counter");
  expect_error("main:\n.rept x, 0, y\n", 2, "undefined name 'y' in the last value of .rept 'x'");
  expect_error("main:\n.rept x, , 1\n", 2, "expected the first value of .rept 'x'");
  expect_error("main:\nloop v, 3, 1\n.rept x, v, 1\n", 3,
               "loop variable 'v' in the first value of .rept 'x': loop variables are only added");
  expect_error("main:\n.rept x, 0, 2147483647 + 1\n", 2, "has last value 2147483648, beyond 2147483647");
}

TEST(Errors, ReptNames) {
  expect_error(".const N 4\nmain:\n.rept N, 0, 1\n", 3, "duplicate name 'N': already a constant (line 1)");
  expect_error("main:\nloop v, 1, 1\n.rept v, 0, 1\n", 3, "already the variable of the enclosing loop (line 2)");
  expect_error("main:\n.rept x, 0, 1\n.rept x, 0, 1\n.endr\n.endr\nhalt\n", 3,
               "(in .rept x = 0) duplicate name 'x': already the counter of the enclosing .rept (line 2)");
  expect_error("main:\n.rept x, 0, 1\nloop x, 1, 1\nendloop\n.endr\nhalt\n", 3,
               "already the counter of the enclosing .rept (line 2)");
  expect_error("main:\n.rept x, 0, 1\nnop\n.endr\nmov r0, [x]\nhalt\n", 5, "undefined name 'x'");
  expect_error("main:\n.rept x, 0, 1\ninner:\n.endr\n", 3,
               "(in .rept x = 0) label 'inner' inside the body of .rept 'x' (line 2): it would be defined once per "
               "repetition");
  expect_error(
      ".rept x, 0, 1\n.const C x\n.endr\n", 2,
      "(in .rept x = 0) .const inside the body of .rept 'x' (line 1): it would be defined once per repetition");
  expect_error(".rept x, 0, 1\n.var v 1\n.endr\n", 2, ".var inside the body of .rept 'x' (line 1)");
}

TEST(Errors, ReptRunaway) {
  expect_error("main:\n.rept x, 0, 2000000\n.stage fill\n.endr\n", 2,
               ".rept 'x' would replay more than 1000000 lines in all");
  // The lines of the inner blocks count as well: 2 lines a pass of a.
  expect_error("main:\n.rept a, 0, 999999\n.rept b, 0, 999999\n.endr\n.endr\nhalt\n", 2,
               ".rept 'a' would replay more than 1000000 lines in all");
}

// Conditional assembly: .if on a constant expression, .else, .endif, the
// constants the caller defines, and the program they select against the
// same program written out by hand.
TEST(Conditional, SelectsTheBranchOfTheCondition) {
  const std::string source =
      ".const WIDE 1\n"
      "main:\n"
      ".if WIDE\n"
      "  add r0, r1, r2\n"
      "  adc r3, r4, r5\n"
      ".else\n"
      "  add r0, r1, r2\n"
      ".endif\n"
      ".if WIDE - 1\n"
      "  nop\n"
      ".endif\n"
      "  halt\n";
  expect_same_words(source, ".const WIDE 1\nmain:\n  add r0, r1, r2\n  adc r3, r4, r5\n  halt\n");
  const Program program = assemble_text(source);
  // Each word's line is its source line.
  EXPECT_EQ(program.lines, (std::vector<unsigned>{4, 5, 12}));
}

TEST(Conditional, NestsAndSkipsWhatItDoesNotTake) {
  // A skipped branch is not assembled: its names need not exist, its
  // labels and constants are not defined, its nested .if not evaluated.
  const std::string source =
      ".const A 0\n"
      ".const B 2\n"
      ".if A\n"
      ".const ONLY_A 1\n"
      "skipped:\n"
      ".if UNDEFINED\n"
      "  mov r0, [NOWHERE]\n"
      ".else\n"
      "  bogus instruction\n"
      ".endif\n"
      ".else\n"
      "main:\n"
      ".if B\n"
      ".rept k, 0, 1\n"
      ".if k\n"
      "  mov r1, r2\n"
      ".else\n"
      "  mov r3, r4\n"
      ".endif\n"
      ".endr\n"
      ".endif\n"
      ".endif\n"
      "  halt\n";
  expect_same_words(source, ".const A 0\n.const B 2\nmain:\n  mov r3, r4\n  mov r1, r2\n  halt\n");
  const Program program = assemble_text(source);
  EXPECT_EQ(program.entries.count("skipped"), 0u);
  EXPECT_EQ(program.constants.count("ONLY_A"), 0u);
  // Inside a loop body, an .if is assembly time only.
  expect_same_words(".const N 0\nmain:\nloop i, 3, 1\n.if N\nnop\n.endif\nmov [i], r0\nendloop\nhalt\n",
                    "main:\nloop i, 3, 1\nmov [i], r0\nendloop\nhalt\n.const N 0\n");
}

TEST(Conditional, TheCallerDefinesConstants) {
  const std::string source =
      "main:\n"
      ".if TABLE\n"
      "  lut r0, r0\n"
      ".else\n"
      "  add r0, r0, r1\n"
      ".endif\n"
      "  halt\n";
  const Program table = assemble(source, "test.s", {}, {{"TABLE", 1}});
  const Program computed = assemble(source, "test.s", {}, {{"TABLE", 0}});
  EXPECT_EQ(table.words, words_of("lut r0, r0"));
  EXPECT_EQ(computed.words, words_of("add r0, r0, r1"));
  // A defined constant is a constant of the program, like a .const.
  EXPECT_EQ(table.constants.at("TABLE"), 1);
  EXPECT_EQ(computed.constants.at("TABLE"), 0);
  // Undefined, it is named, with where a definition would come from.
  expect_error(source, 2, "undefined name 'TABLE' in the condition of .if");
  expect_error(source, 2, "ap_asm -D NAME=VALUE");
  // The source cannot define it again.
  try {
    assemble(".const TABLE 2\n", "test.s", {}, {{"TABLE", 1}});
    ADD_FAILURE() << "no error";
  } catch (const AsmError& error) {
    EXPECT_EQ(std::string(error.what()),
              "test.s:1: duplicate name 'TABLE': already a constant (defined when assembling)");
  }
  for (const std::string bad : {"", "3D", "r2", "a-b", ".x"})
    EXPECT_THROW(assemble("main:\nhalt\n", "test.s", {}, {{bad, 1}}), std::invalid_argument) << bad;
}

TEST(Errors, ConditionalStructure) {
  expect_error("main:\n.endif\nhalt\n", 2, ".endif without an .if");
  expect_error("main:\n.else\nhalt\n", 2, ".else without an .if");
  expect_error(".if 1\nmain:\nhalt\n", 1, ".if is not closed by .endif before the end of the file");
  // The innermost open .if is the one named.
  expect_error(".if 1\n.if 0\n.endif\n.if 1\nmain:\nhalt\n", 4, ".if is not closed by .endif");
  expect_error(".if 1\n.else\n.else\n.endif\n", 3, ".else after an .else: the .if at line 1 has one already");
  expect_error(".if 1\n.endif 1\n", 2, "nothing may follow .endif on its line");
  expect_error(".if 1\n.else x\n.endif\n", 2, "nothing may follow .else on its line");
  expect_error(".if\n.endif\n", 1, "expected the condition of .if");
  expect_error(".if X\n.endif\n", 1, "undefined name 'X' in the condition of .if");
  expect_error("main:\nloop v, 3, 1\n.if v\n.endif\nendloop\nhalt\n", 3, "loop variable 'v' in the condition of .if");
  // Skipped lines are still read: a character the language has not is named.
  expect_error(".if 0\nnop $\n.endif\n", 2, "unexpected character '$'");
  // An .if and its .endif are in the same .rept body, or both outside it.
  expect_error("main:\n.rept k, 0, 1\n.if k\nnop\n.endr\nhalt\n", 3,
               "(in .rept k = 0) .if is not closed by .endif inside the body of .rept 'k' (line 2)");
  expect_error("main:\n.if 1\n.rept k, 0, 1\n.endif\n.endr\nhalt\n", 4,
               "(in .rept k = 0) .endif inside the body of .rept 'k' (line 3) belongs to the .if at line 2");
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
  div r0, r1, r3
  div [5], [6], r2
  nadd r1, left, r2
  nadd r0, down, r7
  nadds [12], left, [13]
  nadcs r1, right, r2
  lut r0, r2
  lut [8], [10]
  zsend r0, r4
  zsend [16], [20]
  add16 r0, r2, r4
  add16 r2, r2, r2
  sub16 r6, r0, r6
  cmp16 r1, r2
  mov16 r4, r6
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
  loop z, 9, 1
    sub r0, r0, r1
    mand nz
  endloopany nz
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
