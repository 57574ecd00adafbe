// One CU's datapath, bit-exact, one lane at a time: the 8-bit ALU with its
// flags, the 16-bit operations on register pairs, the 16 x 8 signed
// multiplier, the 16 / 8 unsigned divider and the mask conditions. This is the
// reference the vectorised array core (core/cu_array.h) and the Verilog
// twin (rtl_models/array/cu_datapath.sv) are both checked against.
//
// Flags: C is the carry out of an addition and "no borrow" after a
// subtraction (a - b is computed as a + ~b + 1, ARM style), so a >= b
// unsigned leaves C set; Z is set when the 8-bit result is 0; S is bit 7 of
// the result. Logic operations and moves leave C as it was.
#pragma once

#include <cstdint>

#include "array/isa/ap_isa.h"

namespace tessera::ap {

struct CuFlags {
  bool c = false, z = false, s = false;
  bool operator==(const CuFlags& other) const { return c == other.c && z == other.z && s == other.s; }
};

struct AluResult {
  uint8_t value = 0;
  CuFlags flags;
  bool writes = true;  // false for the compares, which only set flags
};

// The 8-bit ALU instructions: add, adc, sub, sbc, and, or, xor, not, mov,
// shl, shr, asr, rol, ror, cmp, cmpc, and nadd (an add: `a` is d's value,
// `b` the neighbour's byte, 0 beyond the grid's edge), nadds and nadcs (the
// same with `b` the neighbour's byte at a or a + 1, which the array routes
// by this CU's S; C written, Z and S kept). `b` is ignored by the
// one-source ones.
// Returns the flags unchanged and writes == false for any other opcode.
AluResult cu_alu(Opcode opcode, uint8_t a, uint8_t b, CuFlags flags);

// True for the opcodes cu_alu() computes.
bool is_alu_opcode(Opcode opcode);

// The 16-bit operations on register pairs (add16, sub16, cmp16, mov16,
// behind array.features.wide_ops), as the 8-bit datapath computes them in
// two passes: the low bytes with the operation's carry in, then the high
// bytes with the low pass's carry, as add and adc (sub and sbc) would. C is
// the high pass's carry out (no borrow after a subtraction), Z is set when
// all 16 bits are 0 (not the high byte's alone, as after adc), S is bit 15.
// mov16 keeps C.
struct PairResult {
  uint16_t value = 0;
  CuFlags flags;
  bool writes = true;  // false for cmp16
};
// Returns the flags unchanged and writes == false for any other opcode.
PairResult cu_pair_alu(Opcode opcode, uint16_t a, uint16_t b, CuFlags flags);

// The signed 16 x 8 multiply (mul, mulm): the 24-bit two's complement
// product, computed as the hardware does it, by shift-and-add over the 8
// bits of the multiplier (the last step subtracts: bit 7 weighs -128).
struct MulResult {
  uint32_t product = 0;  // 24 bits
  CuFlags flags;         // C = 0, Z = product == 0, S = bit 23
};
MulResult cu_mul(uint16_t multiplicand, uint8_t multiplier);

// The unsigned 16 / 8 divide (div, behind array.features.divide): the 8-bit
// quotient of a texel border x = num / den, in one instruction as the Image
// Blender's processing elements divide. A quotient that does not fit 8 bits
// (dividend >= 256 x divisor, which a divisor of 0 always meets) saturates:
// 0xff with C = 1, the clamp to the last texel; else C = 0. Z and S are the
// quotient's. The result is that of 8 restoring steps (shift, compare,
// subtract), which a program of the J2210's instructions would run instead.
AluResult cu_div(uint16_t dividend, uint8_t divisor);

bool cond_holds(Cond cond, const CuFlags& flags);

}  // namespace tessera::ap
