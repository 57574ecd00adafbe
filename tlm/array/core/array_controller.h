// The array controller's functional core, plain C++: the program memory
// (kept decoded, each word decoded when it is written), the loop counters,
// and the run of a program from an entry point to its halt on the CU array,
// counting the cycles each instruction costs.
//
// A program runs as a whole: run() executes every instruction at once and
// returns the cycles the array took; the SystemC wrapper (array_processor.h)
// turns them into time at the array clock.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "array/core/cu_array.h"
#include "array/isa/ap_isa.h"

namespace tessera::ap {

// Cycles of every instruction (array.cycles.<mnemonic>) and the extra
// cycles of an RM-form instruction with an operand in CMEM.
struct CycleTable {
  std::array<unsigned, OPCODE_COUNT> cycles{};
  unsigned cmem_operand = 1;  // the default of array.cycles.cmem_operand (docs/calibration.md)
  // Every instruction at its ap_isa.def cycles (array.cycles.*'s defaults).
  static CycleTable defaults();
  // The cost of one execution of `instruction`.
  unsigned cost(const Instruction& instruction) const;
};

// Why a program stopped early; the AC's ERROR_CODE register holds the value.
enum class RunError : uint8_t {
  none = 0,
  bad_word = 1,
  loop = 2,
  cmem_address = 3,
  past_end = 4,
  too_long = 5,
  lut_index = 6,  // a lut index beyond the table (array.lut.entries)
};
const char* run_error_name(RunError error);

struct RunResult {
  bool ok = true;
  RunError kind = RunError::none;
  uint64_t cycles = 0;
  uint64_t instructions = 0;
  std::string error;  // when !ok: what went wrong, naming the program word
  unsigned error_pc = 0;
};

// Totals over every program run since construction (or clear_activity()).
struct ControllerActivity {
  uint64_t programs = 0;
  uint64_t failed_programs = 0;
  uint64_t cycles = 0;
  uint64_t instructions = 0;  // instructions broadcast (loop iterations counted)
  std::array<uint64_t, OPCODE_COUNT> instruction_mix{};
  std::array<uint64_t, STAGE_COUNT> stage_cycles{};
  // The instructions and the lanes' activity per stage, so that the energy of
  // some stages alone (a pass's, without the clears) can be told apart.
  std::array<uint64_t, STAGE_COUNT> stage_instructions{};
  std::array<std::array<uint64_t, OPCODE_COUNT>, STAGE_COUNT> stage_mix{};  // instruction_mix per stage
  std::array<ArrayActivity, STAGE_COUNT> stage_lanes{};
  std::vector<uint64_t> word_cycles;  // per program word: the profile
  std::vector<uint64_t> word_executions;
  // Delayed execution: the (lanes - 1) x K cycles after the first lane's
  // halt until the last lane's, in every program that halted (also in
  // cycles, in the halt's word and stage).
  uint64_t skew_cycles = 0;
  // The cycles the AC waited for the lookup table's ports (also in cycles,
  // in the lut's word and stage).
  uint64_t lut_stall_cycles = 0;
  // zsend (the z-buffer unit's port, set_pixel_port): the cycles the AC
  // waited for the port (also in cycles, in the waiting zsend's or halt's
  // word and stage), the cycles the port was busy, and the pixels sent.
  uint64_t zbuf_stall_cycles = 0;
  uint64_t zbuf_port_cycles = 0;
  uint64_t zbuf_pixels = 0;
  // endloopany (array.features.wired_or_loop): the loops it left before
  // their count ran out, and the iterations the count would still have run.
  uint64_t wired_or_exits = 0;
  uint64_t wired_or_iterations_saved = 0;
};

class ArrayController {
 public:
  ArrayController(const ArrayGeometry& geometry, const CycleTable& cycles, unsigned program_words,
                  uint64_t max_program_cycles);

  CuArray& array() { return m_array; }
  const CuArray& array() const { return m_array; }
  unsigned program_words() const { return static_cast<unsigned>(m_words.size()); }

  // The instructions the array runs (ap_isa.def's feature column): by
  // default the J2210's own. A word holding any other is refused like a
  // word that does not decode (RunError::bad_word), the error naming the
  // switch that enables it.
  void enable_ops(const EnabledOps& enabled);

