// The whole CU array's architectural state and one broadcast instruction at
// a time, in plain C++ (no SystemC).
//
// State is laid out structure-of-arrays: one row of `lanes` bytes per CMEM
// address, per register and per flag (C, Z, S, M), rows `stride` bytes
// apart. An operand, register or CMEM address, is then a pointer to a row,
// and an instruction is one loop over the lanes that the compiler
// vectorises. Lane l is the CU at row l / columns, column l % columns (row
// 0 at the top, column 0 at the left).
//
// Semantics are those of datapath/cu_alu.h, lane by lane; where a CMEM
// write lands only in lanes whose mask M is set, registers and flags are
// written in every lane (the spec: a masked CU does not store).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "array/core/pixel_port.h"
#include "array/datapath/cu_alu.h"
#include "array/isa/ap_isa.h"

namespace tessera::ap {

// The CU grid; by default the J2210's (ap_isa.h), as array.* defaults to.
struct ArrayGeometry {
  unsigned columns = J2210::COLUMNS;
  unsigned rows = J2210::ROWS;
  unsigned registers = J2210::REGISTERS;
  unsigned cmem_bytes = J2210::CMEM_BYTES;
  unsigned lanes() const { return columns * rows; }
};

using LoopVariables = std::array<int, LOOP_LEVELS>;

// Delayed execution (array.issue_skew): none, every CU runs an instruction
// in the same cycle (the J2210); lane, the CUs one after another in
// row-major order (the Image Blender); row, the rows one after another,
// the CUs of a row together (MorphoSys's row-sequential issue).
enum class IssueSkew : uint8_t { none, lane, row };

// What the array did, summed over every instruction it executed. Lane
// counts are lanes x instructions; CMEM counts are bytes accessed in all
// lanes together.
struct ArrayActivity {
  uint64_t lane_operations = 0;      // lanes x instructions that did lane work
  uint64_t useful_operations = 0;    // of those, lanes whose mask was set
  uint64_t cmem_reads = 0;           // bytes read from CMEM, all lanes
  uint64_t cmem_writes = 0;          // bytes written to CMEM (unmasked lanes only)
  uint64_t neighbour_transfers = 0;  // lanes that read a neighbour (not counting reads beyond the edge)
  ArrayActivity& operator+=(const ArrayActivity& more) {
    lane_operations += more.lane_operations;
    useful_operations += more.useful_operations;
    cmem_reads += more.cmem_reads;
    cmem_writes += more.cmem_writes;
    neighbour_transfers += more.neighbour_transfers;
    return *this;
  }
};

class CuArray {
 public:
  explicit CuArray(const ArrayGeometry& geometry);

  const ArrayGeometry& geometry() const { return m_geometry; }
  unsigned lanes() const { return m_lanes; }

  // Every register, flag and CMEM byte 0, every mask set.
  void reset();

  uint8_t cmem(unsigned lane, unsigned address) const { return m_storage[row_offset(address) + lane]; }
  void set_cmem(unsigned lane, unsigned address, uint8_t value) { m_storage[row_offset(address) + lane] = value; }
  uint8_t reg(unsigned lane, unsigned index) const { return m_storage[row_offset(m_reg_rows[index]) + lane]; }
  void set_reg(unsigned lane, unsigned index, uint8_t value) {
    m_storage[row_offset(m_reg_rows[index]) + lane] = value;
  }
  CuFlags flags(unsigned lane) const;
  void set_flags(unsigned lane, const CuFlags& flags);
  bool mask(unsigned lane) const { return m_storage[row_offset(m_flag_row + 3) + lane] != 0; }
  void set_mask(unsigned lane, bool mask);
  unsigned active_lanes() const { return active(); }

  // Executes one instruction that does lane work (not nop, halt, loop or
  // endloop). Returns an empty string, or why it could not run (a CMEM
  // address plus loop variable beyond CMEM, a loop variable of a loop that
  // is not running), in which case no state has changed.
  std::string execute(const Instruction& instruction, const LoopVariables& loop_variables, unsigned active_loops);
  // The same, for the AC's run loop: true, or false with `error` set.
  bool execute(const Instruction& instruction, const LoopVariables& loop_variables, unsigned active_loops,
               std::string& error);

