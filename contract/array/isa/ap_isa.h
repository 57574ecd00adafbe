// The array processor's instruction set (ap_isa.def, ap_cond.def,
// ap_stage.def) as C++: opcodes, the 64-bit instruction word, and its
// decoded form. Everything that encodes or decodes an instruction (the AC,
// the assembler, the disassembler, the RTL adapter, the tests) goes through
// encode() and decode() here.
//
// The instruction word, least significant bit first:
//
//   [5:0]   opcode            (ap_isa.def)
//   [8:6]   stage             (ap_stage.def)
//   [9]     d is a CMEM address (else a register)
//   [10]    a is a CMEM address
//   [11]    b is a CMEM address
//   [27:12] field d           register number, or CMEM operand (below)
//   [43:28] field a
//   [59:44] field b
//   [63:60] zero
//
// A CMEM operand field: [13:0] address, [15:14] loop variable added to it
// (0 none, k the variable of the loop at nesting level k - 1). Other
// patterns reuse the fields: `dna` keeps the direction in b; `cond` keeps
// the condition in a; `loop` keeps the nesting level in d, the start in a
// and the step in b.
//
// Multi-byte values (the multiply's 16-bit source and 24-bit product, the
// register pairs of the 16-bit operations) are big-endian: the most significant byte at the lowest register number or
// CMEM address, the order the host's CIU packing writes them (high bytes,
// then low bytes).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tessera::ap {

// Enumerators are op_<mnemonic>: `and`, `or`, `xor` and `not` are C++ keywords.
enum class Opcode : uint8_t {
#define TESSERA_AP_OP(mnemonic, opcode, operands, forms, cycles, flags, feature, description) op_##mnemonic = (opcode),
#include "array/isa/ap_isa.def"
#undef TESSERA_AP_OP
};

enum class Cond : uint8_t {
#define TESSERA_AP_COND(name, code, description) name = (code),
#include "array/isa/ap_cond.def"
#undef TESSERA_AP_COND
};

enum class Stage : uint8_t {
#define TESSERA_AP_STAGE(name, code, description) name = (code),
#include "array/isa/ap_stage.def"
#undef TESSERA_AP_STAGE
};

enum class OperandPattern : uint8_t { none, dab, da, ab, d, dna, cond, loop };
// The forms column of ap_isa.def, lower-cased (r: registers only, m: CMEM
// only, rm: either per operand, c: the AC's own).
enum class Forms : uint8_t { r, m, rm, c };

// A neighbour, as the grid is drawn: row 0 at the top, column 0 at the left.
enum class Direction : uint8_t { left = 0, right = 1, up = 2, down = 3 };

inline constexpr unsigned OPCODE_COUNT = 0
#define TESSERA_AP_OP(mnemonic, opcode, operands, forms, cycles, flags, feature, description) \
  +1  // NOLINT(bugprone-macro-parentheses)
#include "array/isa/ap_isa.def"
#undef TESSERA_AP_OP
    ;
inline constexpr unsigned COND_COUNT = 8;
inline constexpr unsigned STAGE_COUNT = 8;
inline constexpr unsigned LOOP_LEVELS = 3;    // the loop-variable selector has 3 values besides "none"
inline constexpr unsigned ADDRESS_BITS = 14;  // CMEM operand addresses: up to 16 KiB of CMEM
inline constexpr unsigned MAX_LOOP_START = (1u << 14) - 1;
inline constexpr unsigned MAX_REGISTERS = 16;

// The J2210's array: the one place these numbers live. The defaults of
// array.columns, array.rows, array.registers, array.cmem_bytes and
// array.program_words (ArrayParams::parameters), of the plain-C++ core's
// ArrayGeometry and of the assembler's AsmLimits all read them.
struct J2210 {
  static constexpr unsigned COLUMNS = 24, ROWS = 4, REGISTERS = 8, CMEM_BYTES = 4096, PROGRAM_WORDS = 4096;
};

