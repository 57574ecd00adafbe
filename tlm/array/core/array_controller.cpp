#include "array/core/array_controller.h"

#include <algorithm>
#include <array>
#include <cstring>

#if defined(__x86_64__)
#include <tmmintrin.h>
#endif

namespace tessera::ap {

CycleTable CycleTable::defaults() {
  CycleTable table;
  for (const OpInfo& info : all_ops()) table.cycles[static_cast<unsigned>(info.opcode)] = info.cycles;
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
  if (slot.error.empty() && !m_enabled[static_cast<unsigned>(slot.instruction.opcode)]) {
    const OpInfo& info = op_info(slot.instruction.opcode);
    slot.error = std::string(info.mnemonic) + " is not enabled: it needs " + feature_key(info) + " = true";
  }
  if (slot.error.empty() && slot.instruction.opcode == Opcode::op_zsend) {
    if (m_pixel_port == nullptr)
      slot.error = "zsend has no z-buffer unit to send to: it needs zbuf.enabled = true";
    else if (m_skew_unit == IssueSkew::lane)
      slot.error = "zsend under delayed execution by lane (array.issue_skew = lane) is not modelled";
  }
  if (slot.error.empty() && slot.instruction.opcode == Opcode::op_endloopany && m_skew_unit != IssueSkew::none)
    slot.error =
        "endloopany under delayed execution (array.issue_skew = lane or row) is not modelled: its wired OR would wait "
        "for "
        "the chain's last CU";
  if (slot.error.empty() && slot.instruction.opcode == Opcode::op_lut && m_skew_unit == IssueSkew::row &&
      lut_lockstep_stall() + 1 > m_skew)
    slot.error = "lut under array.issue_skew = row needs a row's lookups (" + std::to_string(m_geometry.columns) +
                 " CUs, array.lut.ports " + std::to_string(m_lut_ports) +
                 " a cycle: " + std::to_string(lut_lockstep_stall() + 1) +
                 " cycles) to fit in array.issue_skew_cycles (" + std::to_string(m_skew) +
                 "): the rows' lookups would collide on the table's ports, which is not modelled";
  slot.cost = slot.error.empty() ? m_cycles.cost(slot.instruction) : 0;
  if (slot.error.empty() && slot.instruction.opcode == Opcode::op_lut && m_skew_unit != IssueSkew::lane)
    slot.cost += lut_lockstep_stall();
}

unsigned ArrayController::lut_lockstep_stall() const {
  // Under row skew the CUs of one row look up together.
  const unsigned lanes = m_skew_unit == IssueSkew::row ? m_geometry.columns : m_geometry.lanes();
  const unsigned ports = std::max(m_lut_ports, 1u);
  return (lanes + ports - 1) / ports - 1;
}

uint64_t ArrayController::skew_cycles() const {
  switch (m_skew_unit) {
    case IssueSkew::none: break;
    case IssueSkew::lane: return uint64_t{m_geometry.lanes() - 1} * m_skew;
    case IssueSkew::row: return uint64_t{m_geometry.rows - 1} * m_skew;
  }
  return 0;
}

void ArrayController::set_issue_skew(unsigned cycles) {
  set_issue_skew(cycles != 0 ? IssueSkew::lane : IssueSkew::none, cycles);
}

void ArrayController::set_issue_skew(IssueSkew unit, unsigned cycles) {
  if (unit == IssueSkew::none || cycles == 0) {
    unit = IssueSkew::none;
    cycles = 0;
  }
  if (cycles == m_skew && unit == m_skew_unit) return;
  m_skew = cycles;
  m_skew_unit = unit;
  m_array.set_issue_skew(unit);
  for (unsigned i = 0; i < m_slots.size(); ++i) decode_slot(i);
  m_runaways.clear();
  m_plans.clear();
  m_memos.clear();
}

void ArrayController::set_lut_ports(unsigned ports) {
  if (ports == m_lut_ports) return;
  m_lut_ports = std::max(ports, 1u);
  for (unsigned i = 0; i < m_slots.size(); ++i) decode_slot(i);
  m_runaways.clear();
}

void ArrayController::set_pixel_port(PixelPort* port) {
  if (port == m_pixel_port) return;
  m_pixel_port = port;
  for (unsigned i = 0; i < m_slots.size(); ++i) decode_slot(i);
  m_runaways.clear();
  m_plans.clear();
  m_memos.clear();
}

void ArrayController::enable_ops(const EnabledOps& enabled) {
  if (enabled == m_enabled) return;
  m_enabled = enabled;
  for (unsigned i = 0; i < m_slots.size(); ++i) decode_slot(i);
  m_runaways.clear();
  m_plans.clear();
  m_memos.clear();
}

bool ArrayController::write_word(unsigned index, uint64_t word) {
  if (index >= m_words.size()) return false;
  if (m_words[index] == word) return true;
  m_words[index] = word;
  decode_slot(index);
  m_runaways.clear();
  m_plans.clear();
  m_memos.clear();
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
    case RunError::lut_index: return "lut index beyond the table";
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
        case Opcode::op_endloop:
        case Opcode::op_endloopany:  // counted at its loop's most iterations
          return depth == 0 ? End::unknown : End::body_end;
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
  if (m_skip_idle) {
    auto plan = m_plans.find(entry);
    if (plan == m_plans.end()) plan = m_plans.emplace(entry, plan_entry(entry)).first;
    if (plan->second.skippable) {
      EntryMemo& memo = m_memos[entry];
      if (memo.plain_runs_left == 0) return run_skipping(entry, plan->second, memo);
      --memo.plain_runs_left;
      memo.valid = false;
      if (trace_ready(memo)) {
        trace_every_lane(memo);
        return finish_from_record(entry, plan->second, memo);
      }
    }
  }
  unsigned last_pc = entry;
  RunResult result = interpret(entry, m_array, last_pc);
  fold_run(entry, last_pc, result);
  return result;
}

RunResult ArrayController::interpret(unsigned entry, CuArray& array, unsigned& last_pc) {
  struct Loop {
    unsigned body;
    unsigned step;
  };
  RunResult result;
  std::array<Loop, LOOP_LEVELS> loops{};
  LoopVariables variables{};
  unsigned depth = 0;
  unsigned pc = entry;
  last_pc = entry;    // the furthest word executed (every one is from entry on)
  std::string error;  // set by an instruction that cannot run
  const auto fail = [&](RunError kind, const std::string& why) {
    result.ok = false;
    result.kind = kind;
    result.error_pc = pc;
    result.error = "program word " + std::to_string(pc) + ": " + why;
  };
  m_stage_changes.clear();
  m_lut_port_free.assign(m_skew_unit == IssueSkew::lane ? m_lut_ports : 0, 0);
  m_zbuf_port_free = 0;
  m_zbuf_row_free.assign(m_geometry.rows, 0);
  // The AC waits for the z-buffer's port before a zsend or a halt (counted
  // in that word and its stage).
  const auto wait_for_zbuf_port = [&](const Instruction& in) {
    const uint64_t stall = zbuf_stall(result.cycles);
    if (stall == 0) return;
    result.cycles += stall;
    m_activity.zbuf_stall_cycles += stall;
    m_activity.word_cycles[pc] += stall;
    m_activity.stage_cycles[static_cast<unsigned>(in.stage)] += stall;
  };
  // The lanes' activity is folded into the stage's totals where the stage
  // changes, not per instruction.
  Stage stage = entry < m_slots.size() ? m_slots[entry].instruction.stage : Stage{};
  ArrayActivity stage_start = array.activity();
  const auto fold_stage = [&] {
    const ArrayActivity& now = array.activity();
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
      case Opcode::op_endloop:
      case Opcode::op_endloopany: {
        if (depth == 0) {
          fail(RunError::loop, std::string(op_info(in.opcode).mnemonic) + " with no loop running");
          break;
        }
        Loop& loop = loops[depth - 1];
        int& variable = variables[depth - 1];
        variable -= static_cast<int>(loop.step);
        bool again = variable >= 0;
        if (again && in.opcode == Opcode::op_endloopany && !array.any_active_holds(in.cond())) {
          // The wired OR: no CU whose mask is set has the condition, so the
          // loop ends before its count does.
          ++m_activity.wired_or_exits;
          m_activity.wired_or_iterations_saved += static_cast<uint64_t>(variable) / loop.step + 1;
          again = false;
        }
        if (again)
          next = loop.body;
        else
          --depth;
        break;
      }
      default:
        if (!array.execute(in, variables, depth, error))
          fail(array.last_fault() == CuArray::Fault::lut_index ? RunError::lut_index : RunError::cmem_address, error);
        break;
    }
    if (!result.ok) break;
    if (m_record_stages && (m_stage_changes.empty() || m_stage_changes.back().stage != in.stage))
      m_stage_changes.push_back({result.cycles, in.stage});
    if (in.opcode == Opcode::op_zsend || halted) wait_for_zbuf_port(in);
    if (in.opcode == Opcode::op_zsend) send_to_zbuf(result.cycles, array.sent_pixels());
    if (in.opcode == Opcode::op_lut && !m_lut_port_free.empty()) {
      // The port that frees first; the AC waits for it when every one is
      // held by an earlier lut's lookups still running down the chain.
      auto port = std::min_element(m_lut_port_free.begin(), m_lut_port_free.end());
      const uint64_t stall = *port > result.cycles ? *port - result.cycles : 0;
      result.cycles += stall;
      *port = result.cycles + uint64_t{m_geometry.lanes() - 1} * m_skew + 1;
      m_activity.lut_stall_cycles += stall;
      m_activity.word_cycles[pc] += stall;
      m_activity.stage_cycles[static_cast<unsigned>(in.stage)] += stall;
    }
    result.cycles += slot.cost;
    ++result.instructions;
    ++m_run_executions[pc];
    last_pc = std::max(last_pc, pc);
    if (halted) {
      // The last lane (row) halts (lanes - 1) x K ((rows - 1) x K) cycles
      // after the first.
      result.cycles += skew_cycles();
      break;
    }
    if (result.cycles > m_max_cycles) {
      fail(RunError::too_long,
           "the program ran for more than array.max_program_cycles (" + std::to_string(m_max_cycles) + ") cycles");
      break;
    }
    pc = next;
  }
  fold_stage();
  return result;
}