  // Delayed execution (array.issue_skew = lane): lane i runs each
  // instruction `cycles` (K, array.issue_skew_cycles) after lane i - 1 of
  // the chain (lanes in row-major order). 0: lockstep, the J2210. The
  // neighbour reads follow CuArray::set_issue_skew; a program that halts
  // takes (lanes - 1) x K cycles more, and lut's stalls follow the chain
  // (README.md, "Delayed execution", "The lookup table").
  void set_issue_skew(unsigned cycles);
  // Delayed execution by lane or by row (array.issue_skew = row: row r runs
  // each instruction r x `cycles` after row 0, the CUs of a row together,
  // MorphoSys's row-sequential issue): the neighbour reads follow
  // CuArray::set_issue_skew; a program that halts takes (rows - 1) x K
  // cycles more; zsend's reservation is per row (set_pixel_port), and a
  // row's lookups take ceil(columns / P) cycles, which must fit in K (a lut
  // is refused otherwise: the rows' lookups would collide).
  void set_issue_skew(IssueSkew unit, unsigned cycles);
  IssueSkew issue_skew() const { return m_skew_unit; }
  // The lookup table's ports (array.lut.ports): without skew, P lanes look
  // up per cycle, so a lut takes ceil(lanes / P) - 1 cycles more than its
  // array.cycles.lut; with lane skew, each lut holds one port while its
  // lookups run down the chain, (lanes - 1) x K + 1 cycles, and a lut
  // finding every port held waits for the first to free; with row skew, a
  // row's lookups take ceil(columns / P) cycles, ceil(columns / P) - 1 more
  // than array.cycles.lut.
  void set_lut_ports(unsigned ports);
  // The z-buffer unit's port that zsend sends to (tlm/zbuf), or nullptr:
  // without one, a word holding zsend is refused like a disabled one. The
  // port's reservation over the instruction stream (tlm/zbuf/README.md,
  // "Timing"): a zsend issues when the port has taken every pixel of the
  // previous one (each CU holds one pixel until the unit takes it), and
  // then holds the port for the cycles the unit answers; the AC meanwhile
  // runs on. A halt waits for the port too, so the unit's planes are
  // complete when the program's interrupt rises. Under row skew the same
  // per row: row r's pixels reach the port r x K after the issue, and a
  // zsend or halt waits (the whole stream) until every row's earlier
  // pixels are taken by the time that row runs it. Under lane skew a zsend
  // is refused (not modelled). Under either skew an endloopany is refused
  // (its wired OR would wait for the last CU or row).
  void set_pixel_port(PixelPort* port);

  // Program memory. write_word() returns false when `index` is beyond it.
  bool write_word(unsigned index, uint64_t word);
  uint64_t word(unsigned index) const { return index < m_words.size() ? m_words[index] : 0; }
  // Writes `words` from `first` on; false (nothing written) if they do not fit.
  bool load(unsigned first, const std::vector<uint64_t>& words);

  // Runs from `entry` to a halt. On an error (an undecodable word, a loop
  // the AC cannot run, a CMEM address out of range, more than
  // max_program_cycles) the run stops at that word with ok == false; the
  // state keeps what the instructions before it did. Except a runaway: the
  // AC's control flow does not depend on data (counted loops, no
  // branches), so a program whose loops take it past max_program_cycles is
  // known before it runs (find_runaway) and stops at once, at the word and
  // cycle count where the cap would have stopped it, without running (the
  // state as it was; a billion-cycle program used to hold the simulation
  // for a minute).
  RunResult run(unsigned entry);

  // Where the run from `entry` would pass max_program_cycles, if its
  // control flow alone says so: the word, the cycles and instructions up to
  // and including it. Empty when the run halts within the cap, or when
  // something else might stop it first (a bad word, a loop error, a CMEM
  // address the loop variables could take beyond CMEM): run() finds those
  // by running. A loop closed by endloopany counts at its most iterations
  // (its count), whatever the CUs' flags would make it run: the cap bounds
  // the worst case, and whether a program is refused does not depend on
  // data.
  struct Runaway {
    unsigned pc = 0;
    uint64_t cycles = 0;
    uint64_t instructions = 0;
  };
  std::optional<Runaway> find_runaway(unsigned entry) const;

  const ControllerActivity& activity() const { return m_activity; }

  // With recording on, run() keeps where the stage changed (the cycle, from
  // the program's start, at which an instruction of a new stage began), for
  // the VCD's stage signal. Off by default: a loop that alternates stages
  // changes them millions of times.
  struct StageChange {
    uint64_t cycle;
    Stage stage;
  };
  void record_stages(bool on) { m_record_stages = on; }
  const std::vector<StageChange>& stage_changes() const { return m_stage_changes; }

