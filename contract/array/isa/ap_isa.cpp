#include "array/isa/ap_isa.h"

namespace tessera::ap {

namespace {

constexpr std::array<OpInfo, OPCODE_COUNT> OPS = {{
#define TESSERA_AP_OP(mnemonic, opcode, operands, forms, cycles, flags, feature, description) \
  {#mnemonic,                                                                                 \
   Opcode::op_##mnemonic,                                                                     \
   OperandPattern::operands,                                                                  \
   Forms::forms,                                                                              \
   cycles,                                                                                    \
   flags,                                                                                     \
   std::string_view(#feature) == "none" ? std::string_view() : std::string_view(#feature),    \
   description},
#include "array/isa/ap_isa.def"
#undef TESSERA_AP_OP
}};

struct Named {
  std::string_view name;
  std::string_view description;
};

constexpr std::array<Named, COND_COUNT> CONDS = {{
#define TESSERA_AP_COND(name, code, description) {#name, description},
#include "array/isa/ap_cond.def"
#undef TESSERA_AP_COND
}};

constexpr std::array<Named, STAGE_COUNT> STAGES = {{
#define TESSERA_AP_STAGE(name, code, description) {#name, description},
#include "array/isa/ap_stage.def"
#undef TESSERA_AP_STAGE
}};

constexpr std::array<std::string_view, 4> DIRECTIONS = {"left", "right", "up", "down"};

// The tables are dense and in code order; a .def edit that breaks that
// fails to compile here rather than decoding wrongly.
constexpr bool ops_in_order() {
  for (unsigned i = 0; i < OPS.size(); ++i)
    if (static_cast<unsigned>(OPS[i].opcode) != i) return false;
  return true;
}
static_assert(ops_in_order(), "ap_isa.def: opcodes must be 0, 1, 2, ... in table order");
static_assert(OPCODE_COUNT <= 64, "the opcode field has 6 bits");

constexpr unsigned FIELD_BITS = 16;
constexpr uint64_t FIELD_MASK = (1u << FIELD_BITS) - 1;
constexpr unsigned D_SHIFT = 12, A_SHIFT = 28, B_SHIFT = 44;
constexpr uint64_t ADDRESS_MASK = (1u << ADDRESS_BITS) - 1;

uint64_t field(const Operand& operand) {
  if (operand.in_cmem) return (operand.value & ADDRESS_MASK) | (uint64_t{operand.loop & 3u} << ADDRESS_BITS);
  return operand.value & FIELD_MASK;
}

Operand unfield(uint64_t bits, bool in_cmem) {
  Operand operand;
  operand.in_cmem = in_cmem;
  if (in_cmem) {
    operand.value = static_cast<uint16_t>(bits & ADDRESS_MASK);
    operand.loop = static_cast<uint8_t>(bits >> ADDRESS_BITS);
  } else {
    operand.value = static_cast<uint16_t>(bits);
  }
  return operand;
}

// Which of d, a, b the pattern uses as data operands (registers or CMEM).
struct DataOperands {
  bool d, a, b;
};
DataOperands data_operands(OperandPattern pattern) {
  switch (pattern) {
    case OperandPattern::dab: return {true, true, true};
    case OperandPattern::da: return {true, true, false};
    case OperandPattern::ab: return {false, true, true};
    case OperandPattern::d: return {true, false, false};
    case OperandPattern::dna: return {true, true, false};
    case OperandPattern::none:
    case OperandPattern::cond:
    case OperandPattern::loop: break;
  }
  return {false, false, false};
}

std::string format_operand(const Operand& operand) {
  if (!operand.in_cmem) return "r" + std::to_string(operand.value);
  std::string text = "[" + std::to_string(operand.value);
  if (operand.loop != 0) text += " + i" + std::to_string(operand.loop - 1);
  return text + "]";
}

}  // namespace

const OpInfo* op_info(unsigned opcode) {
  return opcode < OPS.size() ? &OPS[opcode] : nullptr;
}
const OpInfo& op_info(Opcode opcode) {
  return OPS[static_cast<unsigned>(opcode)];
}
const OpInfo* find_op(std::string_view mnemonic) {
  for (const OpInfo& info : OPS)
    if (info.mnemonic == mnemonic) return &info;
  return nullptr;
}
const std::array<OpInfo, OPCODE_COUNT>& all_ops() {
  return OPS;
}

EnabledOps j2210_ops() {
  EnabledOps enabled{};
  for (const OpInfo& info : OPS) enabled[static_cast<unsigned>(info.opcode)] = info.feature.empty();
  return enabled;
}
EnabledOps all_enabled_ops() {
  EnabledOps enabled{};
  enabled.fill(true);
  return enabled;
}
std::string feature_key(const OpInfo& info) {
  return info.feature.empty() ? std::string() : "array.features." + std::string(info.feature);
}

std::string_view cond_name(Cond cond) {
  return CONDS[static_cast<unsigned>(cond) & 7].name;
}
std::string_view cond_description(Cond cond) {
  return CONDS[static_cast<unsigned>(cond) & 7].description;
}
std::optional<Cond> find_cond(std::string_view name) {
  for (unsigned i = 0; i < CONDS.size(); ++i)
    if (CONDS[i].name == name) return static_cast<Cond>(i);
  return std::nullopt;
}
std::string_view stage_name(Stage stage) {
  return STAGES[static_cast<unsigned>(stage) & 7].name;
}
std::string_view stage_description(Stage stage) {
  return STAGES[static_cast<unsigned>(stage) & 7].description;
}
std::optional<Stage> find_stage(std::string_view name) {
  for (unsigned i = 0; i < STAGES.size(); ++i)
    if (STAGES[i].name == name) return static_cast<Stage>(i);
  return std::nullopt;
}
std::string_view direction_name(Direction direction) {
  return DIRECTIONS[static_cast<unsigned>(direction) & 3];
}
std::optional<Direction> find_direction(std::string_view name) {
  for (unsigned i = 0; i < DIRECTIONS.size(); ++i)
    if (DIRECTIONS[i] == name) return static_cast<Direction>(i);
  return std::nullopt;
}

uint64_t encode(const Instruction& instruction) {
  return uint64_t{static_cast<uint8_t>(instruction.opcode) & 0x3fu} |
         uint64_t{static_cast<uint8_t>(instruction.stage) & 7u} << 6 | uint64_t{instruction.d.in_cmem} << 9 |
         uint64_t{instruction.a.in_cmem} << 10 | uint64_t{instruction.b.in_cmem} << 11 |
         field(instruction.d) << D_SHIFT | field(instruction.a) << A_SHIFT | field(instruction.b) << B_SHIFT;
}

Decoded decode(uint64_t word) {
  Decoded result;
  Instruction& in = result.instruction;
  const OpInfo* info = op_info(static_cast<unsigned>(word & 0x3f));
  if (info == nullptr) {
    result.error = "unknown opcode " + std::to_string(word & 0x3f);
    return result;
  }
  if ((word >> 60) != 0) {
    result.error = "reserved bits 63:60 set";
    return result;
  }
  in.opcode = info->opcode;
  in.stage = static_cast<Stage>((word >> 6) & 7);
  in.d = unfield((word >> D_SHIFT) & FIELD_MASK, ((word >> 9) & 1) != 0);
  in.a = unfield((word >> A_SHIFT) & FIELD_MASK, ((word >> 10) & 1) != 0);
  in.b = unfield((word >> B_SHIFT) & FIELD_MASK, ((word >> 11) & 1) != 0);

  const DataOperands used = data_operands(info->operands);
  const std::string name(info->mnemonic);
  const auto bad_form = [&](char which, const Operand& operand, bool is_data) -> bool {
    if (!is_data) {
      if (operand.in_cmem) result.error = name + ": operand field " + which + " cannot be a CMEM address";
      return operand.in_cmem;
    }
    if (info->forms == Forms::r && operand.in_cmem) {
      result.error = name + " takes registers only (operand " + which + " is a CMEM address)";
      return true;
    }
    if (info->forms == Forms::m && !operand.in_cmem) {
      result.error = name + " takes CMEM addresses only (operand " + which + " is a register)";
      return true;
    }
    if (!operand.in_cmem && operand.value >= MAX_REGISTERS) {
      result.error = name + ": operand " + which + " is register " + std::to_string(operand.value) + ", beyond r" +
                     std::to_string(MAX_REGISTERS - 1);
      return true;
    }
    return false;
  };
  if (bad_form('d', in.d, used.d) || bad_form('a', in.a, used.a) || bad_form('b', in.b, used.b)) return result;
  // Fields the pattern does not use must be zero, so every instruction has
  // exactly one encoding.
  const auto must_be_zero = [&](char which, const Operand& operand, bool used_field) {
    if (!used_field && (operand.value != 0 || operand.loop != 0)) {
      result.error = name + ": field " + std::string(1, which) + " must be 0";
      return true;
    }
    return false;
  };
  switch (info->operands) {
    case OperandPattern::dna:
      if (in.b.value > 3) {
        result.error = name + ": direction " + std::to_string(in.b.value) + " is not left, right, up or down";
        return result;
      }
      break;
    case OperandPattern::cond:
      if (in.a.value >= COND_COUNT) {
        result.error = name + ": condition " + std::to_string(in.a.value) + " does not exist";
        return result;
      }
      if (must_be_zero('d', in.d, false) || must_be_zero('b', in.b, false)) return result;
      break;
    case OperandPattern::loop:
      if (in.d.value >= LOOP_LEVELS) {
        result.error = "loop: nesting level " + std::to_string(in.d.value) + " beyond the AC's " +
                       std::to_string(LOOP_LEVELS) + " loop counters";
        return result;
      }
      if (in.a.value > MAX_LOOP_START) {
        result.error = "loop: start " + std::to_string(in.a.value) + " beyond " + std::to_string(MAX_LOOP_START);
        return result;
      }
      if (in.b.value == 0 || in.b.value > MAX_LOOP_START) {
        result.error = "loop: step " + std::to_string(in.b.value) + " is not 1.." + std::to_string(MAX_LOOP_START);
        return result;
      }
      break;
    default:
      if (must_be_zero('d', in.d, used.d) || must_be_zero('a', in.a, used.a) || must_be_zero('b', in.b, used.b))
        return result;
      break;
  }
  if (is_pair_op(info->opcode) && info->operands != OperandPattern::ab) {
    // The result's pair and a source's are the same pair or share no
    // register: a datapath of 8 bits computes the low byte first and
    // writes d + 1 before it reads the sources' high bytes, so a pair
    // overlapping by one register would read its own result.
    const auto straddles = [](const Operand& x, const Operand& y) {
      return x.value != y.value && x.value < y.value + 2 && y.value < x.value + 2;
    };
    const bool uses_b = info->operands == OperandPattern::dab;
    if (straddles(in.d, in.a) || (uses_b && straddles(in.d, in.b))) {
      result.error = name + ": the result pair d:d+1 overlaps a source pair by one register";
      return result;
    }
  }
  if (info->opcode == Opcode::op_mul || info->opcode == Opcode::op_mulm) {
    // The product must not overlap a source: the steps read the sources
    // while they accumulate into d.
    const auto overlaps = [](const Operand& x, unsigned x_width, const Operand& y, unsigned y_width) {
      return x.loop == y.loop && x.value < y.value + y_width && y.value < x.value + x_width;
    };
    if (overlaps(in.d, 3, in.a, 2) || overlaps(in.d, 3, in.b, 1)) {
      result.error = name + ": the product d..d+2 overlaps a source";
      return result;
    }
  }
  return result;
}

bool is_pair_op(Opcode opcode) {
  return opcode == Opcode::op_add16 || opcode == Opcode::op_sub16 || opcode == Opcode::op_cmp16 ||
         opcode == Opcode::op_mov16;
}

bool closes_loop(Opcode opcode) {
  return opcode == Opcode::op_endloop || opcode == Opcode::op_endloopany;
}

unsigned operand_width(Opcode opcode, char which) {
  if (is_pair_op(opcode)) return 2;
  if (opcode == Opcode::op_mul || opcode == Opcode::op_mulm) {
    if (which == 'd') return 3;
    if (which == 'a') return 2;
  }
  if (opcode == Opcode::op_div && which == 'a') return 2;
  if (opcode == Opcode::op_lut && (which == 'd' || which == 'a')) return 2;
  // The chain's selecting adds read the neighbour's a or a + 1.
  if ((opcode == Opcode::op_nadds || opcode == Opcode::op_nadcs) && which == 'a') return 2;
  // The z-buffer's pixel: x:2 y:2 in a, z:2 colour:2 in b.
  if (opcode == Opcode::op_zsend && (which == 'a' || which == 'b')) return 4;
  return 1;
}

std::string check_limits(const Instruction& instruction, unsigned registers, unsigned cmem_bytes) {
  const OpInfo& info = op_info(instruction.opcode);
  const DataOperands used = data_operands(info.operands);
  const auto check = [&](char which, const Operand& operand, bool is_data) -> std::string {
    if (!is_data) return {};
    const unsigned width = operand_width(instruction.opcode, which);
    if (operand.in_cmem) {
      if (operand.value + width > cmem_bytes)
        return std::string(info.mnemonic) + ": operand " + which + " at CMEM address " + std::to_string(operand.value) +
               " is beyond the " + std::to_string(cmem_bytes) + " bytes of CMEM";
    } else if (operand.value + width > registers) {
      return std::string(info.mnemonic) + ": operand " + which + " uses register r" +
             std::to_string(operand.value + width - 1) + ", beyond the " + std::to_string(registers) +
             " registers of a CU";
    }
    return {};
  };
  for (const std::string& error :
       {check('d', instruction.d, used.d), check('a', instruction.a, used.a), check('b', instruction.b, used.b)})
    if (!error.empty()) return error;
  return {};
}

std::string format_instruction(const Instruction& in) {
  const OpInfo& info = op_info(in.opcode);
  std::string text(info.mnemonic);
  switch (info.operands) {
    case OperandPattern::none: break;
    case OperandPattern::dab:
      text += " " + format_operand(in.d) + ", " + format_operand(in.a) + ", " + format_operand(in.b);
      break;
    case OperandPattern::da: text += " " + format_operand(in.d) + ", " + format_operand(in.a); break;
    case OperandPattern::ab: text += " " + format_operand(in.a) + ", " + format_operand(in.b); break;
    case OperandPattern::d: text += " " + format_operand(in.d); break;
    case OperandPattern::dna:
      text +=
          " " + format_operand(in.d) + ", " + std::string(direction_name(in.direction())) + ", " + format_operand(in.a);
      break;
    case OperandPattern::cond: text += " " + std::string(cond_name(in.cond())); break;
    case OperandPattern::loop:
      text += " i" + std::to_string(in.loop_level()) + ", " + std::to_string(in.loop_start()) + ", " +
              std::to_string(in.loop_step());
      break;
  }
  return text;
}

}  // namespace tessera::ap