uint64_t ArrayController::zbuf_row_delay() const {
  return m_skew_unit == IssueSkew::row ? m_skew : 0;
}

uint64_t ArrayController::zbuf_stall(uint64_t now) const {
  // Row r runs the stream at now + K r (lockstep: K = 0); each of its CUs
  // holds one pixel until the port takes it, so the whole stream waits
  // until every row's earlier pixels are taken when that row runs it (the
  // rows keep their delays).
  uint64_t stall = 0;
  for (unsigned r = 0; r < m_zbuf_row_free.size(); ++r) {
    const uint64_t runs_at = now + zbuf_row_delay() * r;
    if (m_zbuf_row_free[r] > runs_at) stall = std::max(stall, m_zbuf_row_free[r] - runs_at);
  }
  return stall;
}

void ArrayController::send_to_zbuf(uint64_t now, const std::vector<SentPixel>& pixels) {
  // Row r's pixels reach the port K r after the issue; the port takes sends
  // in program order, so none before the previous send's last.
  const SendArrival arrival{m_geometry.columns, static_cast<unsigned>(zbuf_row_delay()),
                            m_zbuf_port_free > now ? m_zbuf_port_free - now : 0};
  const SendTimes times = m_pixel_port->send(pixels, arrival);
  for (size_t i = 0; i < pixels.size(); ++i) {
    const uint64_t taken = now + times.cycles[i] + 1;
    uint64_t& row_free = m_zbuf_row_free[pixels[i].lane / m_geometry.columns];
    row_free = std::max(row_free, taken);
    m_zbuf_port_free = std::max(m_zbuf_port_free, taken);
  }
  m_activity.zbuf_port_cycles += times.busy;
  m_activity.zbuf_pixels += pixels.size();
}