  // Skipping idle CUs (array.skip_idle_cus; README.md, "Skipping idle
  // CUs"). A program's work in one CU is a function of that CU's inputs
  // alone when the program has no nget (nor any other instruction that
  // reads another CU, the lookup table, the z-buffer's port, or makes the
  // AC's control flow depend on the CUs, endloopany): the CMEM bytes it may read and the
  // registers and flags it reads before writing them (the mask included,
  // which every lane operation reads to count the useful ones), since its
  // control flow and addresses do not depend on data. So a CU whose inputs
  // hold what they held when it last ran the program, and whose CMEM bytes
  // the program may write hold what they held at that run's end, would do
  // exactly what it did then: it changes no CMEM byte and ends with the
  // registers and flags it ended with then. The controller keeps, per entry,
  // each CU's inputs and outputs of its last run and its counts (useful
  // operations, CMEM bytes stored); it runs the program only on the CUs
  // whose state differs (gathered into a work array), gives the others
  // their registers and flags from that record, and adds their counts as
  // they were, stage by stage (the instructions' stages: the activity per
  // stage is the same as well). The cycles, the profile and the stage
  // changes do not depend on data and are the same either way. Off: every
  // CU runs every program.
  void skip_idle_cus(bool on) { m_skip_idle = on; }
  // CUs run and CUs skipped since construction (not statistics: the
  // statistics are the same with skipping on and off).
  uint64_t lanes_run() const { return m_lanes_run; }
  uint64_t lanes_skipped() const { return m_lanes_skipped; }

 private:
  struct Slot {
    Instruction instruction;
    unsigned cost = 0;
    std::string error;  // why the word cannot run, or empty
  };
  void decode_slot(unsigned index);
  std::optional<Runaway> walk_for_runaway(unsigned entry) const;
  // The run's loop on `array` (m_array or the work array); the counts per
  // word stay in m_run_executions up to `last_pc` for fold_run().
  RunResult interpret(unsigned entry, CuArray& array, unsigned& last_pc);
  void fold_run(unsigned entry, unsigned last_pc, const RunResult& result);

  // What a program from one entry reads and writes, from its text: the
  // state rows of CuArray::state_row(). Skippable: no nget, nadd, nadds,
  // nadcs, lut, zsend or endloopany, and it
  // reaches its halt with every word decoded and every loop well formed.
  struct EntryPlan {
    bool skippable = false;
    unsigned last_pc = 0;            // its halt
    std::vector<unsigned> inputs;    // CMEM rows it may read, registers and flags read before written
    std::vector<unsigned> cmem_out;  // CMEM rows it may write
    std::vector<unsigned> defined;   // registers and flags it writes
    std::vector<unsigned> gathered;  // inputs and cmem_out, each row once: what a work array needs
    // The record's outputs: cmem_out, then defined.
    size_t outputs() const { return cmem_out.size() + defined.size(); }
    unsigned output_row(size_t i) const { return i < cmem_out.size() ? cmem_out[i] : defined[i - cmem_out.size()]; }
  };
  EntryPlan plan_entry(unsigned entry) const;
  // Per entry, every CU's last run of it (lanes() bytes per row, row-major)
  // and the run's figures that do not depend on data.
  struct EntryMemo {
    bool valid = false;
    std::vector<uint8_t> inputs;   // inputs x lanes, at the run's start
    std::vector<uint8_t> outputs;  // (cmem_out, then defined) x lanes, at its end
    // Per stage: per lane, the useful operations and CMEM bytes stored; the
    // instructions that did lane work and the CMEM bytes each lane read
    // (the same in every lane); the stages with lane work.
    std::array<std::vector<uint32_t>, STAGE_COUNT> useful, stores;
    std::array<uint64_t, STAGE_COUNT> lane_instructions{}, cmem_reads_per_lane{};
    std::vector<unsigned> lane_stages;
    RunResult result;
    std::vector<uint64_t> executions;  // per word from the entry to last_pc
    bool stages_recorded = false;
    std::vector<StageChange> stages;
    // The run's instructions in the order they ran, loop variables added,
    // compiled (CuArray::compile_trace): what the CUs that differ run.
    // Kept while the record is taken again (valid false): it depends on the
    // program alone. Every CU then runs it in place of the interpreter
    // (trace_every_lane), while the run still needs every CU (back-off) or
    // is recorded again.
    CuArray::CompiledTrace trace;
    bool traced = false;
    // Back-off: after FULL_RUNS_BEFORE_BACK_OFF runs in a row with most CUs
    // differing, the next BACK_OFF_RUNS run on every CU without the record
    // (what comparing and recording would cost for nothing).
    unsigned full_runs = 0;
    unsigned plain_runs_left = 0;
  };
  std::vector<Instruction> build_trace(unsigned entry) const;
  RunResult run_skipping(unsigned entry, const EntryPlan& plan, EntryMemo& memo);
  RunResult run_and_record(unsigned entry, const EntryPlan& plan, EntryMemo& memo);
  // run_skipping's run of the lanes in m_run_lanes (at least one): gathered
  // into a work array, or in place when they are all in one block of lanes
  // (from first_lane); each updates the record's inputs, outputs and counts
  // of those lanes.
  void run_gathered(const EntryPlan& plan, EntryMemo& memo);
  void run_in_place(const EntryPlan& plan, EntryMemo& memo, unsigned first_lane);
  // The run lanes' counts per stage into the record, from the array `ran`
  // ran them on: at each lane's own index (kInPlace), or at its place
  // among the run lanes (gathered into a work array).
  template <bool kInPlace>
  void record_lane_counts(EntryMemo& memo, const CuArray& ran);
  void record_outputs(const EntryPlan& plan, EntryMemo& memo);
  // The entry's compiled trace can run it: compiled, with the stage changes
  // when they are recorded.
  bool trace_ready(const EntryMemo& memo) const;
  // The trace on every CU in place; their counts into the record.
  void trace_every_lane(EntryMemo& memo);
  // A run whose lanes have run (or were skipped) by the record: its cycles,
  // profile, stage changes and activity from the record, folded in.
  RunResult finish_from_record(unsigned entry, const EntryPlan& plan, const EntryMemo& memo);

