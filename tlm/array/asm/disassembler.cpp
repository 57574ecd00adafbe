#include "array/asm/disassembler.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <utility>
#include <vector>

#include "array/isa/ap_isa.h"

namespace tessera::ap {

namespace {

// The names the disassembly gives loop variables: a constant or variable of
// the same name would clash with them, so it is written as a comment.
bool is_loop_variable_name(const std::string& name) {
  return name.size() == 2 && name[0] == 'i' && name[1] >= '0' && name[1] < static_cast<char>('0' + LOOP_LEVELS);
}

std::string hex_word(uint64_t word) {
  char text[24];
  std::snprintf(text, sizeof text, "0x%016" PRIx64, word);
  return text;
}

}  // namespace

std::string disassemble(const Program& program) {
  std::string text = "; " + program.source_name + ", disassembled\n";
  for (const auto& [name, value] : program.constants)
    text +=
        (is_loop_variable_name(name) ? "; " : "") + std::string(".const ") + name + " " + std::to_string(value) + "\n";
  std::vector<std::pair<std::string, Variable>> variables(program.variables.begin(), program.variables.end());
  std::stable_sort(variables.begin(), variables.end(),
                   [](const auto& x, const auto& y) { return x.second.address < y.second.address; });
  for (const auto& [name, variable] : variables)
    text += (is_loop_variable_name(name) ? "; " : "") + std::string(".var ") + name + " " +
            std::to_string(variable.size) + " @ " + std::to_string(variable.address) + "\n";

  std::vector<std::vector<std::string>> labels(program.words.size() + 1);
  for (const auto& [name, index] : program.entries)
    labels[std::min<size_t>(index, program.words.size())].push_back(name);

  unsigned depth = 0;
  Stage stage = Stage::other;
  for (size_t i = 0; i <= program.words.size(); ++i) {
    for (const std::string& name : labels[i]) {
      text += "\n" + name + ":\n";
      stage = Stage::other;
    }
    if (i == program.words.size()) break;
    const Decoded decoded = decode(program.words[i]);
    if (!decoded.error.empty()) {
      text += "; word " + std::to_string(i) + " " + hex_word(program.words[i]) + ": " + decoded.error + "\n";
      continue;
    }
    const Instruction& in = decoded.instruction;
    if (closes_loop(in.opcode) && depth > 0) --depth;
    const std::string indent(2 * (depth + 1), ' ');
    if (in.stage != stage) {
      text += indent + ".stage " + std::string(stage_name(in.stage)) + "\n";
      stage = in.stage;
    }
    text += indent + format_instruction(in) + "\n";
    if (in.opcode == Opcode::op_loop) ++depth;
  }
  return text;
}

}  // namespace tessera::ap