void ArrayController::fold_run(unsigned entry, unsigned last_pc, const RunResult& result) {
  ++m_activity.programs;
  const uint64_t lut_before = m_activity.instruction_mix[static_cast<unsigned>(Opcode::op_lut)];
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
  if (result.ok && m_skew != 0 && last_pc < m_slots.size()) {
    const uint64_t skew = skew_cycles();
    m_activity.skew_cycles += skew;
    m_activity.word_cycles[last_pc] += skew;
    m_activity.stage_cycles[static_cast<unsigned>(m_slots[last_pc].instruction.stage)] += skew;
  }
  if (m_skew_unit != IssueSkew::lane) {
    const unsigned lut = static_cast<unsigned>(Opcode::op_lut);
    m_activity.lut_stall_cycles += (m_activity.instruction_mix[lut] - lut_before) * lut_lockstep_stall();
  }
  m_activity.cycles += result.cycles;
  m_activity.instructions += result.instructions;
  if (!result.ok) ++m_activity.failed_programs;
}

namespace {

// The work array's lanes are a multiple of this: the width of the vector
// unit the lane loops are compiled for (SSE2's 16 bytes).
constexpr unsigned WORK_LANE_BLOCK = 16;
// The longest run recorded for skipping (its trace holds an instruction per
// instruction run): longer programs run on every CU.
constexpr uint64_t MAX_TRACE = 1u << 22;
// The back-off of EntryMemo: ap-pixel's blocks fill nearly every CU, and its
// programs are short enough that comparing and recording cost a few % of
// its frame.
constexpr unsigned FULL_RUNS_BEFORE_BACK_OFF = 8, BACK_OFF_RUNS = 64;

// differs[l] |= now[l] ^ then[l], a loop the compiler vectorises.
void accumulate_differences(size_t n, const uint8_t* __restrict now, const uint8_t* __restrict then,
                            uint8_t* __restrict differs) {
  for (size_t l = 0; l < n; ++l) differs[l] |= static_cast<uint8_t>(now[l] ^ then[l]);
}

// The run's k lanes between the array's rows and the work array's (lane j
// of the work array is lane lanes[j] of the array) or a record's.
void gather_lanes(unsigned k, const unsigned* __restrict lanes, const uint8_t* __restrict from,
                  uint8_t* __restrict to) {
  for (unsigned j = 0; j < k; ++j) to[j] = from[lanes[j]];
}
void copy_lanes(unsigned k, const unsigned* __restrict lanes, const uint8_t* __restrict from, uint8_t* __restrict to) {
  for (unsigned j = 0; j < k; ++j) to[lanes[j]] = from[lanes[j]];
}
void scatter_lanes(unsigned k, const unsigned* __restrict lanes, const uint8_t* __restrict from, uint8_t* __restrict to,
                   uint8_t* __restrict record) {
  for (unsigned j = 0; j < k; ++j) to[lanes[j]] = record[lanes[j]] = from[j];
}

// The same three moves on a processor with SSSE3's byte shuffle, when the
// lanes are a whole number of 16-lane chunks (the rows, and the records'
// rows, are then whole chunks): each chunk of a row that holds run lanes
// is loaded whole, its run lanes picked out of it, or put back into it,
// by one shuffle, instead of a byte at a time. The run lanes of chunk c
// are work lanes offset[c] .. offset[c + 1] - 1.
class LaneChunks {
 public:
  static constexpr unsigned CHUNK = 16;
  // Whether the chunks can take the k lanes (ascending) of an array of n.
  bool set(unsigned k, const unsigned* lanes, unsigned n) {
#if defined(__x86_64__)
    static const bool shuffles = __builtin_cpu_supports("ssse3");
    if (!shuffles || k == 0 || 2 * k > n || n % CHUNK != 0 || n / CHUNK > MAX_CHUNKS) return false;
    m_used = 0;
    for (unsigned j = 0; j < k;) {
      Chunk& chunk = m_chunks[m_used++];
      chunk.first_lane = lanes[j] / CHUNK * CHUNK;
      chunk.offset = j;
      std::memset(chunk.pick, 0x80, CHUNK);  // 0x80: the shuffle gives 0
      std::memset(chunk.put, 0x80, CHUNK);
      std::memset(chunk.select, 0, CHUNK);
      for (; j < k && lanes[j] < chunk.first_lane + CHUNK; ++j) {
        const unsigned byte = lanes[j] - chunk.first_lane, at = j - chunk.offset;
        chunk.pick[at] = static_cast<uint8_t>(byte);
        chunk.put[byte] = static_cast<uint8_t>(at);
        chunk.select[byte] = 0xff;
      }
    }
    return true;
#else
    (void)k, (void)lanes, (void)n;
    return false;
#endif
  }
#if defined(__x86_64__)
  // gather_lanes. Each chunk's store writes 16 bytes from its offset on:
  // the next chunk's overwrites what is past its lanes, and the last
  // writes at most 16 bytes past the k-th lane, in the work row's
  // padding (a work array runs at most half of a row's lanes).
  __attribute__((target("ssse3"))) void gather(const uint8_t* from, uint8_t* to) const {
    for (unsigned c = 0; c < m_used; ++c) {
      const Chunk& chunk = m_chunks[c];
      store(to + chunk.offset, _mm_shuffle_epi8(load(from + chunk.first_lane), load(chunk.pick)));
    }
  }
  // copy_lanes: each chunk's run lanes from `from`, its other lanes kept.
  __attribute__((target("ssse3"))) void copy(const uint8_t* from, uint8_t* to) const {
    for (unsigned c = 0; c < m_used; ++c) {
      const Chunk& chunk = m_chunks[c];
      const __m128i select = load(chunk.select);
      uint8_t* at = to + chunk.first_lane;
      store(at, _mm_or_si128(_mm_andnot_si128(select, load(at)), _mm_and_si128(select, load(from + chunk.first_lane))));
    }
  }
  // scatter_lanes: the work lanes into each chunk's run lanes, in `to` and
  // in `record`, the chunks' other lanes kept.
  __attribute__((target("ssse3"))) void scatter(const uint8_t* from, uint8_t* to, uint8_t* record) const {
    for (unsigned c = 0; c < m_used; ++c) {
      const Chunk& chunk = m_chunks[c];
      const __m128i put = _mm_shuffle_epi8(load(from + chunk.offset), load(chunk.put));
      const __m128i select = load(chunk.select);
      uint8_t* at = to + chunk.first_lane;
      store(at, _mm_or_si128(_mm_andnot_si128(select, load(at)), put));
      at = record + chunk.first_lane;
      store(at, _mm_or_si128(_mm_andnot_si128(select, load(at)), put));
    }
  }