  // endloopany's wired OR: whether any lane whose mask is set has `cond`
  // on its flags.
  bool any_active_holds(Cond cond);

  const ArrayActivity& activity() const { return m_activity; }
  void add_activity(const ArrayActivity& more);

  // Delayed execution (array.issue_skew; README.md, "Delayed execution"):
  // lane, the lanes run each instruction one after another in chain order
  // (lane 0, 1, 2, ...: row-major), so a neighbour read from an earlier lane
  // (left, up) sees its state after the instruction, one from a later lane
  // (right, down) its state before it; row, the rows run it one after
  // another and the lanes of a row together, so up sees the state after
  // the instruction, and down, left and right (the same row, the row ring's
  // wrap included) before it. Only the neighbour reads can tell; every
  // other instruction's result is the same either way.
  void set_issue_skew(IssueSkew skew) { m_skew = skew; }
  void set_issue_skew(bool on) { m_skew = on ? IssueSkew::lane : IssueSkew::none; }
  IssueSkew issue_skew() const { return m_skew; }
  // The row ring (array.row_ring; README.md, "The row ring"): column 0's
  // left neighbour is the same row's last column and the last column's right
  // neighbour is column 0, for every neighbour read; up and down keep the
  // grid's edges. Under skew the wrapped link follows the read rule like any
  // other: under lane skew column 0 reads the last column, a later lane,
  // before the instruction and the last column reads column 0 after it;
  // under row skew both read the same row, before it.
  void set_row_ring(bool on);
  bool row_ring() const { return m_ring; }

  // The shared lookup table of lut (array.features.lut): `entries` 16-bit
  // entries, all 0. The host writes it (the AC's LUT_INDEX and LUT_DATA).
  void set_lut_entries(unsigned entries) { m_lut.assign(entries, 0); }
  unsigned lut_entries() const { return static_cast<unsigned>(m_lut.size()); }
  uint16_t lut_entry(unsigned index) const { return m_lut[index]; }
  void set_lut_entry(unsigned index, uint16_t value) { m_lut[index] = value; }
  // Why the last execute() that returned false failed: an operand (a CMEM
  // address or a loop variable) or a lut index beyond the table.
  enum class Fault : uint8_t { operand, lut_index };
  Fault last_fault() const { return m_fault; }
  // The pixels the last zsend read, one per CU whose mask was set, in
  // ascending lanes (x = a:a+1, y = a+2:a+3, z = b:b+1, colour = b+2:b+3).
  // Every CU reads its operands, masked or not; only the masked-in ones send.
  const std::vector<SentPixel>& sent_pixels() const { return m_sent; }

