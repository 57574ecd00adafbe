#include "array/asm/isa_table.h"

#include <cstdio>

#include "array/isa/ap_isa.h"

namespace tessera::ap {

namespace {

// A table cell: a literal `|` would end it.
std::string cell(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

std::string_view operand_syntax(OperandPattern pattern) {
  switch (pattern) {
    case OperandPattern::none: return "";
    case OperandPattern::dab: return "d, a, b";
    case OperandPattern::da: return "d, a";
    case OperandPattern::ab: return "a, b";
    case OperandPattern::d: return "d";
    case OperandPattern::dna: return "d, left|right|up|down, a";
    case OperandPattern::cond: return "cond";
    case OperandPattern::loop: return "var, start, step";
  }
  return "";
}

std::string_view forms_name(Forms forms) {
  switch (forms) {
    case Forms::r: return "R";
    case Forms::m: return "M";
    case Forms::rm: return "RM";
    case Forms::c: return "C";
  }
  return "";
}

std::string hex_code(unsigned code) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02x", code);
  return text;
}

}  // namespace

std::string isa_table_markdown() {
  std::string text =
      "| Opcode | Mnemonic | Operands | Forms | Cycles | Flags | Switch | Description |\n"
      "|---|---|---|---|---|---|---|---|\n";
  for (const OpInfo& info : all_ops()) {
    const std::string_view syntax = operand_syntax(info.operands);
    const std::string operands = "`" + std::string(info.mnemonic) + (syntax.empty() ? "" : " ") + cell(syntax) + "`";
    text += "| " + hex_code(static_cast<unsigned>(info.opcode)) + " | `" + std::string(info.mnemonic) + "` | " +
            operands + " | " + std::string(forms_name(info.forms)) + " | " + std::to_string(info.cycles) + " | " +
            cell(info.flags) + " | " + (info.feature.empty() ? "-" : "`" + feature_key(info) + "`") + " | " +
            cell(info.description) + " |\n";
  }
  text +=
      "\nConditions of `mmov`, `mand`, `mor` and `endloopany`:\n\n"
      "| Condition | Code | Description |\n"
      "|---|---|---|\n";
  for (unsigned code = 0; code < COND_COUNT; ++code) {
    const auto cond = static_cast<Cond>(code);
    text += "| `" + std::string(cond_name(cond)) + "` | " + std::to_string(code) + " | " +
            cell(cond_description(cond)) + " |\n";
  }
  text +=
      "\nStages of `.stage`:\n\n"
      "| Stage | Code | Description |\n"
      "|---|---|---|\n";
  for (unsigned code = 0; code < STAGE_COUNT; ++code) {
    const auto stage = static_cast<Stage>(code);
    text += "| `" + std::string(stage_name(stage)) + "` | " + std::to_string(code) + " | " +
            cell(stage_description(stage)) + " |\n";
  }
  return text;
}

}  // namespace tessera::ap