 private:
  static __m128i load(const uint8_t* p) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  }
  static void store(uint8_t* p, __m128i v) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p), v);
  }
#else
  void gather(const uint8_t*, uint8_t*) const {}
  void copy(const uint8_t*, uint8_t*) const {}
  void scatter(const uint8_t*, uint8_t*, uint8_t*) const {}

 private:
#endif
  static constexpr unsigned MAX_CHUNKS = 64;
  struct Chunk {
    alignas(16) uint8_t pick[CHUNK];    // byte at of the work lanes: the chunk's byte it takes, or 0x80
    alignas(16) uint8_t put[CHUNK];     // the chunk's byte: the work lane (from offset) it takes, or 0x80
    alignas(16) uint8_t select[CHUNK];  // 0xff at the chunk's run lanes
    unsigned first_lane = 0, offset = 0;
  };
  std::array<Chunk, MAX_CHUNKS> m_chunks;
  unsigned m_used = 0;
};

}  // namespace

ArrayController::EntryPlan ArrayController::plan_entry(unsigned entry) const {
  // Registers and flags by slot: register r at r, flag f (C, Z, S, M, as
  // CuArray's state rows) at registers + f.
  constexpr unsigned FLAG_C = 0, FLAG_Z = 1, FLAG_S = 2, FLAG_M = 3, FLAGS = 4;
  const unsigned cmem = m_geometry.cmem_bytes, registers = m_geometry.registers;
  std::vector<uint8_t> read(cmem, 0), written(cmem, 0), defined(registers + FLAGS, 0), live_in(registers + FLAGS, 0);
  const auto use = [&](unsigned slot) {
    if (defined[slot] == 0) live_in[slot] = 1;
  };
  std::array<unsigned, LOOP_LEVELS> starts{};
  unsigned depth = 0;
  // Marks every CMEM byte byte `byte` of `operand` may address (its loop
  // variable anywhere from 0 to its loop's start); false if that leaves
  // CMEM or the running loops.
  const auto mark = [&](const Operand& operand, unsigned byte, std::vector<uint8_t>& marks) {
    const uint64_t first = uint64_t{operand.value} + byte;
    uint64_t last = first;
    if (operand.loop != 0) {
      if (operand.loop > depth) return false;
      last += starts[operand.loop - 1];
    }
    if (last >= cmem) return false;
    std::fill(marks.begin() + static_cast<long>(first), marks.begin() + static_cast<long>(last) + 1, 1);
    return true;
  };
  const auto read_operand = [&](const Operand& operand, unsigned width) {
    for (unsigned byte = 0; byte < width; ++byte) {
      if (operand.in_cmem) {
        if (!mark(operand, byte, read)) return false;
      } else if (operand.value + byte >= registers) {
        return false;
      } else {
        use(operand.value + byte);
      }
    }
    return true;
  };
  const auto use_condition = [&](Cond cond) {
    switch (cond) {
      case Cond::c:
      case Cond::nc: use(registers + FLAG_C); break;
      case Cond::z:
      case Cond::nz: use(registers + FLAG_Z); break;
      case Cond::s:
      case Cond::ns: use(registers + FLAG_S); break;
      case Cond::hi:
      case Cond::ls:
        use(registers + FLAG_C);
        use(registers + FLAG_Z);
        break;
    }
  };
  for (unsigned pc = entry; pc < m_slots.size(); ++pc) {
    const Slot& slot = m_slots[pc];
    if (!slot.error.empty()) return {};
    const Instruction& in = slot.instruction;
    switch (in.opcode) {
      case Opcode::op_nop: continue;
      case Opcode::op_halt: {
        EntryPlan plan;
        plan.skippable = true;
        plan.last_pc = pc;
        for (unsigned a = 0; a < cmem; ++a) {
          if (read[a] != 0) plan.inputs.push_back(a);
          if (written[a] != 0) plan.cmem_out.push_back(a);
          if (read[a] != 0 || written[a] != 0) plan.gathered.push_back(a);
        }
        for (unsigned slot_index = 0; slot_index < registers + FLAGS; ++slot_index) {
          if (live_in[slot_index] != 0) plan.inputs.push_back(cmem + slot_index);
          if (live_in[slot_index] != 0) plan.gathered.push_back(cmem + slot_index);
          if (defined[slot_index] != 0) plan.defined.push_back(cmem + slot_index);
        }
        return plan;
      }
      case Opcode::op_loop:
        if (in.loop_level() != depth || depth >= LOOP_LEVELS) return {};
        starts[depth++] = in.loop_start();
        continue;
      case Opcode::op_endloop:
        if (depth == 0) return {};
        --depth;
        continue;
      case Opcode::op_nget:
      case Opcode::op_nadd:
      case Opcode::op_nadds:
      case Opcode::op_nadcs: return {};       // reads another CU
      case Opcode::op_lut: return {};         // reads the table, which the host may rewrite between runs
      case Opcode::op_zsend: return {};       // sends to the z-buffer unit: every run's pixels count
      case Opcode::op_endloopany: return {};  // the AC's control flow depends on every CU's flags
      case Opcode::op_mset:
      case Opcode::op_mclr: defined[registers + FLAG_M] = 1; continue;
      case Opcode::op_mmov:
        use_condition(in.cond());
        defined[registers + FLAG_M] = 1;
        continue;
      case Opcode::op_mand:
      case Opcode::op_mor:
        use_condition(in.cond());
        use(registers + FLAG_M);
        defined[registers + FLAG_M] = 1;
        continue;
      default: break;
    }
    const OpInfo& info = op_info(in.opcode);
    const bool uses_d = info.operands != OperandPattern::ab;
    const bool uses_b = info.operands == OperandPattern::dab || info.operands == OperandPattern::ab;
    const bool uses_a = info.operands != OperandPattern::d;
    // Every lane operation reads the mask: the useful ones are counted.
    use(registers + FLAG_M);
    if (uses_a && !read_operand(in.a, std::max(operand_width(in.opcode, 'a'), 1u))) return {};
    if (uses_b && !read_operand(in.b, std::max(operand_width(in.opcode, 'b'), 1u))) return {};
    switch (in.opcode) {
      case Opcode::op_adc:
      case Opcode::op_sbc:
      case Opcode::op_cmpc:
      case Opcode::op_rol:
      case Opcode::op_ror: use(registers + FLAG_C); break;
      default: break;
    }
    if (uses_d) {
      for (unsigned byte = 0; byte < std::max(operand_width(in.opcode, 'd'), 1u); ++byte) {
        if (in.d.in_cmem) {
          if (!mark(in.d, byte, written)) return {};
        } else if (in.d.value + byte >= registers) {
          return {};
        } else {
          defined[in.d.value + byte] = 1;
        }
      }
    }
    for (const char flag : info.flags) {
      if (flag == 'C') defined[registers + FLAG_C] = 1;
      if (flag == 'Z') defined[registers + FLAG_Z] = 1;
      if (flag == 'S') defined[registers + FLAG_S] = 1;
    }
  }
  return {};
}

