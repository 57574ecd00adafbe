#include "cu_datapath_adapter.h"

#include <stdexcept>
#include <string>

#include "Vcu_datapath.h"
#include "verilated.h"

namespace tessera::ap {

namespace {

// More edges than the multiply needs: done_o missing by then is a bug.
constexpr unsigned MAX_EDGES = 2 * CuDatapathRtl::MUL_CYCLES;
constexpr unsigned REGISTER_MASK = CuDatapathRtl::REGISTERS - 1;
static_assert((CuDatapathRtl::REGISTERS & REGISTER_MASK) == 0, "the register port is log2(REGISTERS) bits wide");

// The CMEM byte at `operand` + `byte` in `lane`, or 0 beyond CMEM or for a
// register operand.
uint8_t cmem_byte(const CuArray& array, unsigned lane, const Operand& operand, unsigned byte,
                  const LoopVariables& loop_variables) {
  if (!operand.in_cmem) return 0;
  const long address = long{operand.value} + byte + (operand.loop != 0 ? loop_variables[operand.loop - 1] : 0);
  if (address < 0 || address >= static_cast<long>(array.geometry().cmem_bytes)) return 0;
  return array.cmem(lane, static_cast<unsigned>(address));
}

}  // namespace

CuLaneInputs cu_lane_inputs(const CuArray& array, unsigned lane, const Instruction& in,
                            const LoopVariables& loop_variables) {
  CuLaneInputs inputs;
  inputs.operands.a = {cmem_byte(array, lane, in.a, 0, loop_variables),
                       cmem_byte(array, lane, in.a, 1, loop_variables)};
  inputs.operands.b = cmem_byte(array, lane, in.b, 0, loop_variables);
  inputs.operands.d = cmem_byte(array, lane, in.d, 0, loop_variables);
  const bool selects = in.opcode == Opcode::op_nadds || in.opcode == Opcode::op_nadcs;
  if (in.opcode != Opcode::op_nget && in.opcode != Opcode::op_nadd && !selects) return inputs;
  const unsigned columns = array.geometry().columns, rows = array.geometry().rows;
  const unsigned column = lane % columns, row = lane / columns;
  for (unsigned k = 0; k < 4; ++k) {
    bool present = false;
    unsigned other = 0;
    switch (static_cast<Direction>(k)) {
      case Direction::left: present = column > 0, other = lane - 1; break;
      case Direction::right: present = column + 1 < columns, other = lane + 1; break;
      case Direction::up: present = row > 0, other = lane - columns; break;
      case Direction::down: present = row + 1 < rows, other = lane + columns; break;
    }
    inputs.neighbours.present[k] = present;
    if (!present) continue;
    inputs.neighbours.value[k] =
        in.a.in_cmem ? cmem_byte(array, other, in.a, 0, loop_variables) : array.reg(other, in.a.value);
    if (selects)
      inputs.neighbours.next[k] =
          in.a.in_cmem ? cmem_byte(array, other, in.a, 1, loop_variables) : array.reg(other, in.a.value + 1u);
  }
  return inputs;
}

CuDatapathRtl::CuDatapathRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vcu_datapath>(m_context.get(), "cu_datapath")) {
  reset();
}

CuDatapathRtl::~CuDatapathRtl() {
  m_model->final();
}

// The reset is asynchronous on the falling edge of rst_ni, and a new model's
// inputs are all 0: raise rst_ni first so that lowering it is an edge.
void CuDatapathRtl::reset() {
  m_model->clk_i = 0;
  m_model->valid_i = 0;
  m_model->rst_ni = 1;
  m_model->eval();
  m_model->rst_ni = 0;
  m_model->eval();
  m_model->rst_ni = 1;
  m_model->eval();
  m_last_cycles = 0;
}

// Inputs are set while the clock is low; lowering it and evaluating first
// settles them, so the rising edge samples them free of any input/clock race.
void CuDatapathRtl::clock_edge() {
  m_model->clk_i = 0;
  m_model->eval();
  m_model->clk_i = 1;
  m_model->eval();
}

CuCmemWrite CuDatapathRtl::execute(const Instruction& in, const CuOperandBytes& operands,
                                   const CuNeighbours& neighbours) {
  Vcu_datapath& m = *m_model;
  if (!m.ready_o) throw std::logic_error("cu_datapath: not ready for an instruction");
  m.valid_i = 1;
  m.opcode_i = static_cast<uint8_t>(in.opcode);
  m.cond_i = static_cast<uint8_t>(in.cond());
  m.direction_i = static_cast<uint8_t>(in.direction());
  m.d_is_cmem_i = in.d.in_cmem ? 1 : 0;
  m.a_is_cmem_i = in.a.in_cmem ? 1 : 0;
  m.b_is_cmem_i = in.b.in_cmem ? 1 : 0;
  m.d_reg_i = in.d.value & REGISTER_MASK;
  m.a_reg_i = in.a.value & REGISTER_MASK;
  m.b_reg_i = in.b.value & REGISTER_MASK;
  m.a_cmem_i = static_cast<uint16_t>(operands.a[0] << 8 | operands.a[1]);
  m.b_cmem_i = operands.b;
  m.d_cmem_i = operands.d;
  uint32_t neighbour_bytes = 0, next_bytes = 0;
  uint8_t present = 0;
  for (unsigned k = 0; k < 4; ++k) {
    neighbour_bytes |= uint32_t{neighbours.value[k]} << (8 * k);
    next_bytes |= uint32_t{neighbours.next[k]} << (8 * k);
    present |= static_cast<uint8_t>((neighbours.present[k] ? 1u : 0u) << k);
  }
  m.neighbour_i = neighbour_bytes;
  m.neighbour_next_i = next_bytes;
  m.neighbour_present_i = present;
  clock_edge();
  m.valid_i = 0;
  unsigned edges = 1;
  while (!m.done_o) {
    if (edges == MAX_EDGES) throw std::logic_error("cu_datapath: no done_o after " + std::to_string(edges) + " edges");
    clock_edge();
    ++edges;
  }
  m_last_cycles = edges;
  CuCmemWrite write;
  // Byte lane i (address d + i) is bits [23 - 8i : 16 - 8i]: big-endian.
  for (unsigned i = 0; i < 3; ++i) {
    write.data[i] = static_cast<uint8_t>(m.cmem_wdata_o >> (16 - 8 * i));
    write.enable[i] = ((m.cmem_we_o >> (2 - i)) & 1u) != 0;
  }
  return write;
}

uint8_t CuDatapathRtl::reg(unsigned index) const {
  if (index >= REGISTERS) throw std::out_of_range("cu_datapath: register " + std::to_string(index));
  return static_cast<uint8_t>(m_model->regs_o >> (8 * index));
}

CuFlags CuDatapathRtl::flags() const {
  return {m_model->flag_c_o != 0, m_model->flag_z_o != 0, m_model->flag_s_o != 0};
}

bool CuDatapathRtl::mask() const {
  return m_model->mask_o != 0;
}

}  // namespace tessera::ap