  ArrayGeometry m_geometry;
  CycleTable m_cycles;
  uint64_t m_max_cycles;
  CuArray m_array;
  std::vector<uint64_t> m_words;
  std::vector<Slot> m_slots;
  ControllerActivity m_activity;
  std::vector<uint64_t> m_run_executions;  // per word, during run(): executions so far, folded in at its end
  // find_runaway's answer per entry word, until program memory is written:
  // a renderer starts the same programs thousands of times a frame.
  mutable std::unordered_map<unsigned, std::optional<Runaway>> m_runaways;
  bool m_record_stages = false;
  std::vector<StageChange> m_stage_changes;
  bool m_skip_idle = false;
  EnabledOps m_enabled = j2210_ops();
  unsigned m_skew = 0;  // K, 0 for lockstep
  IssueSkew m_skew_unit = IssueSkew::none;
  // The cycles after the first lane's (row's) halt until the last's.
  uint64_t skew_cycles() const;
  unsigned m_lut_ports = 1;  // P
  // With skew: per port, the run's cycle from which it is free (during run()).
  std::vector<uint64_t> m_lut_port_free;
  PixelPort* m_pixel_port = nullptr;
  // During run(): the run's cycle from which the z-buffer's port has taken
  // every pixel sent, and per row every pixel of that row.
  uint64_t m_zbuf_port_free = 0;
  std::vector<uint64_t> m_zbuf_row_free;
  // The port's reservation (tlm/zbuf/README.md, "Timing"): K under row
  // skew, else 0; the stall before a zsend or halt due at `now`; a zsend's
  // pixels, issued at `now`, sent and reserved.
  uint64_t zbuf_row_delay() const;
  uint64_t zbuf_stall(uint64_t now) const;
  void send_to_zbuf(uint64_t now, const std::vector<SentPixel>& pixels);
  // The extra cycles of one lut without skew (folded into its slot's cost).
  unsigned lut_lockstep_stall() const;
  std::unordered_map<unsigned, EntryPlan> m_plans;  // until program memory is written
  std::unordered_map<unsigned, EntryMemo> m_memos;  // likewise
  std::unique_ptr<CuArray> m_work;                  // made at the first skip
  std::vector<uint8_t> m_differs;                   // per lane, during a run
  std::vector<unsigned> m_run_lanes;
  uint64_t m_lanes_run = 0, m_lanes_skipped = 0;
};

}  // namespace tessera::ap