std::vector<Instruction> ArrayController::build_trace(unsigned entry) const {
  struct Loop {
    unsigned body;
    unsigned step;
  };
  std::vector<Instruction> trace;
  std::array<Loop, LOOP_LEVELS> loops{};
  LoopVariables variables{};
  unsigned depth = 0;
  // Only for an entry whose run reached its halt: its words and loops are sound.
  for (unsigned pc = entry; pc < m_slots.size();) {
    const Instruction& in = m_slots[pc].instruction;
    unsigned next = pc + 1;
    switch (in.opcode) {
      case Opcode::op_nop: break;
      case Opcode::op_halt: return trace;
      case Opcode::op_loop:
        loops[depth] = {pc + 1, in.loop_step()};
        variables[depth] = static_cast<int>(in.loop_start());
        ++depth;
        break;
      case Opcode::op_endloop:
        variables[depth - 1] -= static_cast<int>(loops[depth - 1].step);
        if (variables[depth - 1] >= 0)
          next = loops[depth - 1].body;
        else
          --depth;
        break;
      case Opcode::op_mset:
      case Opcode::op_mclr:
      case Opcode::op_mmov:
      case Opcode::op_mand:
      case Opcode::op_mor: trace.push_back(in); break;
      default: {
        Instruction resolved = in;
        for (Operand* operand : {&resolved.d, &resolved.a, &resolved.b})
          if (operand->in_cmem && operand->loop != 0) {
            operand->value = static_cast<uint16_t>(operand->value + variables[operand->loop - 1]);
            operand->loop = 0;
          }
        trace.push_back(resolved);
      }
    }
    pc = next;
  }
  return trace;
}

