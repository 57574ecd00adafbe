#include "array/datapath/cu_alu.h"

namespace tessera::ap {

namespace {

// a + b + carry_in on 8 bits, with the flags of the result.
AluResult add_with_carry(uint8_t a, uint8_t b, bool carry_in) {
  const unsigned sum = unsigned{a} + unsigned{b} + (carry_in ? 1u : 0u);
  AluResult result;
  result.value = static_cast<uint8_t>(sum);
  result.flags = {sum > 0xffu, result.value == 0, (result.value & 0x80u) != 0};
  return result;
}

AluResult logic(uint8_t value, CuFlags flags) {
  return {value, {flags.c, value == 0, (value & 0x80u) != 0}, true};
}

AluResult shift(uint8_t value, bool carry_out) {
  return {value, {carry_out, value == 0, (value & 0x80u) != 0}, true};
}

}  // namespace

bool is_alu_opcode(Opcode opcode) {
  switch (opcode) {
    case Opcode::op_add:
    case Opcode::op_adc:
    case Opcode::op_sub:
    case Opcode::op_sbc:
    case Opcode::op_and:
    case Opcode::op_or:
    case Opcode::op_xor:
    case Opcode::op_not:
    case Opcode::op_mov:
    case Opcode::op_shl:
    case Opcode::op_shr:
    case Opcode::op_asr:
    case Opcode::op_rol:
    case Opcode::op_ror:
    case Opcode::op_cmp:
    case Opcode::op_cmpc:
    case Opcode::op_nadd:
    case Opcode::op_nadds:
    case Opcode::op_nadcs: return true;
    default: return false;
  }
}

AluResult cu_alu(Opcode opcode, uint8_t a, uint8_t b, CuFlags flags) {
  const auto inverted = static_cast<uint8_t>(~b);
  switch (opcode) {
    case Opcode::op_add:
    case Opcode::op_nadd: return add_with_carry(a, b, false);
    case Opcode::op_adc: return add_with_carry(a, b, flags.c);
    case Opcode::op_nadds:
    case Opcode::op_nadcs: {
      // The chain's selecting adds write C only: S chose the source byte
      // (the array's routing) and must stay for the wide sum's next byte.
      AluResult sum = add_with_carry(a, b, opcode == Opcode::op_nadcs && flags.c);
      sum.flags.z = flags.z;
      sum.flags.s = flags.s;
      return sum;
    }
    case Opcode::op_sub: return add_with_carry(a, inverted, true);
    case Opcode::op_sbc: return add_with_carry(a, inverted, flags.c);
    case Opcode::op_cmp: {
      AluResult result = add_with_carry(a, inverted, true);
      result.writes = false;
      return result;
    }
    case Opcode::op_cmpc: {
      AluResult result = add_with_carry(a, inverted, flags.c);
      result.writes = false;
      return result;
    }
    case Opcode::op_and: return logic(a & b, flags);
    case Opcode::op_or: return logic(a | b, flags);
    case Opcode::op_xor: return logic(a ^ b, flags);
    case Opcode::op_not: return logic(static_cast<uint8_t>(~a), flags);
    case Opcode::op_mov: return logic(a, flags);
    case Opcode::op_shl: return shift(static_cast<uint8_t>(a << 1), (a & 0x80u) != 0);
    case Opcode::op_shr: return shift(static_cast<uint8_t>(a >> 1), (a & 1u) != 0);
    case Opcode::op_asr: return shift(static_cast<uint8_t>((a >> 1) | (a & 0x80u)), (a & 1u) != 0);
    case Opcode::op_rol: return shift(static_cast<uint8_t>((a << 1) | (flags.c ? 1u : 0u)), (a & 0x80u) != 0);
    case Opcode::op_ror: return shift(static_cast<uint8_t>((a >> 1) | (flags.c ? 0x80u : 0u)), (a & 1u) != 0);
    default: return {0, flags, false};
  }
}

PairResult cu_pair_alu(Opcode opcode, uint16_t a, uint16_t b, CuFlags flags) {
  const auto high = [](uint16_t value) { return static_cast<uint8_t>(value >> 8); };
  const auto low = [](uint16_t value) { return static_cast<uint8_t>(value); };
  PairResult result;
  switch (opcode) {
    case Opcode::op_mov16:
      result.value = a;
      result.flags = {flags.c, a == 0, (a & 0x8000u) != 0};
      return result;
    case Opcode::op_add16:
    case Opcode::op_sub16:
    case Opcode::op_cmp16: {
      const bool subtract = opcode != Opcode::op_add16;
      const uint16_t addend = subtract ? static_cast<uint16_t>(~b) : b;
      const AluResult low_pass = add_with_carry(low(a), low(addend), subtract);
      const AluResult high_pass = add_with_carry(high(a), high(addend), low_pass.flags.c);
      result.value = static_cast<uint16_t>(high_pass.value << 8 | low_pass.value);
      result.flags = {high_pass.flags.c, low_pass.flags.z && high_pass.flags.z, high_pass.flags.s};
      result.writes = opcode != Opcode::op_cmp16;
      return result;
    }
    default: return {0, flags, false};
  }
}

MulResult cu_mul(uint16_t multiplicand, uint8_t multiplier) {
  // Sign-extend the multiplicand to the 24-bit accumulator's width; each of
  // the 8 steps adds it, shifted by the step, where the multiplier's bit is
  // set; bit 7 is the sign bit and its step subtracts.
  const uint32_t extended = (multiplicand & 0x8000u) != 0 ? (0xff0000u | multiplicand) : multiplicand;
  uint32_t accumulator = 0;
  for (unsigned bit = 0; bit < 8; ++bit) {
    if (((multiplier >> bit) & 1u) == 0) continue;
    const uint32_t addend = (extended << bit) & 0xffffffu;
    accumulator = (bit == 7 ? accumulator - addend : accumulator + addend) & 0xffffffu;
  }
  MulResult result;
  result.product = accumulator;
  result.flags = {false, accumulator == 0, (accumulator & 0x800000u) != 0};
  return result;
}

AluResult cu_div(uint16_t dividend, uint8_t divisor) {
  AluResult result;
  if ((dividend >> 8) >= divisor) {
    result.value = 0xff;
    result.flags = {true, false, true};
    return result;
  }
  // Restoring division: the partial remainder, 9 bits wide, takes one bit of
  // the dividend per step; where it reaches the divisor, the divisor is
  // subtracted and the quotient's bit is 1. The high byte is below the
  // divisor, so 8 steps give the whole quotient.
  unsigned remainder = dividend >> 8, quotient = 0;
  for (int bit = 7; bit >= 0; --bit) {
    remainder = (remainder << 1) | ((dividend >> bit) & 1u);
    quotient <<= 1;
    if (remainder >= divisor) {
      remainder -= divisor;
      quotient |= 1u;
    }
  }
  result.value = static_cast<uint8_t>(quotient);
  result.flags = {false, result.value == 0, (result.value & 0x80u) != 0};
  return result;
}

bool cond_holds(Cond cond, const CuFlags& flags) {
  switch (cond) {
    case Cond::c: return flags.c;
    case Cond::nc: return !flags.c;
    case Cond::z: return flags.z;
    case Cond::nz: return !flags.z;
    case Cond::s: return flags.s;
    case Cond::ns: return !flags.s;
    case Cond::hi: return flags.c && !flags.z;
    case Cond::ls: return !flags.c || flags.z;
  }
  return false;
}

}  // namespace tessera::ap