struct OpInfo {
  std::string_view mnemonic;
  Opcode opcode;
  OperandPattern operands;
  Forms forms;
  unsigned cycles;  // default of array.cycles.<mnemonic>
  std::string_view flags;
  // The switch array.features.<feature> that enables an instruction beyond
  // the J2210's own, or empty for those (ap_isa.def's feature column).
  std::string_view feature;
  std::string_view description;
};

// Information on `opcode`, or nullptr when the value is not an instruction.
const OpInfo* op_info(unsigned opcode);
const OpInfo& op_info(Opcode opcode);
const OpInfo* find_op(std::string_view mnemonic);
// Every instruction in opcode order.
const std::array<OpInfo, OPCODE_COUNT>& all_ops();

// Which opcodes a configured array runs: the J2210's own always, the others
// when their feature's switch is on. Indexed by opcode.
using EnabledOps = std::array<bool, OPCODE_COUNT>;
// The J2210's own instructions only (every feature off).
EnabledOps j2210_ops();
// Every instruction (every feature on), for tests of the datapath.
EnabledOps all_enabled_ops();
// The configuration key of the switch that enables `info`'s instruction
// ("array.features.<feature>"), or an empty string for a J2210 instruction.
std::string feature_key(const OpInfo& info);

std::string_view cond_name(Cond cond);
std::string_view cond_description(Cond cond);
std::optional<Cond> find_cond(std::string_view name);
std::string_view stage_name(Stage stage);
std::string_view stage_description(Stage stage);
std::optional<Stage> find_stage(std::string_view name);
std::string_view direction_name(Direction direction);
std::optional<Direction> find_direction(std::string_view name);

struct Operand {
  bool in_cmem = false;
  uint16_t value = 0;  // the register number or the CMEM address
  uint8_t loop = 0;    // loop variable added to the address: 0 none, k level k - 1
};

struct Instruction {
  Opcode opcode = Opcode::op_nop;
  Stage stage = Stage::other;
  Operand d, a, b;

  // Pattern-specific views of the fields.
  Direction direction() const { return static_cast<Direction>(b.value & 3); }
  Cond cond() const { return static_cast<Cond>(a.value & 7); }
  unsigned loop_level() const { return d.value; }
  unsigned loop_start() const { return a.value; }
  unsigned loop_step() const { return b.value; }
  bool any_cmem() const { return d.in_cmem || a.in_cmem || b.in_cmem; }
};

uint64_t encode(const Instruction& instruction);

// The instruction in `word`, or a description of why it is not one (an
// unknown opcode, reserved bits set, an operand form or field the
// instruction does not allow). Limits that depend on the array's
// configuration (registers, CMEM size) are checked by check_limits().
struct Decoded {
  Instruction instruction;
  std::string error;  // empty when the word is an instruction
};
Decoded decode(uint64_t word);

// Why `instruction` cannot run on an array with `registers` registers and
// `cmem_bytes` of CMEM per CU (a register beyond the file, a static address
// beyond CMEM), or an empty string. Addresses plus loop variables are
// checked by the AC when it runs.
std::string check_limits(const Instruction& instruction, unsigned registers, unsigned cmem_bytes);

// How many consecutive bytes operand `which` ('d', 'a' or 'b') of the
// instruction covers (3, 2 and 1 for the multiply's; the divide's dividend
// a is 2; the lookup's index a and entry d are 2; every operand of the
// 16-bit operations is a register pair, 2; else 1).
unsigned operand_width(Opcode opcode, char which);

// The 16-bit operations on register pairs (add16, sub16, cmp16, mov16;
// array.features.wide_ops).
bool is_pair_op(Opcode opcode);
// The instructions that end the innermost loop's body: endloop, and
// endloopany, which also leaves the loop early (array.features.wired_or_loop).
bool closes_loop(Opcode opcode);

// One line of assembly for the instruction (the disassembler's format, which
// the assembler reads back).
std::string format_instruction(const Instruction& instruction);

}  // namespace tessera::ap