RunResult ArrayController::run_and_record(unsigned entry, const EntryPlan& plan, EntryMemo& memo) {
  const unsigned n = m_array.lanes();
  memo.valid = false;
  memo.inputs.resize(plan.inputs.size() * n);
  for (size_t i = 0; i < plan.inputs.size(); ++i)
    std::copy_n(m_array.state_row(plan.inputs[i]), n, memo.inputs.begin() + static_cast<long>(i * n));
  if (trace_ready(memo)) {
    // The entry's trace, compiled at an earlier record, runs every CU: the
    // figures that do not depend on data are that record's.
    trace_every_lane(memo);
    RunResult result = finish_from_record(entry, plan, memo);
    record_outputs(plan, memo);
    memo.valid = true;
    return result;
  }
  const std::array<ArrayActivity, STAGE_COUNT> before = m_activity.stage_lanes;
  m_array.count_per_lane(true);
  unsigned last_pc = entry;
  RunResult result = interpret(entry, m_array, last_pc);
  m_array.count_per_lane(false);
  m_lanes_run += n;
  if (result.ok && result.instructions <= MAX_TRACE && last_pc == plan.last_pc) {
    record_outputs(plan, memo);
    memo.lane_stages.clear();
    for (unsigned stage = 0; stage < STAGE_COUNT; ++stage) {
      const ArrayActivity& after = m_activity.stage_lanes[stage];
      memo.lane_instructions[stage] = (after.lane_operations - before[stage].lane_operations) / n;
      memo.cmem_reads_per_lane[stage] = (after.cmem_reads - before[stage].cmem_reads) / n;
      if (memo.lane_instructions[stage] == 0) continue;
      memo.lane_stages.push_back(stage);
      memo.useful[stage] = m_array.lane_useful(static_cast<Stage>(stage));
      memo.stores[stage] = m_array.lane_stores(static_cast<Stage>(stage));
    }
    memo.result = result;
    memo.executions.assign(m_run_executions.begin() + entry, m_run_executions.begin() + last_pc + 1);
    memo.stages_recorded = m_record_stages;
    memo.stages = m_stage_changes;
    memo.trace = m_array.compile_trace(build_trace(entry));
    memo.traced = true;
    memo.valid = true;
  }
  fold_run(entry, last_pc, result);
  return result;
}