  // For the controller's skipping of idle CUs (array_controller.h): every
  // row of architectural state by one index, CMEM address a at a, register
  // r at cmem_bytes + r, then the flags C, Z, S and M (state_flag_row()).
  unsigned state_rows() const { return m_geometry.cmem_bytes + m_geometry.registers + 4; }
  unsigned state_flag_row(unsigned flag) const { return m_geometry.cmem_bytes + m_geometry.registers + flag; }
  uint8_t* state_row(unsigned index) {
    if (index < m_geometry.cmem_bytes) return row(index);
    if (index < m_geometry.cmem_bytes + m_geometry.registers) return row(m_reg_rows[index - m_geometry.cmem_bytes]);
    return row(m_flag_row + (index - m_geometry.cmem_bytes - m_geometry.registers));
  }
  // To call after writing the mask's row through state_row().
  void mask_written() { m_active_stale = true; }
  // A work array runs on its first `lanes` lanes only (at most the
  // geometry's), which it then takes as lanes 0..lanes-1 of no grid: its
  // neighbour reads are meaningless, so only programs without nget, nadd
  // or lut run on it.
  void set_lane_count(unsigned lanes);
  // With counting on, execute() also counts per lane and per stage (the
  // instruction's) the useful operations and the CMEM bytes stored
  // (lane_useful(), lane_stores()), from 0 at clear_lane_counts().
  void count_per_lane(bool on);
  void clear_lane_counts();
  const std::vector<uint32_t>& lane_useful(Stage stage) const { return m_lane_useful[static_cast<unsigned>(stage)]; }
  const std::vector<uint32_t>& lane_stores(Stage stage) const { return m_lane_stores[static_cast<unsigned>(stage)]; }
  // A program's instructions in the order a run executed them, loop
  // variables already added to the addresses (no loop, halt, nget, nadd,
  // nadds, nadcs, lut or zsend; every address within CMEM), made ready to
  // run (compile_trace): per instruction its handler, the one for its
  // opcode and the kind of its destination, and the byte offsets of its
  // rows in the array's storage (two neighbouring one-byte instructions
  // of a frequent pair share a step: FUSED_PAIRS); the lane operations
  // and CMEM stores between two changes of the mask or the stage, which
  // do not depend on data, summed in advance at the change (README.md,
  // "Skipping idle CUs").
  struct TraceStep {
    uint16_t handler = 0;
    uint8_t cond = 0;                     // mmov, mand, mor
    uint8_t stage = 0;                    // a stage change's new stage
    uint32_t operations = 0, stores = 0;  // at a mask or stage change: since the last one
    std::array<uint32_t, 3> d{};          // the destination's rows (its bytes)
    uint32_t a = 0, a_low = 0, b = 0, b_low = 0;
  };
  struct CompiledTrace {
    std::vector<TraceStep> steps;
    uint8_t first_stage = 0;
    uint32_t tail_operations = 0, tail_stores = 0;  // after the last change
    size_t storage_bytes = 0;                       // the layout the offsets are for (its size and stride)
    size_t stride = 0;
  };
  // Valid for any array of this one's geometry; run_trace() refuses one
  // compiled for another layout (std::logic_error).
  CompiledTrace compile_trace(const std::vector<Instruction>& trace) const;
  // Runs a compiled trace as execute() would run its instructions, counting
  // per lane and stage only (lane_useful(), lane_stores(), from 0;
  // activity() does not change). Registers are not renamed: each
  // instruction's result is copied into its register, whose row the
  // trace's offsets name.
  void run_trace(const CompiledTrace& trace);
  // run_trace on a window of the lanes only, `lanes` from `first_lane` (a
  // multiple of 16; the window within the array's lanes): the other lanes'
  // rows are left as they are, and their counts at 0 (std::logic_error
  // for a window that is not).
  void run_trace(const CompiledTrace& trace, unsigned first_lane, unsigned lanes);

 private:
  // compile_trace's flags per instruction: the flags each sets that a later
  // instruction, mask condition or the trace's end reads before another
  // sets them (the others are not computed; FlagWrites in cu_array.cpp).
  std::vector<uint8_t> live_flag_writes(const std::vector<Instruction>& trace) const;
  size_t row_offset(unsigned row) const { return (size_t{row} + 1) * m_stride; }  // row 0 is a guard
  uint8_t* row(unsigned index) { return m_storage.data() + row_offset(index); }
  // The row of byte `byte` of `operand`, or nullptr when it is beyond CMEM
  // or uses a loop variable of a loop that is not running;
  // operand_error() then says which.
  uint8_t* operand_row(const Operand& operand, unsigned byte, const LoopVariables& loop_variables,
                       unsigned active_loops);
  std::string operand_error(const Operand& operand, unsigned byte, const LoopVariables& loop_variables,
                            unsigned active_loops) const;
  // Copies a whole row (the lanes and the padding after them, which no lane
  // reads) in fixed-size blocks the compiler keeps inline.
  void copy_row(uint8_t* __restrict destination, const uint8_t* __restrict source) const;
  // The lanes whose mask is set, counted when first needed after a mask
  // instruction (several often follow each other).
  unsigned active() const {
    if (m_active_stale) count_active();
    return m_active;
  }
  void count_active() const;
  // lut: true when every lane's index (high:low) lies within the table,
  // else false with `error` naming the first lane that does not.
  bool lut_indices_fit(const uint8_t* high, const uint8_t* low, std::string& error);
  // zsend: reads both 4-byte operands in every lane, the masked-in lanes'
  // pixels into m_sent.
  bool send_pixels(const Instruction& in, const LoopVariables& loop_variables, unsigned active_loops,
                   std::string& error);
  // nget and nadd: the neighbour's byte of row `a` into `neighbour`, and for
  // nadd d + it into `out` with the flags; in chain order under skew when
  // the neighbour is an earlier lane and `a` is d's row.
  void neighbour_lanes(const Instruction& in, const uint8_t* a, const uint8_t* d, bool d_masked, uint8_t* neighbour,
                       uint8_t* out);
  // The same, lane by lane in chain order, for the row ring and for nadds
  // and nadcs (whose source row, a or a + 1, each lane chooses by its S):
  // `a_next` is the row of a + 1 (nadds, nadcs) or nullptr.
  void neighbour_lanes_in_order(const Instruction& in, const uint8_t* a, const uint8_t* a_next, const uint8_t* d,
                                bool d_masked, uint8_t* neighbour, uint8_t* out);
  // Undoes the renaming of registers (each register back in its own row),
  // for run_trace().
  void unrename_registers();

