#include "array/core/array_controller.h"

#include <algorithm>

namespace tessera::ap {

CycleTable CycleTable::defaults() {
  CycleTable table;
  for (const OpInfo& info : all_ops()) table.cycles[static_cast<unsigned>(info.opcode)] = info.cycles;
  table.cmem_operand = 1;
  return table;
}

unsigned CycleTable::cost(const Instruction& instruction) const {
  const OpInfo& info = op_info(instruction.opcode);
  unsigned total = cycles[static_cast<unsigned>(instruction.opcode)];
  if (info.forms == Forms::rm && instruction.any_cmem()) total += cmem_operand;
  return total;
}

ArrayController::ArrayController(const ArrayGeometry& geometry, const CycleTable& cycles, unsigned program_words,
                                 uint64_t max_program_cycles)
    : m_geometry(geometry),
      m_cycles(cycles),
      m_max_cycles(max_program_cycles),
      m_array(geometry),
      m_words(program_words, 0),
      m_slots(program_words) {
  m_activity.word_cycles.assign(program_words, 0);
  m_activity.word_executions.assign(program_words, 0);
  m_run_executions.assign(program_words, 0);
  for (unsigned i = 0; i < program_words; ++i) decode_slot(i);
}

void ArrayController::decode_slot(unsigned index) {
  Slot& slot = m_slots[index];
  Decoded decoded = decode(m_words[index]);
  slot.instruction = decoded.instruction;
  slot.error = decoded.error;
  if (slot.error.empty()) slot.error = check_limits(slot.instruction, m_geometry.registers, m_geometry.cmem_bytes);
  slot.cost = slot.error.empty() ? m_cycles.cost(slot.instruction) : 0;
}

bool ArrayController::write_word(unsigned index, uint64_t word) {
  if (index >= m_words.size()) return false;
  m_words[index] = word;
  decode_slot(index);
  return true;
}

bool ArrayController::load(unsigned first, const std::vector<uint64_t>& words) {
  if (first > m_words.size() || words.size() > m_words.size() - first) return false;
  for (size_t i = 0; i < words.size(); ++i) write_word(first + static_cast<unsigned>(i), words[i]);
  return true;
}

const char* run_error_name(RunError error) {
  switch (error) {
    case RunError::none: return "none";
    case RunError::bad_word: return "bad instruction word";
    case RunError::loop: return "loop the AC cannot run";
    case RunError::cmem_address: return "CMEM address out of range";
    case RunError::past_end: return "past the end of program memory";
    case RunError::too_long: return "longer than array.max_program_cycles";
  }
  return "unknown";
}

RunResult ArrayController::run(unsigned entry) {
  struct Loop {
    unsigned body;
    unsigned step;
  };
  RunResult result;
  std::array<Loop, LOOP_LEVELS> loops{};
  LoopVariables variables{};
  unsigned depth = 0;
  unsigned pc = entry;
  unsigned last_pc = entry;  // the furthest word executed (every one is from entry on)
  std::string error;         // set by an instruction that cannot run
  const auto fail = [&](RunError kind, const std::string& why) {
    result.ok = false;
    result.kind = kind;
    result.error_pc = pc;
    result.error = "program word " + std::to_string(pc) + ": " + why;
  };
  ++m_activity.programs;
  m_stage_changes.clear();
  while (true) {
    if (pc >= m_slots.size()) {
      fail(RunError::past_end,
           "past the end of program memory (" + std::to_string(m_slots.size()) + " words) without a halt");
      break;
    }
    const Slot& slot = m_slots[pc];
    if (!slot.error.empty()) {
      fail(RunError::bad_word, slot.error);
      break;
    }
    const Instruction& in = slot.instruction;
    unsigned next = pc + 1;
    bool halted = false;
    switch (in.opcode) {
      case Opcode::op_nop: break;
      case Opcode::op_halt: halted = true; break;
      case Opcode::op_loop:
        if (in.loop_level() != depth) {
          fail(RunError::loop, "loop at nesting level " + std::to_string(in.loop_level()) + " where " +
                                   std::to_string(depth) + " loops are running");
          break;
        }
        loops[depth] = {pc + 1, in.loop_step()};
        variables[depth] = static_cast<int>(in.loop_start());
        ++depth;
        break;
      case Opcode::op_endloop: {
        if (depth == 0) {
          fail(RunError::loop, "endloop with no loop running");
          break;
        }
        Loop& loop = loops[depth - 1];
        variables[depth - 1] -= static_cast<int>(loop.step);
        if (variables[depth - 1] >= 0)
          next = loop.body;
        else
          --depth;
        break;
      }
      default:
        if (!m_array.execute(in, variables, depth, error)) fail(RunError::cmem_address, error);
        break;
    }
    if (!result.ok) break;
    if (m_record_stages && (m_stage_changes.empty() || m_stage_changes.back().stage != in.stage))
      m_stage_changes.push_back({result.cycles, in.stage});
    result.cycles += slot.cost;
    ++result.instructions;
    ++m_run_executions[pc];
    last_pc = std::max(last_pc, pc);
    if (halted) break;
    if (result.cycles > m_max_cycles) {
      fail(RunError::too_long,
           "the program ran for more than array.max_program_cycles (" + std::to_string(m_max_cycles) + ") cycles");
      break;
    }
    pc = next;
  }
  // The per-word, per-opcode and per-stage totals from the run's counts per
  // word (each word's cost and instruction are fixed during a run).
  for (unsigned word = entry; word <= last_pc && word < m_slots.size(); ++word) {
    const uint64_t executions = m_run_executions[word];
    if (executions == 0) continue;
    m_run_executions[word] = 0;
    const Slot& slot = m_slots[word];
    m_activity.word_executions[word] += executions;
    m_activity.word_cycles[word] += executions * slot.cost;
    m_activity.instruction_mix[static_cast<unsigned>(slot.instruction.opcode)] += executions;
    m_activity.stage_cycles[static_cast<unsigned>(slot.instruction.stage)] += executions * slot.cost;
  }
  m_activity.cycles += result.cycles;
  m_activity.instructions += result.instructions;
  if (!result.ok) ++m_activity.failed_programs;
  return result;
}

}  // namespace tessera::ap