void ArrayController::record_outputs(const EntryPlan& plan, EntryMemo& memo) {
  const unsigned n = m_array.lanes();
  memo.outputs.resize(plan.outputs() * n);
  for (size_t i = 0; i < plan.outputs(); ++i)
    std::copy_n(m_array.state_row(plan.output_row(i)), n, memo.outputs.begin() + static_cast<long>(i * n));
}

bool ArrayController::trace_ready(const EntryMemo& memo) const {
  return memo.traced && (!m_record_stages || memo.stages_recorded);
}

void ArrayController::trace_every_lane(EntryMemo& memo) {
  m_array.run_trace(memo.trace);
  for (const unsigned stage : memo.lane_stages) {
    memo.useful[stage] = m_array.lane_useful(static_cast<Stage>(stage));
    memo.stores[stage] = m_array.lane_stores(static_cast<Stage>(stage));
  }
  m_lanes_run += m_array.lanes();
}

RunResult ArrayController::run_skipping(unsigned entry, const EntryPlan& plan, EntryMemo& memo) {
  const unsigned n = m_array.lanes();
  if (!memo.valid || (m_record_stages && !memo.stages_recorded)) return run_and_record(entry, plan, memo);
  // The CUs whose inputs, or CMEM bytes the program may write, differ
  // from their last run's.
  m_differs.assign(n, 0);
  for (size_t i = 0; i < plan.inputs.size(); ++i)
    accumulate_differences(n, m_array.state_row(plan.inputs[i]), memo.inputs.data() + i * n, m_differs.data());
  for (size_t i = 0; i < plan.cmem_out.size(); ++i)
    accumulate_differences(n, m_array.state_row(plan.cmem_out[i]), memo.outputs.data() + i * n, m_differs.data());
  m_run_lanes.clear();
  for (unsigned l = 0; l < n; ++l)
    if (m_differs[l] != 0) m_run_lanes.push_back(l);
  const auto k = static_cast<unsigned>(m_run_lanes.size());
  // Gathering and scattering costs about what running every CU does when
  // half of them run.
  if (2 * k > n) {
    if (++memo.full_runs == FULL_RUNS_BEFORE_BACK_OFF) {
      memo.full_runs = 0;
      memo.plain_runs_left = BACK_OFF_RUNS;
    }
    return run_and_record(entry, plan, memo);
  }
  memo.full_runs = 0;

  const size_t outputs = plan.outputs();
  if (k > 0 && n % WORK_LANE_BLOCK == 0 && m_run_lanes[0] / WORK_LANE_BLOCK == m_run_lanes[k - 1] / WORK_LANE_BLOCK)
    run_in_place(plan, memo, m_run_lanes[0] / WORK_LANE_BLOCK * WORK_LANE_BLOCK);
  else if (k > 0)
    run_gathered(plan, memo);
  // The skipped CUs end with the registers and flags their last run left.
  for (size_t i = plan.cmem_out.size(); i < outputs; ++i) {
    uint8_t* to = m_array.state_row(plan.output_row(i));
    const uint8_t* record = memo.outputs.data() + i * n;
    for (unsigned l = 0; l < n; ++l)
      if (m_differs[l] == 0) to[l] = record[l];
  }
  m_lanes_run += k;
  m_lanes_skipped += n - k;
  return finish_from_record(entry, plan, memo);
}

