// Instructions of the array processor, built by hand or at random: the
// vectors of the CU's co-simulation (tests/rtl_models/array/), of the CU
// benchmark (bench_cu_rtl) and of the array core's tests. Random ones have
// valid encodings across every lane-work opcode, loop variables included.
#pragma once

#include <array>
#include <cstdint>
#include <random>

#include "array/core/cu_array.h"
#include "array/isa/ap_isa.h"

namespace tessera::ap {

inline Operand reg(unsigned index) {
  return {false, static_cast<uint16_t>(index), 0};
}
inline Operand mem(unsigned address, unsigned loop = 0) {
  return {true, static_cast<uint16_t>(address), static_cast<uint8_t>(loop)};
}
inline Instruction make(Opcode opcode, Operand d = {}, Operand a = {}, Operand b = {}) {
  Instruction in;
  in.opcode = opcode;
  in.d = d;
  in.a = a;
  in.b = b;
  return in;
}
inline Instruction make_cond(Opcode opcode, Cond cond) {
  return make(opcode, {}, {false, static_cast<uint16_t>(cond), 0});
}
inline Instruction make_nget(Operand d, Direction direction, Operand a) {
  return make(Opcode::op_nget, d, a, {false, static_cast<uint16_t>(direction), 0});
}

// The lane-work opcodes: every instruction the CU executes, those behind an
// array.features switch (div, nadd, nadds, nadcs, add16, sub16, cmp16,
// mov16) included; not lut, whose shared table is the array's, outside the
// CU and its Verilog twin, nor zsend, which writes nothing in a CU.
constexpr std::array<Opcode, 33> LANE_OPCODES{
    Opcode::op_add,   Opcode::op_adc,   Opcode::op_sub,  Opcode::op_sbc,   Opcode::op_and,   Opcode::op_or,
    Opcode::op_xor,   Opcode::op_not,   Opcode::op_mov,  Opcode::op_shl,   Opcode::op_shr,   Opcode::op_asr,
    Opcode::op_rol,   Opcode::op_ror,   Opcode::op_cmp,  Opcode::op_cmpc,  Opcode::op_mul,   Opcode::op_mulm,
    Opcode::op_nget,  Opcode::op_getm,  Opcode::op_mset, Opcode::op_mclr,  Opcode::op_mmov,  Opcode::op_mand,
    Opcode::op_mor,   Opcode::op_div,   Opcode::op_nadd, Opcode::op_nadds, Opcode::op_nadcs, Opcode::op_add16,
    Opcode::op_sub16, Opcode::op_cmp16, Opcode::op_mov16};

struct RandomInstruction {
  Instruction instruction;
  LoopVariables variables{};
  unsigned active_loops = 0;
};

// A random instruction with a valid encoding: random fields as the
// instruction's operand pattern and forms allow, encoded, then decoded (and
// checked against `registers` and `cmem_bytes`); operands the decoder refuses (a
// multiply whose product overlaps a source, a result pair straddling a
// source pair) are drawn again, so that every
// opcode is as frequent as the others.
inline RandomInstruction random_instruction(std::mt19937_64& rng, unsigned registers, unsigned cmem_bytes) {
  const Opcode opcode = LANE_OPCODES[rng() % LANE_OPCODES.size()];
  while (true) {
    RandomInstruction r;
    r.active_loops = static_cast<unsigned>(rng() % (LOOP_LEVELS + 1));
    for (unsigned k = 0; k < r.active_loops; ++k) r.variables[k] = static_cast<int>(rng() % (cmem_bytes / 4));
    const OpInfo& info = op_info(opcode);
    const auto operand = [&](char which) {
      const unsigned width = operand_width(opcode, which);
      const bool in_cmem = info.forms == Forms::m || (info.forms == Forms::rm && (rng() & 1) != 0);
      if (!in_cmem) return reg(static_cast<unsigned>(rng() % (registers - width + 1)));
      unsigned loop = 0;
      if (r.active_loops > 0 && rng() % 4 == 0) loop = 1 + static_cast<unsigned>(rng() % r.active_loops);
      const unsigned offset = loop != 0 ? static_cast<unsigned>(r.variables[loop - 1]) : 0;
      return mem(static_cast<unsigned>(rng() % (cmem_bytes - width + 1 - offset)), loop);
    };
    Instruction in = make(opcode);
    switch (info.operands) {
      case OperandPattern::dab:
        in.d = operand('d');
        in.a = operand('a');
        in.b = operand('b');
        break;
      case OperandPattern::da:
        in.d = operand('d');
        in.a = operand('a');
        break;
      case OperandPattern::ab:
        in.a = operand('a');
        in.b = operand('b');
        break;
      case OperandPattern::d: in.d = operand('d'); break;
      case OperandPattern::dna:
        in.d = operand('d');
        in.a = operand('a');
        in.b = reg(static_cast<unsigned>(rng() % 4));
        break;
      case OperandPattern::cond: in.a = reg(static_cast<unsigned>(rng() % COND_COUNT)); break;
      case OperandPattern::none:
      case OperandPattern::loop: break;
    }
    in.stage = static_cast<Stage>(rng() % STAGE_COUNT);
    const Decoded decoded = decode(encode(in));
    if (!decoded.error.empty()) continue;
    if (!check_limits(decoded.instruction, registers, cmem_bytes).empty()) continue;
    r.instruction = decoded.instruction;
    return r;
  }
}

}  // namespace tessera::ap
