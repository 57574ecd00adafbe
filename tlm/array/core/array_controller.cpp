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
  m_runaways.clear();
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

namespace {

// The symbolic walk of find_runaway: the program's control flow with loop
// iterations counted, not run. `Slots`: ArrayController's decoded words.
template <typename Slots>
class RunawayWalk {
 public:
  enum class End { body_end, halted, crossed, unknown };

  RunawayWalk(const Slots& slots, unsigned cmem_bytes, uint64_t max_cycles)
      : m_slots(slots), m_cmem_bytes(cmem_bytes), m_max_cycles(max_cycles) {}

  // Walks from `pc` with `depth` loops running (their start values in
  // m_starts) to the endloop closing the innermost (body_end, `pc` left on
  // it), a halt at depth 0, the cap's crossing (crossing_pc) or something
  // only running can decide.
  End walk(unsigned& pc, unsigned depth) {
    while (true) {
      if (pc >= m_slots.size() || !m_slots[pc].error.empty()) return End::unknown;
      const Instruction& in = m_slots[pc].instruction;
      switch (in.opcode) {
        case Opcode::op_halt: return depth == 0 ? End::halted : End::unknown;
        case Opcode::op_endloop: return depth == 0 ? End::unknown : End::body_end;
        case Opcode::op_loop: {
          if (in.loop_level() != depth || depth >= LOOP_LEVELS) return End::unknown;
          if (step(pc)) return End::crossed;
          const End end = loop(pc, depth, in.loop_start(), in.loop_step());
          if (end != End::body_end) return end;
          break;  // pc on the loop's endloop: carry on after it
        }
        default:
          if (!cmem_in_range(in, depth)) return End::unknown;
          if (step(pc)) return End::crossed;
      }
      ++pc;
    }
  }

  uint64_t cycles = 0, instructions = 0;
  unsigned crossing_pc = 0;

 private:
  // One instruction: its cost, and true when it takes the run past the cap.
  bool step(unsigned pc) {
    cycles += m_slots[pc].cost;
    ++instructions;
    if (cycles <= m_max_cycles) return false;
    crossing_pc = pc;
    return true;
  }

  // The loop at `pc` (already counted): its iterations, the first walked,
  // the rest added as multiples of the first while they fit under the cap,
  // the one that crosses it walked. Returns body_end with `pc` on the
  // endloop when the loop ends within the cap.
  End loop(unsigned& pc, unsigned depth, unsigned start, unsigned step_size) {
    // The variable runs start, start - step, ... while >= 0 (the decoder
    // refuses a step of 0).
    if (step_size == 0) return End::unknown;
    m_starts[depth] = start;
    const uint64_t iterations = uint64_t{start} / step_size + 1;
    const unsigned body = pc + 1;
    const uint64_t cycles_before = cycles, instructions_before = instructions;
    unsigned end = body;
    const End first = walk(end, depth + 1);
    if (first != End::body_end) return first;
    if (step(end)) return End::crossed;
    const uint64_t per_cycles = cycles - cycles_before, per_instructions = instructions - instructions_before;
    const uint64_t left = iterations - 1;
    if (per_cycles == 0) {  // instructions of 0 cycles (a cycle table may say so): the cap never comes
      instructions += per_instructions * left;
      pc = end;
      return End::body_end;
    }
    const uint64_t fit = (m_max_cycles - cycles) / per_cycles;  // whole iterations within the cap
    if (fit >= left) {
      cycles += per_cycles * left;
      instructions += per_instructions * left;
      pc = end;
      return End::body_end;
    }
    cycles += per_cycles * fit;
    instructions += per_instructions * fit;
    // The next iteration crosses the cap: walked to find the word.
    unsigned again = body;
    const End crossing = walk(again, depth + 1);
    if (crossing == End::body_end && step(again)) return End::crossed;
    return crossing == End::crossed ? End::crossed : End::unknown;
  }