  // What execute() needs of each opcode, from the ISA's tables.
  struct OpLanes {
    uint8_t d_width = 0, a_width = 0, b_width = 0;
    bool uses_d = false, uses_a = false, uses_b = false;
    uint8_t writes = 0;  // the flags it sets (ap_isa.def's flags), as cu_array.cpp's FlagWrites
  };

  ArrayGeometry m_geometry;
  unsigned m_lanes;
  size_t m_stride;
  size_t m_copy_bytes;  // the lanes rounded up to copy_row's block, at most m_stride
  unsigned m_reg_row, m_flag_row, m_scratch_row;
  // Registers are renamed: an instruction computes its result into a spare
  // row, which then becomes the destination register's row (the register's
  // old row the spare), instead of being copied. m_reg_rows[r] is register
  // r's row; beyond the register file (an instruction check_limits refuses)
  // the rows after it, as without renaming. m_spare_rows are the spare rows:
  // the result, the neighbour's bytes, the multiply's three product bytes.
  std::array<unsigned, MAX_REGISTERS + 3> m_reg_rows{};
  std::array<unsigned, 5> m_spare_rows{};
  std::vector<uint8_t> m_storage;
  // Per direction, 0xff where the lane has a neighbour that way, else 0.
  std::array<std::vector<uint8_t>, 4> m_has_neighbour;
  std::array<int, 4> m_neighbour_step{};
  std::array<unsigned, 4> m_lanes_with_neighbour{};
  mutable unsigned m_active = 0;
  mutable bool m_active_stale = false;
  ArrayActivity m_activity;
  bool m_count_lanes = false;
  // By stage, then lane.
  std::array<std::vector<uint32_t>, STAGE_COUNT> m_lane_useful, m_lane_stores;
  std::vector<uint8_t> m_trace_counts;   // run_trace's counts since they were last widened, a byte per lane
  std::array<OpLanes, 64> m_op_lanes{};  // by opcode: the word's 6-bit field
  IssueSkew m_skew = IssueSkew::none;
  bool m_ring = false;
  // Under skew, whether lane `from` has run the current instruction before
  // lane `to` reads it (an earlier lane, or a CU of an earlier row).
  bool runs_before(size_t from, size_t to) const {
    if (m_skew == IssueSkew::lane) return from < to;
    if (m_skew == IssueSkew::row) return from / m_geometry.columns < to / m_geometry.columns;
    return false;
  }
  // Per direction and lane, the neighbour's lane, or -1 beyond the edge
  // (with the row ring, left and right wrap); for neighbour_lanes_in_order.
  std::array<std::vector<int>, 4> m_neighbour_lane;
  std::vector<uint16_t> m_lut;
  std::vector<SentPixel> m_sent;
  Fault m_fault = Fault::operand;
};

}  // namespace tessera::ap