void ArrayController::run_gathered(const EntryPlan& plan, EntryMemo& memo) {
  // The run lanes gathered into the first lanes of a work array, the trace
  // run there, its results scattered back.
  const unsigned n = m_array.lanes();
  const auto k = static_cast<unsigned>(m_run_lanes.size());
  const size_t outputs = plan.outputs();
  if (!m_work) m_work = std::make_unique<CuArray>(m_geometry);
  CuArray& work = *m_work;
  // Whole vectors of lanes: the lane loops have no scalar tail (the lanes
  // after the k-th compute on stale bytes and are never read back).
  work.set_lane_count((k + WORK_LANE_BLOCK - 1) / WORK_LANE_BLOCK * WORK_LANE_BLOCK);
  // The lanes in a local: a byte stored through a row may alias the
  // vector's own pointer as far as the compiler knows, which would then
  // load it again for every lane.
  const unsigned* const lanes = m_run_lanes.data();
  LaneChunks chunks;
  const bool chunked = chunks.set(k, lanes, n);
  for (const unsigned row : plan.gathered) {
    if (chunked)
      chunks.gather(m_array.state_row(row), work.state_row(row));
    else
      gather_lanes(k, lanes, m_array.state_row(row), work.state_row(row));
  }
  for (size_t i = 0; i < plan.inputs.size(); ++i) {
    if (chunked)
      chunks.copy(m_array.state_row(plan.inputs[i]), memo.inputs.data() + i * n);
    else
      copy_lanes(k, lanes, m_array.state_row(plan.inputs[i]), memo.inputs.data() + i * n);
  }
  work.mask_written();
  // Control flow and addresses do not depend on data: this run takes the
  // recorded run's path.
  work.run_trace(memo.trace);
  for (size_t i = 0; i < outputs; ++i) {
    const unsigned row = plan.output_row(i);
    if (chunked)
      chunks.scatter(work.state_row(row), m_array.state_row(row), memo.outputs.data() + i * n);
    else
      scatter_lanes(k, lanes, work.state_row(row), m_array.state_row(row), memo.outputs.data() + i * n);
  }
  record_lane_counts<false>(memo, work);
}

void ArrayController::run_in_place(const EntryPlan& plan, EntryMemo& memo, unsigned first_lane) {
  // Every run lane in the block of WORK_LANE_BLOCK lanes from first_lane:
  // the trace runs on that block of the array itself, with nothing
  // gathered or scattered. The block's other lanes differ in nothing from
  // their last run (inputs and the CMEM bytes it writes), and control flow
  // does not depend on data, so the trace writes them what they hold.
  const unsigned n = m_array.lanes();
  const auto k = static_cast<unsigned>(m_run_lanes.size());
  const unsigned* const lanes = m_run_lanes.data();
  for (size_t i = 0; i < plan.inputs.size(); ++i)
    copy_lanes(k, lanes, m_array.state_row(plan.inputs[i]), memo.inputs.data() + i * n);
  m_array.run_trace(memo.trace, first_lane, WORK_LANE_BLOCK);
  for (size_t i = 0; i < plan.outputs(); ++i)
    copy_lanes(k, lanes, m_array.state_row(plan.output_row(i)), memo.outputs.data() + i * n);
  record_lane_counts<true>(memo, m_array);
}

template <bool kInPlace>
void ArrayController::record_lane_counts(EntryMemo& memo, const CuArray& ran) {
  const unsigned* const lanes = m_run_lanes.data();
  const auto k = static_cast<unsigned>(m_run_lanes.size());
  for (const unsigned stage : memo.lane_stages) {
    const uint32_t* useful = ran.lane_useful(static_cast<Stage>(stage)).data();
    const uint32_t* stores = ran.lane_stores(static_cast<Stage>(stage)).data();
    for (unsigned j = 0; j < k; ++j) {
      const unsigned from = kInPlace ? lanes[j] : j;
      memo.useful[stage][lanes[j]] = useful[from];
      memo.stores[stage][lanes[j]] = stores[from];
    }
  }
}

RunResult ArrayController::finish_from_record(unsigned entry, const EntryPlan& plan, const EntryMemo& memo) {
  const unsigned n = m_array.lanes();
  // The run's figures are the recorded run's: they do not depend on data.
  m_stage_changes.clear();
  if (m_record_stages) m_stage_changes = memo.stages;
  std::copy(memo.executions.begin(), memo.executions.end(), m_run_executions.begin() + entry);
  m_array.mask_written();
  // The lanes' activity stage by stage, as interpret() folds it (no nget:
  // no neighbour transfers), from the record's counts per lane.
  ArrayActivity total;
  for (const unsigned stage : memo.lane_stages) {
    ArrayActivity counts;
    counts.lane_operations = memo.lane_instructions[stage] * n;
    counts.cmem_reads = memo.cmem_reads_per_lane[stage] * n;
    for (unsigned l = 0; l < n; ++l) {
      counts.useful_operations += memo.useful[stage][l];
      counts.cmem_writes += memo.stores[stage][l];
    }
    m_activity.stage_lanes[stage] += counts;
    total += counts;
  }
  m_array.add_activity(total);
  fold_run(entry, plan.last_pc, memo.result);
  return memo.result;
}

}  // namespace tessera::ap