  // Every CMEM byte the instruction may address, with any loop variable at
  // its largest (its loop's start), within CMEM.
  bool cmem_in_range(const Instruction& in, unsigned depth) const {
    const std::pair<const Operand*, char> operands[] = {{&in.d, 'd'}, {&in.a, 'a'}, {&in.b, 'b'}};
    for (const auto& [operand, which] : operands) {
      if (!operand->in_cmem) continue;
      uint64_t last = uint64_t{operand->value} + std::max(operand_width(in.opcode, which), 1u) - 1;
      if (operand->loop != 0) {
        if (operand->loop > depth) return false;
        last += m_starts[operand->loop - 1];
      }
      if (last >= m_cmem_bytes) return false;
    }
    return true;
  }

  const Slots& m_slots;
  unsigned m_cmem_bytes;
  uint64_t m_max_cycles;
  std::array<unsigned, LOOP_LEVELS> m_starts{};
};

}  // namespace

std::optional<ArrayController::Runaway> ArrayController::find_runaway(unsigned entry) const {
  if (const auto known = m_runaways.find(entry); known != m_runaways.end()) return known->second;
  return m_runaways[entry] = walk_for_runaway(entry);
}

std::optional<ArrayController::Runaway> ArrayController::walk_for_runaway(unsigned entry) const {
  RunawayWalk<std::vector<Slot>> walk(m_slots, m_geometry.cmem_bytes, m_max_cycles);
  unsigned pc = entry;
  if (walk.walk(pc, 0) != RunawayWalk<std::vector<Slot>>::End::crossed) return std::nullopt;
  return Runaway{walk.crossing_pc, walk.cycles, walk.instructions};
}

RunResult ArrayController::run(unsigned entry) {
  if (const std::optional<Runaway> runaway = find_runaway(entry)) {
    RunResult result;
    result.ok = false;
    result.kind = RunError::too_long;
    result.error_pc = runaway->pc;
    result.cycles = runaway->cycles;
    result.instructions = runaway->instructions;
    result.error = "program word " + std::to_string(runaway->pc) + ": the program ran for more than " +
                   "array.max_program_cycles (" + std::to_string(m_max_cycles) + ") cycles: its loops reach the " +
                   "limit at this word (known from its loop counts at the start, so it was not run)";
    ++m_activity.programs;
    ++m_activity.failed_programs;
    m_activity.cycles += result.cycles;
    m_activity.instructions += result.instructions;
    m_stage_changes.clear();
    return result;
  }
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
  // The lanes' activity is folded into the stage's totals where the stage
  // changes, not per instruction.
  Stage stage = entry < m_slots.size() ? m_slots[entry].instruction.stage : Stage{};
  ArrayActivity stage_start = m_array.activity();
  const auto fold_stage = [&] {
    const ArrayActivity& now = m_array.activity();
    ArrayActivity& total = m_activity.stage_lanes[static_cast<unsigned>(stage)];
    total.lane_operations += now.lane_operations - stage_start.lane_operations;
    total.useful_operations += now.useful_operations - stage_start.useful_operations;
    total.cmem_reads += now.cmem_reads - stage_start.cmem_reads;
    total.cmem_writes += now.cmem_writes - stage_start.cmem_writes;
    total.neighbour_transfers += now.neighbour_transfers - stage_start.neighbour_transfers;
    stage_start = now;
  };
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
    if (in.stage != stage) {
      fold_stage();
      stage = in.stage;
    }
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
  fold_stage();
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
    m_activity.stage_instructions[static_cast<unsigned>(slot.instruction.stage)] += executions;
    m_activity
        .stage_mix[static_cast<unsigned>(slot.instruction.stage)][static_cast<unsigned>(slot.instruction.opcode)] +=
        executions;
  }
  m_activity.cycles += result.cycles;
  m_activity.instructions += result.instructions;
  if (!result.ok) ++m_activity.failed_programs;
  return result;
}

}  // namespace tessera::ap
