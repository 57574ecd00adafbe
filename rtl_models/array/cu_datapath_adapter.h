// Thin adapter over the Verilated cu_datapath.sv (one CU of the array
// processor), speaking the types of contract/array/isa/ap_isa.h and
// tlm/array/datapath/cu_alu.h: an ap::Instruction goes in with the CMEM and
// neighbour bytes the array would hand the CU, the CMEM write comes out, and
// the registers, flags and mask are read back for comparison. The Verilator
// headers stay in the .cpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "array/core/cu_array.h"
#include "array/datapath/cu_alu.h"
#include "array/isa/ap_isa.h"

class VerilatedContext;
class Vcu_datapath;

namespace tessera::ap {

// The CMEM bytes of the instruction's memory operands, read by the array at
// the operands' addresses (loop variables added): a[0] at a, a[1] at a + 1
// (the multiplicand's low byte, used by mulm only), b at b.
struct CuOperandBytes {
  std::array<uint8_t, 2> a{};
  uint8_t b = 0;
  uint8_t d = 0;  // the byte at d, which nadds and nadcs add into
};

// For nget: each neighbour's byte (its register a, or its CMEM byte at a),
// indexed by Direction, and whether the neighbour exists.
struct CuNeighbours {
  std::array<uint8_t, 4> value{};
  std::array<bool, 4> present{};
  std::array<uint8_t, 4> next{};  // the byte at a + 1, for nadds and nadcs
};

// The CU's store into its CMEM: data[i] for address d + i, written where
// enable[i] (already gated by the mask).
struct CuCmemWrite {
  std::array<uint8_t, 3> data{};
  std::array<bool, 3> enable{};
};

// What the array hands CU `lane` of `array` for `instruction`, read from the
// state before it runs: the CMEM bytes at the operand addresses (loop
// variables added; 0 for a byte beyond CMEM or an operand in a register) and,
// for nget, the neighbours' register a or CMEM byte at a (0 and absent
// beyond the grid's edge).
struct CuLaneInputs {
  CuOperandBytes operands;
  CuNeighbours neighbours;
};
CuLaneInputs cu_lane_inputs(const CuArray& array, unsigned lane, const Instruction& instruction,
                            const LoopVariables& loop_variables);

class CuDatapathRtl {
 public:
  // The Registers parameter the unit is Verilated with (its default).
  static constexpr unsigned REGISTERS = 8;
  // Clock edges from taking an instruction to done_o: one shift-and-add
  // step per edge for the multiply, one edge for everything else.
  static constexpr unsigned MUL_CYCLES = 8;
  static constexpr unsigned ALU_CYCLES = 1;

  // Builds the model and applies reset: registers and flags 0, mask set.
  CuDatapathRtl();
  ~CuDatapathRtl();
  CuDatapathRtl(const CuDatapathRtl&) = delete;
  CuDatapathRtl& operator=(const CuDatapathRtl&) = delete;

  void reset();

  // Runs one instruction to completion: drives it with valid_i on one clock
  // edge, then clocks until done_o. Register operands must be below
  // REGISTERS. Throws std::logic_error if done_o does not come in time.
  CuCmemWrite execute(const Instruction& instruction, const CuOperandBytes& operands, const CuNeighbours& neighbours);

  // Clock edges the last execute() took.
  unsigned last_cycles() const { return m_last_cycles; }

  uint8_t reg(unsigned index) const;
  CuFlags flags() const;
  bool mask() const;

 private:
  void clock_edge();

  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vcu_datapath> m_model;
  unsigned m_last_cycles = 0;
};

}  // namespace tessera::ap
