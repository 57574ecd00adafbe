// The array's functional core (tlm/array/core): CuArray against a scalar
// model of every lane written here from the one-lane reference
// (datapath/cu_alu.h), and ArrayController's loops, halt, cycle counts and
// errors, with the expected values worked out by hand from ap_isa.def.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "array/core/array_controller.h"
#include "array/core/cu_array.h"
#include "array/datapath/cu_alu.h"
#include "array/isa/ap_isa.h"
#include "cosim/random_instruction.h"

namespace tessera::ap {
namespace {

// The full grid, with a small CMEM so that random operands alias.
constexpr unsigned COLUMNS = 24, ROWS = 4, REGISTERS = 8, CMEM_BYTES = 64;
constexpr uint64_t RANDOM_INSTRUCTIONS = 100'000;

ArrayGeometry small_cmem_geometry() {
  ArrayGeometry geometry;
  geometry.columns = COLUMNS;
  geometry.rows = ROWS;
  geometry.registers = REGISTERS;
  geometry.cmem_bytes = CMEM_BYTES;
  return geometry;
}

// One lane as plain state, and the array as a vector of them, executed one
// lane after the other from a copy of the state before the instruction
// (neighbour reads see the old values, as in hardware). With `skew`
// (delayed execution, README.md): a neighbour read from an earlier lane of
// the chain (a lower lane number; by row, a lane of an earlier row) sees
// that lane as this instruction left it, from a later lane (by row, one of
// the same or a later row) as it was before.
struct Lane {
  std::array<uint8_t, REGISTERS> regs{};
  std::array<uint8_t, CMEM_BYTES> cmem{};
  CuFlags flags;
  bool mask = true;
};

class ScalarArray {
 public:
  explicit ScalarArray(IssueSkew skew = IssueSkew::none, bool ring = false)
      : m_lanes(COLUMNS * ROWS), m_skew(skew), m_ring(ring) {}
  std::vector<Lane>& lanes() { return m_lanes; }

  void execute(const Instruction& in, const LoopVariables& variables) {
    const std::vector<Lane> before = m_lanes;
    for (unsigned l = 0; l < m_lanes.size(); ++l) execute_lane(in, variables, before, l);
  }

 private:
  static unsigned address(const Operand& operand, const LoopVariables& variables) {
    return operand.value + (operand.loop != 0 ? static_cast<unsigned>(variables[operand.loop - 1]) : 0);
  }
  static uint8_t read(const Lane& lane, const Operand& operand, unsigned byte, const LoopVariables& variables) {
    return operand.in_cmem ? lane.cmem[address(operand, variables) + byte] : lane.regs[operand.value + byte];
  }
  static void write(Lane& lane, const Operand& operand, unsigned byte, uint8_t value, const LoopVariables& variables,
                    bool mask) {
    if (!operand.in_cmem)
      lane.regs[operand.value + byte] = value;
    else if (mask)
      lane.cmem[address(operand, variables) + byte] = value;
  }
  // The lane that way, or -1 beyond the grid: row 0 at the top; with the
  // row ring, left and right wrap around the row.
  int neighbour(unsigned lane, Direction direction) const {
    const unsigned column = lane % COLUMNS, row = lane / COLUMNS;
    const int wrap_left = m_ring ? static_cast<int>(lane + COLUMNS - 1) : -1;
    const int wrap_right = m_ring ? static_cast<int>(lane + 1 - COLUMNS) : -1;
    switch (direction) {
      case Direction::left: return column == 0 ? wrap_left : static_cast<int>(lane) - 1;
      case Direction::right: return column == COLUMNS - 1 ? wrap_right : static_cast<int>(lane) + 1;
      case Direction::up: return row == 0 ? -1 : static_cast<int>(lane - COLUMNS);
      case Direction::down: return row == ROWS - 1 ? -1 : static_cast<int>(lane + COLUMNS);
    }
    return -1;
  }

  // The neighbour `other` as lane `l` sees it.
  const Lane& source(const std::vector<Lane>& before, int other, unsigned l) const {
    const auto index = static_cast<unsigned>(other);
    const bool earlier =
        (m_skew == IssueSkew::lane && index < l) || (m_skew == IssueSkew::row && index / COLUMNS < l / COLUMNS);
    return earlier ? m_lanes[index] : before[index];
  }

  void execute_lane(const Instruction& in, const LoopVariables& v, const std::vector<Lane>& before, unsigned l) {
    Lane& lane = m_lanes[l];
    const Lane& old = before[l];
    const bool mask = old.mask;
    switch (in.opcode) {
      case Opcode::op_mset: lane.mask = true; return;
      case Opcode::op_mclr: lane.mask = false; return;
      case Opcode::op_mmov: lane.mask = cond_holds(in.cond(), old.flags); return;
      case Opcode::op_mand: lane.mask = mask && cond_holds(in.cond(), old.flags); return;
      case Opcode::op_mor: lane.mask = mask || cond_holds(in.cond(), old.flags); return;
      case Opcode::op_getm: write(lane, in.d, 0, mask ? 0xff : 0x00, v, mask); return;
      case Opcode::op_nget: {
        const int other = neighbour(l, in.direction());
        const uint8_t value = other < 0 ? 0 : read(source(before, other, l), in.a, 0, v);
        write(lane, in.d, 0, value, v, mask);
        return;
      }
      case Opcode::op_nadd: {
        const int other = neighbour(l, in.direction());
        const uint8_t value = other < 0 ? 0 : read(source(before, other, l), in.a, 0, v);
        const AluResult sum = cu_alu(in.opcode, read(old, in.d, 0, v), value, old.flags);
        lane.flags = sum.flags;
        write(lane, in.d, 0, sum.value, v, mask);
        return;
      }
      case Opcode::op_nadds:
      case Opcode::op_nadcs: {
        // The neighbour's a, or its a + 1 where this lane's S is set.
        const int other = neighbour(l, in.direction());
        const unsigned byte = old.flags.s ? 1 : 0;
        const uint8_t value = other < 0 ? 0 : read(source(before, other, l), in.a, byte, v);
        const AluResult sum = cu_alu(in.opcode, read(old, in.d, 0, v), value, old.flags);
        lane.flags = sum.flags;
        write(lane, in.d, 0, sum.value, v, mask);
        return;
      }
      case Opcode::op_div: {
        const auto dividend = static_cast<uint16_t>(read(old, in.a, 0, v) << 8 | read(old, in.a, 1, v));
        const AluResult quotient = cu_div(dividend, read(old, in.b, 0, v));
        lane.flags = quotient.flags;
        write(lane, in.d, 0, quotient.value, v, mask);
        return;
      }
      case Opcode::op_add16:
      case Opcode::op_sub16:
      case Opcode::op_cmp16:
      case Opcode::op_mov16: {
        const auto pair = [&](const Operand& operand) {
          return static_cast<uint16_t>(read(old, operand, 0, v) << 8 | read(old, operand, 1, v));
        };
        const bool reads_b = in.opcode != Opcode::op_mov16;
        const PairResult result = cu_pair_alu(in.opcode, pair(in.a), reads_b ? pair(in.b) : 0, old.flags);
        lane.flags = result.flags;
        if (result.writes) {
          write(lane, in.d, 0, static_cast<uint8_t>(result.value >> 8), v, mask);
          write(lane, in.d, 1, static_cast<uint8_t>(result.value), v, mask);
        }
        return;
      }
      case Opcode::op_mul:
      case Opcode::op_mulm: {
        const auto multiplicand = static_cast<uint16_t>(read(old, in.a, 0, v) << 8 | read(old, in.a, 1, v));
        const MulResult product = cu_mul(multiplicand, read(old, in.b, 0, v));
        for (unsigned byte = 0; byte < 3; ++byte)
          write(lane, in.d, byte, static_cast<uint8_t>(product.product >> (16 - 8 * byte)), v, mask);
        lane.flags = product.flags;
        return;
      }
      default: {
        const bool two_sources = op_info(in.opcode).operands != OperandPattern::da;
        const AluResult result =
            cu_alu(in.opcode, read(old, in.a, 0, v), two_sources ? read(old, in.b, 0, v) : 0, old.flags);
        lane.flags = result.flags;
        if (result.writes) write(lane, in.d, 0, result.value, v, mask);
        return;
      }
    }
  }

  std::vector<Lane> m_lanes;
  IssueSkew m_skew;
  bool m_ring;
};

// An instruction whose result delayed execution changes: a neighbour read
// from an earlier lane of the chain (left, up; by row, up) of the operand it
// writes.
bool skew_visible(const Instruction& in, IssueSkew skew) {
  const bool reads_neighbour = in.opcode == Opcode::op_nget || in.opcode == Opcode::op_nadd ||
                               in.opcode == Opcode::op_nadds || in.opcode == Opcode::op_nadcs;
  const bool earlier =
      in.direction() == Direction::up || (skew == IssueSkew::lane && in.direction() == Direction::left);
  return skew != IssueSkew::none && reads_neighbour && earlier && in.a.in_cmem == in.d.in_cmem &&
         in.a.value == in.d.value && in.a.loop == in.d.loop;
}

void random_instructions_match_the_scalar_model(IssueSkew skew, bool ring = false) {
  std::mt19937_64 rng(0xa77a);
  CuArray array(small_cmem_geometry());
  array.set_issue_skew(skew);
  array.set_row_ring(ring);
  ScalarArray model(skew, ring);
  uint64_t visible = 0;
  ASSERT_EQ(array.lanes(), COLUMNS * ROWS);
  for (unsigned l = 0; l < array.lanes(); ++l)
    for (unsigned a = 0; a < CMEM_BYTES; ++a) {
      const auto value = static_cast<uint8_t>(rng());
      array.set_cmem(l, a, value);
      model.lanes()[l].cmem[a] = value;
    }
  uint64_t refused = 0;
  for (uint64_t i = 0; i < RANDOM_INSTRUCTIONS; ++i) {
    RandomInstruction r = random_instruction(rng, REGISTERS, CMEM_BYTES);
    const Instruction& in = r.instruction;
    // Now and then an address the loop variable pushes beyond CMEM: refused,
    // nothing changes.
    const bool beyond = in.d.in_cmem && rng() % 64 == 0;
    if (beyond) {
      r.active_loops = std::max(r.active_loops, 1u);
      Instruction bad = in;
      bad.d.loop = 1;
      r.variables[0] = static_cast<int>(CMEM_BYTES);
      const std::string error = array.execute(bad, r.variables, r.active_loops);
      EXPECT_NE(error.find("beyond"), std::string::npos) << format_instruction(bad) << ": " << error;
      ++refused;
    } else {
      ASSERT_EQ(array.execute(in, r.variables, r.active_loops), "") << format_instruction(in);
      model.execute(in, r.variables);
      visible += skew_visible(in, skew) ? 1 : 0;
    }
    unsigned active = 0;
    for (unsigned l = 0; l < array.lanes(); ++l) {
      const Lane& lane = model.lanes()[l];
      bool same = array.flags(l) == lane.flags && array.mask(l) == lane.mask;
      for (unsigned k = 0; k < REGISTERS; ++k) same = same && array.reg(l, k) == lane.regs[k];
      // CMEM in full every 256 instructions, else where the store went.
      if (in.d.in_cmem && i % 256 != 0) {
        const unsigned d = in.d.value + (in.d.loop != 0 ? static_cast<unsigned>(r.variables[in.d.loop - 1]) : 0);
        for (unsigned b = 0; b < operand_width(in.opcode, 'd') && d + b < CMEM_BYTES; ++b)
          same = same && array.cmem(l, d + b) == lane.cmem[d + b];
      } else if (i % 256 == 0) {
        for (unsigned a = 0; a < CMEM_BYTES; ++a) same = same && array.cmem(l, a) == lane.cmem[a];
      }
      ASSERT_TRUE(same) << "instruction " << i << " '" << format_instruction(in) << "', lane " << l;
      active += lane.mask ? 1 : 0;
    }
    ASSERT_EQ(array.active_lanes(), active);
  }
  EXPECT_GT(refused, 0u);
  // The skew's own case comes up often enough to be tested.
  if (skew != IssueSkew::none) {
    EXPECT_GT(visible, 25u);
  }
}

TEST(CuArray, RandomInstructionsMatchAScalarModelOfEveryLane) {
  random_instructions_match_the_scalar_model(IssueSkew::none);
}

TEST(CuArray, UnderDelayedExecutionRandomInstructionsMatchTheChainsScalarModel) {
  random_instructions_match_the_scalar_model(IssueSkew::lane);
}

TEST(CuArray, UnderRowSkewRandomInstructionsMatchTheRowsScalarModel) {
  random_instructions_match_the_scalar_model(IssueSkew::row);
}

TEST(CuArray, WithTheRowRingRandomInstructionsMatchTheScalarModelLockstepAndSkewed) {
  random_instructions_match_the_scalar_model(IssueSkew::none, true);
  random_instructions_match_the_scalar_model(IssueSkew::lane, true);
  random_instructions_match_the_scalar_model(IssueSkew::row, true);
}

TEST(CuArray, LoopVariableOfALoopThatIsNotRunningIsRefused) {
  CuArray array(small_cmem_geometry());
  const std::string error = array.execute(make(Opcode::op_mov, mem(0, 2), reg(0)), {0, 0, 0}, 1);
  EXPECT_NE(error.find("outside its loop"), std::string::npos) << error;
  EXPECT_NE(array.execute(make(Opcode::op_loop), {}, 0).find("does no lane work"), std::string::npos);
}

// --- The Image Blender's instructions (array.features.*) -----------------

CuFlags czs(bool c, bool z, bool s) {
  return {c, z, s};
}

TEST(CuDatapath, DivideSixteenByEightWithItsFlagsByHand) {
  struct Case {
    uint16_t dividend;
    uint8_t divisor;
    uint8_t quotient;
    CuFlags flags;
  };
  const std::array<Case, 9> cases{{
      {0x1234, 0x56, 0x36, czs(false, false, false)},  // 4660 / 86 = 54.19
      {0x0380, 0x07, 0x80, czs(false, false, true)},   // a texel border: 3.5 (8.8) / 7 = 128, bit 7 set
      {0x00ff, 0x01, 0xff, czs(false, false, true)},   // the largest quotient that fits
      {0xfeff, 0xff, 0xff, czs(false, false, true)},   // 65279 / 255 = 255.99: fits
      {0x8000, 0x81, 0xfe, czs(false, false, true)},   // 32768 / 129 = 254.02
      {0x0003, 0x07, 0x00, czs(false, true, false)},   // below 1: 0
      {0x0100, 0x01, 0xff, czs(true, false, true)},    // 256 does not fit: saturated
      {0xff00, 0xff, 0xff, czs(true, false, true)},    // exactly 256: saturated
      {0x0005, 0x00, 0xff, czs(true, false, true)},    // division by zero: saturated
  }};
  for (const Case& c : cases) {
    const AluResult result = cu_div(c.dividend, c.divisor);
    EXPECT_EQ(result.value, c.quotient) << std::hex << c.dividend << " / " << unsigned{c.divisor};
    EXPECT_EQ(result.flags, c.flags) << std::hex << c.dividend << " / " << unsigned{c.divisor};
    EXPECT_TRUE(result.writes);
  }
  // The same as the quotient where it fits, for every divisor and a sweep of dividends.
  for (unsigned divisor = 1; divisor < 256; ++divisor)
    for (unsigned dividend = 0; dividend < 0x10000; dividend += 251) {
      const AluResult result = cu_div(static_cast<uint16_t>(dividend), static_cast<uint8_t>(divisor));
      const unsigned expected = dividend / divisor > 0xff ? 0xff : dividend / divisor;
      ASSERT_EQ(result.value, expected) << dividend << " / " << divisor;
      ASSERT_EQ(result.flags.c, dividend / divisor > 0xff) << dividend << " / " << divisor;
    }
}

TEST(CuDatapath, NeighbourAddIsAnAddOfDAndTheNeighboursByte) {
  // d 0x70 + 0x90 = 0x100: 0 with a carry out.
  AluResult result = cu_alu(Opcode::op_nadd, 0x70, 0x90, czs(false, false, true));
  EXPECT_EQ(result.value, 0x00);
  EXPECT_EQ(result.flags, czs(true, true, false));
  // 0x7f + 0x01 = 0x80; the carry in is not used.
  result = cu_alu(Opcode::op_nadd, 0x7f, 0x01, czs(true, false, false));
  EXPECT_EQ(result.value, 0x80);
  EXPECT_EQ(result.flags, czs(false, false, true));
}

TEST(CuArray, NeighbourAddSumsAChainFromTheLeftAndReadsZeroBeyondTheEdge) {
  CuArray array(small_cmem_geometry());
  // Every CU holds 1 in r0 and its column in r1; nadd r1, left, r0 adds the
  // left neighbour's r0 (1) except in column 0, which has none and adds 0.
  for (unsigned l = 0; l < array.lanes(); ++l) {
    array.set_reg(l, 0, 1);
    array.set_reg(l, 1, static_cast<uint8_t>(l % COLUMNS));
  }
  const Instruction nadd = make(Opcode::op_nadd, reg(1), reg(0), {false, static_cast<uint16_t>(Direction::left), 0});
  ASSERT_EQ(array.execute(nadd, {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l)
    EXPECT_EQ(array.reg(l, 1), l % COLUMNS + (l % COLUMNS == 0 ? 0 : 1)) << l;
  // 0xff + 1 from the neighbour: 0 with C and Z; lanes in column 0 keep 0xff.
  for (unsigned l = 0; l < array.lanes(); ++l) array.set_reg(l, 1, 0xff);
  ASSERT_EQ(array.execute(nadd, {}, 0), "");
  EXPECT_EQ(array.reg(1, 1), 0x00);
  EXPECT_EQ(array.flags(1), czs(true, true, false));
  EXPECT_EQ(array.reg(0, 1), 0xff);
  EXPECT_EQ(array.flags(0), czs(false, false, true));
  // Lanes with a left neighbour each read it once.
  EXPECT_EQ(array.activity().neighbour_transfers, 2u * (COLUMNS - 1) * ROWS);
}

TEST(CuArray, DivideFromCmemStoresTheQuotientWhereTheMaskIsSet) {
  CuArray array(small_cmem_geometry());
  for (unsigned l = 0; l < array.lanes(); ++l) {
    array.set_cmem(l, 10, 0x03);  // 0x0380: 3.5 in 8.8
    array.set_cmem(l, 11, 0x80);
    array.set_cmem(l, 12, static_cast<uint8_t>(l % 8));  // divisors 0..7
    array.set_cmem(l, 20, 0x55);
    array.set_mask(l, l % 2 == 0);
  }
  ASSERT_EQ(array.execute(make(Opcode::op_div, mem(20), mem(10), mem(12)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) {
    const unsigned divisor = l % 8;
    // 0x0380 / d fits 8 bits from d = 4 on (high byte 3 < d).
    const uint8_t quotient = divisor > 3 ? static_cast<uint8_t>(0x380 / divisor) : 0xff;
    EXPECT_EQ(array.cmem(l, 20), l % 2 == 0 ? quotient : 0x55) << l;
    EXPECT_EQ(array.flags(l).c, divisor <= 3) << l;
  }
  // Two dividend bytes and the divisor read in every lane.
  EXPECT_EQ(array.activity().cmem_reads, 3u * array.lanes());
}

// --- Delayed execution and the lookup table --------------------------------

Operand direction(Direction which) {
  return {false, static_cast<uint16_t>(which), 0};
}

TEST(CuArray, UnderDelayedExecutionOneNaddAlongTheChainIsAPrefixSum) {
  // r0 = the lane's value; nadd r0, left, r0. The J2210 adds the left
  // neighbour's old r0; under skew the left neighbour ran the nadd first,
  // so each CU adds its left neighbour's new sum: the prefix sum of its row
  // (the row's first CU has no left neighbour and adds 0).
  const Instruction nadd = make(Opcode::op_nadd, reg(0), reg(0), direction(Direction::left));
  const auto value = [](unsigned l) { return static_cast<uint8_t>(1 + l % 7); };
  CuArray lockstep(small_cmem_geometry()), skewed(small_cmem_geometry());
  skewed.set_issue_skew(true);
  for (unsigned l = 0; l < lockstep.lanes(); ++l) {
    lockstep.set_reg(l, 0, value(l));
    skewed.set_reg(l, 0, value(l));
  }
  ASSERT_EQ(lockstep.execute(nadd, {}, 0), "");
  ASSERT_EQ(skewed.execute(nadd, {}, 0), "");
  for (unsigned l = 0; l < lockstep.lanes(); ++l) {
    const unsigned column = l % COLUMNS;
    unsigned prefix = 0;
    for (unsigned k = l - column; k <= l; ++k) prefix += value(k);
    EXPECT_EQ(lockstep.reg(l, 0), column == 0 ? value(l) : value(l) + value(l - 1)) << l;
    EXPECT_EQ(skewed.reg(l, 0), static_cast<uint8_t>(prefix)) << l;
    EXPECT_EQ(skewed.flags(l).c, prefix > 0xff) << l;
  }
  // The same neighbour reads either way.
  EXPECT_EQ(skewed.activity().neighbour_transfers, lockstep.activity().neighbour_transfers);
}

TEST(CuArray, UnderDelayedExecutionEarlierLanesAreReadAfterAndLaterLanesBefore) {
  CuArray array(small_cmem_geometry());
  array.set_issue_skew(true);
  const auto fill = [&] {
    for (unsigned l = 0; l < array.lanes(); ++l) {
      array.set_reg(l, 1, static_cast<uint8_t>(l));
      array.set_cmem(l, 5, static_cast<uint8_t>(100 + l));
      array.set_mask(l, true);
    }
  };
  // nget r1, left, r1: the row's first CU reads 0 beyond the edge, and
  // each CU after it passes that on: the whole row ends with 0 (on the
  // J2210, each CU the value of its left neighbour).
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::left)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) EXPECT_EQ(array.reg(l, 1), 0) << l;
  // nget r1, right, r1: the right neighbour has not run it yet: its old value.
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::right)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) EXPECT_EQ(array.reg(l, 1), l % COLUMNS == COLUMNS - 1 ? 0 : l + 1) << l;
  // nadd r1, up, r1: up is earlier in the chain (a row before): column sums.
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nadd, reg(1), reg(1), direction(Direction::up)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) {
    unsigned sum = 0;
    for (unsigned k = l % COLUMNS; k <= l; k += COLUMNS) sum += k;
    EXPECT_EQ(array.reg(l, 1), static_cast<uint8_t>(sum)) << l;
  }
  // nadd r2, left, r1 reads an operand it does not write: as on the J2210.
  fill();
  for (unsigned l = 0; l < array.lanes(); ++l) array.set_reg(l, 2, 1);
  ASSERT_EQ(array.execute(make(Opcode::op_nadd, reg(2), reg(1), direction(Direction::left)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) EXPECT_EQ(array.reg(l, 2), 1 + (l % COLUMNS == 0 ? 0 : l - 1)) << l;
  // nget [5], left, [5] with the mask clear in every fourth CU: a CU reads
  // its left neighbour's byte as the neighbour's masked store left it (the
  // new value where it stored, its old one where it did not).
  fill();
  const auto stores = [](unsigned l) { return l % 4 != 3; };
  for (unsigned l = 0; l < array.lanes(); ++l) array.set_mask(l, stores(l));
  ASSERT_EQ(array.execute(make(Opcode::op_nget, mem(5), mem(5), direction(Direction::left)), {}, 0), "");
  std::vector<unsigned> after(array.lanes());
  for (unsigned l = 0; l < array.lanes(); ++l) {
    after[l] = !stores(l) ? 100 + l : l % COLUMNS == 0 ? 0 : after[l - 1];
    EXPECT_EQ(array.cmem(l, 5), static_cast<uint8_t>(after[l])) << l;
  }
}

TEST(CuArray, UnderRowSkewUpIsReadAfterAndDownLeftRightBefore) {
  CuArray array(small_cmem_geometry());
  array.set_issue_skew(IssueSkew::row);
  const auto fill = [&] {
    for (unsigned l = 0; l < array.lanes(); ++l) {
      array.set_reg(l, 1, static_cast<uint8_t>(l));
      array.set_cmem(l, 5, static_cast<uint8_t>(100 + l));
      array.set_mask(l, true);
    }
  };
  // nget r1, left, r1: the same row runs together: each CU its left
  // neighbour's old value, as on the J2210.
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::left)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) EXPECT_EQ(array.reg(l, 1), l % COLUMNS == 0 ? 0 : l - 1) << l;
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::right)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) EXPECT_EQ(array.reg(l, 1), l % COLUMNS == COLUMNS - 1 ? 0 : l + 1) << l;
  // nget r1, down, r1: the row below has not run it yet: its old value.
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::down)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l)
    EXPECT_EQ(array.reg(l, 1), l / COLUMNS == ROWS - 1 ? 0 : l + COLUMNS) << l;
  // nget r1, up, r1: the row above ran it already: row 0 reads 0 beyond the
  // edge and every row below passes it on.
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::up)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) EXPECT_EQ(array.reg(l, 1), 0) << l;
  // nadd r1, up, r1: column sums, as under lane skew.
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nadd, reg(1), reg(1), direction(Direction::up)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) {
    unsigned sum = 0;
    for (unsigned k = l % COLUMNS; k <= l; k += COLUMNS) sum += k;
    EXPECT_EQ(array.reg(l, 1), static_cast<uint8_t>(sum)) << l;
  }
  // nadd r1, left, r1: the left neighbour's old r1 (a lane skew would sum the row).
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nadd, reg(1), reg(1), direction(Direction::left)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l)
    EXPECT_EQ(array.reg(l, 1), static_cast<uint8_t>(l + (l % COLUMNS == 0 ? 0 : l - 1))) << l;
  // nget [5], up, [5] with the mask clear in every third row's CUs of odd
  // columns: a CU reads the byte the CU above left (its new value where it
  // stored, its old one where it did not).
  fill();
  const auto stores = [](unsigned l) { return (l / COLUMNS) % 3 != 1 || l % 2 == 0; };
  for (unsigned l = 0; l < array.lanes(); ++l) array.set_mask(l, stores(l));
  ASSERT_EQ(array.execute(make(Opcode::op_nget, mem(5), mem(5), direction(Direction::up)), {}, 0), "");
  std::vector<unsigned> after(array.lanes());
  for (unsigned l = 0; l < array.lanes(); ++l) {
    after[l] = !stores(l) ? 100 + l : l < COLUMNS ? 0 : after[l - COLUMNS];
    EXPECT_EQ(array.cmem(l, 5), static_cast<uint8_t>(after[l])) << l;
  }
  // The row ring stays within the row: both wraps read the old value.
  array.set_row_ring(true);
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::left)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l)
    EXPECT_EQ(array.reg(l, 1), l % COLUMNS == 0 ? l + COLUMNS - 1 : l - 1) << l;
  fill();
  ASSERT_EQ(array.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::right)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l)
    EXPECT_EQ(array.reg(l, 1), l % COLUMNS == COLUMNS - 1 ? l + 1 - COLUMNS : l + 1) << l;
}

TEST(CuArray, TheRowRingWrapsLeftAndRightAndFollowsTheReadRule) {
  // r1 = the lane number in every CU.
  const auto fill = [](CuArray& array) {
    for (unsigned l = 0; l < array.lanes(); ++l) array.set_reg(l, 1, static_cast<uint8_t>(l));
  };
  const auto last_column = [](unsigned l) { return l - l % COLUMNS + COLUMNS - 1; };
  const auto first_column = [](unsigned l) { return l - l % COLUMNS; };
  // Lockstep: column 0's left is the row's last column, the last column's
  // right is column 0; up and down keep the grid's edges.
  CuArray lockstep(small_cmem_geometry());
  lockstep.set_row_ring(true);
  fill(lockstep);
  ASSERT_EQ(lockstep.execute(make(Opcode::op_nget, reg(2), reg(1), direction(Direction::left)), {}, 0), "");
  ASSERT_EQ(lockstep.execute(make(Opcode::op_nget, reg(3), reg(1), direction(Direction::right)), {}, 0), "");
  ASSERT_EQ(lockstep.execute(make(Opcode::op_nget, reg(4), reg(1), direction(Direction::up)), {}, 0), "");
  for (unsigned l = 0; l < lockstep.lanes(); ++l) {
    EXPECT_EQ(lockstep.reg(l, 2), l % COLUMNS == 0 ? last_column(l) : l - 1) << l;
    EXPECT_EQ(lockstep.reg(l, 3), l % COLUMNS == COLUMNS - 1 ? first_column(l) : l + 1) << l;
    EXPECT_EQ(lockstep.reg(l, 4), l < COLUMNS ? 0 : l - COLUMNS) << l;
  }
  // Every CU reads a neighbour across the ring: 96 transfers each.
  EXPECT_EQ(lockstep.activity().neighbour_transfers, 2u * COLUMNS * ROWS + (ROWS - 1) * COLUMNS);
  // Skewed, nget r1, left, r1: column 0 reads the last column, a later lane,
  // before the instruction (its lane number); each CU after it passes that
  // on, so the whole row holds the last column's old r1. That is the relay:
  // the last column's value reaches column 0 with the next instruction.
  CuArray skewed(small_cmem_geometry());
  skewed.set_row_ring(true);
  skewed.set_issue_skew(true);
  fill(skewed);
  ASSERT_EQ(skewed.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::left)), {}, 0), "");
  for (unsigned l = 0; l < skewed.lanes(); ++l) EXPECT_EQ(skewed.reg(l, 1), last_column(l)) << l;
  // Skewed, nget r1, right, r1: each CU reads its right neighbour before
  // the instruction; the last column reads column 0, an earlier lane, after
  // it: column 1's old r1.
  fill(skewed);
  ASSERT_EQ(skewed.execute(make(Opcode::op_nget, reg(1), reg(1), direction(Direction::right)), {}, 0), "");
  for (unsigned l = 0; l < skewed.lanes(); ++l)
    EXPECT_EQ(skewed.reg(l, 1), l % COLUMNS == COLUMNS - 1 ? first_column(l) + 1 : l + 1) << l;
  // Skewed, nadd r1, left, r1 with the ring: the row's prefix sums, column 0
  // starting from the last column's old value.
  fill(skewed);
  ASSERT_EQ(skewed.execute(make(Opcode::op_nadd, reg(1), reg(1), direction(Direction::left)), {}, 0), "");
  for (unsigned l = 0; l < skewed.lanes(); ++l) {
    unsigned sum = last_column(l);
    for (unsigned k = first_column(l); k <= l; ++k) sum += k;
    EXPECT_EQ(skewed.reg(l, 1), static_cast<uint8_t>(sum)) << l;
  }
}

TEST(CuArray, NaddsAndNadcsPassAWindowDownTheChainShiftedWhereSIsSet) {
  // Van Sinten's step 5 on two 16-bit slots: CMEM [10 + j] the high bytes,
  // [20 + j] the low bytes of slot j (j = 0, 1; slot 2 = 0), each CU's own
  // scaling already in its slots; in the CUs with S set the window moved
  // on, so they add their predecessor's slot j + 1. Slot 1 first, then 0,
  // low byte then high, under skew: each CU's slots then hold the row's
  // chained sums, and the lowest CU of a row starts from 0.
  CuArray array(small_cmem_geometry());
  array.set_issue_skew(true);
  const auto moved = [](unsigned l) { return l % 3 == 1; };
  const auto own = [](unsigned l, unsigned j) { return static_cast<unsigned>(200 + 37 * l + 11 * j); };
  for (unsigned l = 0; l < array.lanes(); ++l) {
    for (unsigned j = 0; j < 3; ++j) {
      const unsigned value = j < 2 ? own(l, j) : 0;
      array.set_cmem(l, 10 + j, static_cast<uint8_t>(value >> 8));
      array.set_cmem(l, 20 + j, static_cast<uint8_t>(value));
    }
    array.set_flags(l, {false, false, moved(l)});
  }
  for (const unsigned j : {1u, 0u}) {
    ASSERT_EQ(array.execute(make(Opcode::op_nadds, mem(20 + j), mem(20 + j), direction(Direction::left)), {}, 0), "");
    ASSERT_EQ(array.execute(make(Opcode::op_nadcs, mem(10 + j), mem(10 + j), direction(Direction::left)), {}, 0), "");
  }
  std::vector<std::array<unsigned, 3>> expected(array.lanes());
  for (unsigned l = 0; l < array.lanes(); ++l) {
    for (unsigned j = 0; j < 2; ++j) {
      const unsigned from = j + (moved(l) ? 1 : 0);
      const unsigned incoming = l % COLUMNS == 0 ? 0 : expected[l - 1][from];
      expected[l][j] = (incoming + own(l, j)) & 0xffffu;
    }
    expected[l][2] = 0;
    for (unsigned j = 0; j < 2; ++j) {
      EXPECT_EQ(array.cmem(l, 10 + j) << 8 | array.cmem(l, 20 + j), expected[l][j]) << "lane " << l << " slot " << j;
    }
    // S (the selector) and Z are kept; C is the high byte's carry.
    EXPECT_EQ(array.flags(l).s, moved(l)) << l;
    EXPECT_FALSE(array.flags(l).z) << l;
  }
}

TEST(CuArray, LutReadsTheSharedTablesEntryAtEachCusIndex) {
  CuArray array(small_cmem_geometry());
  array.set_lut_entries(300);
  for (unsigned i = 0; i < 300; ++i) array.set_lut_entry(i, static_cast<uint16_t>(0x8000 + 7 * i));
  for (unsigned l = 0; l < array.lanes(); ++l) {
    const unsigned index = 3 * l;  // up to 285: both bytes of the index used
    array.set_reg(l, 2, static_cast<uint8_t>(index >> 8));
    array.set_reg(l, 3, static_cast<uint8_t>(index));
    array.set_cmem(l, 8, static_cast<uint8_t>(index >> 8));
    array.set_cmem(l, 9, static_cast<uint8_t>(index));
    array.set_cmem(l, 20, 0x11);
    array.set_cmem(l, 21, 0x22);
    array.set_mask(l, l % 3 != 0);
  }
  const CuFlags flags = array.flags(5);
  ASSERT_EQ(array.execute(make(Opcode::op_lut, reg(0), reg(2)), {}, 0), "");
  // From CMEM into CMEM: stored where the mask is set.
  ASSERT_EQ(array.execute(make(Opcode::op_lut, mem(20), mem(8)), {}, 0), "");
  for (unsigned l = 0; l < array.lanes(); ++l) {
    const unsigned entry = 0x8000 + 21 * l;
    EXPECT_EQ(array.reg(l, 0), entry >> 8) << l;
    EXPECT_EQ(array.reg(l, 1), entry & 0xff) << l;
    EXPECT_EQ(array.cmem(l, 20), l % 3 != 0 ? entry >> 8 : 0x11) << l;
    EXPECT_EQ(array.cmem(l, 21), l % 3 != 0 ? (entry & 0xff) : 0x22) << l;
  }
  EXPECT_EQ(array.flags(5), flags) << "lut writes no flag";
  // An index beyond the table in one CU: refused, naming the CU, the index
  // and the key; nothing changes.
  array.set_reg(17, 3, 44);
  array.set_reg(17, 2, 1);  // 300
  const std::string error = array.execute(make(Opcode::op_lut, reg(4), reg(2)), {}, 0);
  EXPECT_NE(error.find("lut index 300 in CU 17"), std::string::npos) << error;
  EXPECT_NE(error.find("array.lut.entries"), std::string::npos) << error;
  EXPECT_EQ(array.last_fault(), CuArray::Fault::lut_index);
  EXPECT_EQ(array.reg(0, 4), 0);
}

// --- ArrayController -------------------------------------------------------

constexpr unsigned PROGRAM_WORDS = 64;
// --- MorphoSys's 16-bit operations (array.features.wide_ops) -------------

// The 16-bit model the pair operations are checked against: plain integer
// arithmetic on the two bytes joined, nothing of the byte passes.
struct Pair16 {
  uint16_t value;
  CuFlags flags;
  bool writes;
};
Pair16 pair_model(Opcode opcode, unsigned x, unsigned y, CuFlags before) {
  switch (opcode) {
    case Opcode::op_add16: {
      const unsigned sum = x + y;
      return {static_cast<uint16_t>(sum), {sum > 0xffff, (sum & 0xffff) == 0, (sum & 0x8000) != 0}, true};
    }
    case Opcode::op_sub16:
    case Opcode::op_cmp16: {
      const unsigned difference = (x - y) & 0xffff;
      return {static_cast<uint16_t>(difference),
              {x >= y, difference == 0, (difference & 0x8000) != 0},
              opcode == Opcode::op_sub16};
    }
    default: return {static_cast<uint16_t>(x), {before.c, x == 0, (x & 0x8000) != 0}, true};
  }
}

TEST(CuDatapath, PairOperationsMatchA16BitModel) {
  // By hand: the carry and Z of all 16 bits (0x0010 + 0x0002 = 0x0012: an
  // add/adc chain's Z, the high byte's, would be set), no borrow, C kept.
  PairResult r = cu_pair_alu(Opcode::op_add16, 0xffff, 0x0001, czs(false, false, true));
  EXPECT_EQ(r.value, 0x0000);
  EXPECT_EQ(r.flags, czs(true, true, false));
  r = cu_pair_alu(Opcode::op_add16, 0x0010, 0x0002, czs(true, true, true));
  EXPECT_EQ(r.value, 0x0012);
  EXPECT_EQ(r.flags, czs(false, false, false));
  r = cu_pair_alu(Opcode::op_sub16, 0x0100, 0x0001, czs(false, false, false));
  EXPECT_EQ(r.value, 0x00ff);
  EXPECT_EQ(r.flags, czs(true, false, false));
  r = cu_pair_alu(Opcode::op_cmp16, 0x1234, 0x1235, czs(true, true, false));
  EXPECT_EQ(r.value, 0xffff);
  EXPECT_EQ(r.flags, czs(false, false, true));
  EXPECT_FALSE(r.writes);
  r = cu_pair_alu(Opcode::op_mov16, 0x8000, 0, czs(true, true, false));
  EXPECT_EQ(r.flags, czs(true, false, true));
  // Random values and flags.
  std::mt19937_64 rng(0x1616);
  for (unsigned i = 0; i < 200'000; ++i) {
    const auto opcode = std::array{Opcode::op_add16, Opcode::op_sub16, Opcode::op_cmp16, Opcode::op_mov16}[i % 4];
    const auto x = static_cast<uint16_t>(rng()), y = static_cast<uint16_t>(rng());
    const CuFlags before{(rng() & 1) != 0, (rng() & 2) != 0, (rng() & 4) != 0};
    const PairResult got = cu_pair_alu(opcode, x, y, before);
    const Pair16 expected = pair_model(opcode, x, y, before);
    ASSERT_EQ(got.value, expected.value) << op_info(opcode).mnemonic << " " << x << ", " << y;
    ASSERT_EQ(got.flags, expected.flags) << op_info(opcode).mnemonic << " " << x << ", " << y;
    ASSERT_EQ(got.writes, expected.writes) << op_info(opcode).mnemonic;
  }
}

// Every lane, random pairs of registers (d equal to a source included),
// random values, flags and masks: the core against the 16-bit model. The
// registers are written in every CU, masked or not; nothing else changes.
TEST(CuArray, PairOperationsInEveryLaneMatchA16BitModel) {
  std::mt19937_64 rng(0xa16);
  CuArray array(small_cmem_geometry());
  const std::array<Opcode, 4> opcodes{Opcode::op_add16, Opcode::op_sub16, Opcode::op_cmp16, Opcode::op_mov16};
  std::array<unsigned, 4> runs{};
  for (unsigned i = 0; i < 4000; ++i) {
    const auto which = static_cast<unsigned>(rng() % opcodes.size());
    const Opcode opcode = opcodes[which];
    const Instruction in =
        make(opcode, reg(static_cast<unsigned>(rng() % (REGISTERS - 1))),
             reg(static_cast<unsigned>(rng() % (REGISTERS - 1))),
             opcode == Opcode::op_mov16 ? reg(0) : reg(static_cast<unsigned>(rng() % (REGISTERS - 1))));
    Instruction encoded = in;
    if (opcode == Opcode::op_cmp16) encoded.d = {};
    if (opcode == Opcode::op_mov16) encoded.b = {};
    const Decoded decoded = decode(encode(encoded));
    if (!decoded.error.empty()) {
      // Only a result pair straddling a source pair is refused.
      EXPECT_NE(decoded.error.find("overlaps a source pair"), std::string::npos) << decoded.error;
      continue;
    }
    ++runs[which];
    std::vector<Lane> before(array.lanes());
    for (unsigned l = 0; l < array.lanes(); ++l) {
      for (unsigned r = 0; r < REGISTERS; ++r) array.set_reg(l, r, static_cast<uint8_t>(rng()));
      array.set_flags(l, {(rng() & 1) != 0, (rng() & 2) != 0, (rng() & 4) != 0});
      array.set_mask(l, (rng() & 8) != 0);
      for (unsigned r = 0; r < REGISTERS; ++r) before[l].regs[r] = array.reg(l, r);
      before[l].flags = array.flags(l);
    }
    const Instruction& run = decoded.instruction;
    ASSERT_EQ(array.execute(run, {}, 0), "") << format_instruction(run);
    for (unsigned l = 0; l < array.lanes(); ++l) {
      const auto pair = [&](const Operand& o) {
        return unsigned{before[l].regs[o.value]} << 8 | before[l].regs[o.value + 1];
      };
      const Pair16 expected =
          pair_model(opcode, pair(run.a), opcode == Opcode::op_mov16 ? 0 : pair(run.b), before[l].flags);
      std::array<uint8_t, REGISTERS> regs = before[l].regs;
      if (expected.writes) {
        regs[run.d.value] = static_cast<uint8_t>(expected.value >> 8);
        regs[run.d.value + 1] = static_cast<uint8_t>(expected.value);
      }
      for (unsigned r = 0; r < REGISTERS; ++r)
        ASSERT_EQ(array.reg(l, r), regs[r]) << format_instruction(run) << ", lane " << l << ", r" << r;
      ASSERT_EQ(array.flags(l), expected.flags) << format_instruction(run) << ", lane " << l;
    }
  }
  for (unsigned count : runs) EXPECT_GT(count, 500u);
}

constexpr uint64_t MAX_CYCLES = 1'000'000;

Instruction loop(unsigned level, unsigned start, unsigned step) {
  return make(Opcode::op_loop, reg(level), reg(start), reg(step));
}

struct Program {
  ArrayController controller{small_cmem_geometry(), CycleTable::defaults(), PROGRAM_WORDS, MAX_CYCLES};

  explicit Program(const std::vector<Instruction>& instructions) {
    std::vector<uint64_t> words;
    words.reserve(instructions.size());
    for (const Instruction& in : instructions) words.push_back(encode(in));
    EXPECT_TRUE(controller.load(0, words));
  }
  CuArray& array() { return controller.array(); }
};

TEST(ArrayController, CycleTableDefaultsByHand) {
  const CycleTable table = CycleTable::defaults();
  // Register ALU ops 2, one more with a CMEM operand; mul 40, mulm 105
  // (always in CMEM: no extra); mask ops, loop, halt, nop 1; endloop 0.
  EXPECT_EQ(table.cost(make(Opcode::op_add, reg(0), reg(1), reg(2))), 2u);
  EXPECT_EQ(table.cost(make(Opcode::op_add, reg(0), mem(1), reg(2))), 3u);
  EXPECT_EQ(table.cost(make(Opcode::op_add, mem(0), mem(1), mem(2))), 3u);
  EXPECT_EQ(table.cost(make(Opcode::op_ror, mem(0), reg(1))), 3u);
  EXPECT_EQ(table.cost(make(Opcode::op_cmpc, {}, reg(1), reg(2))), 2u);
  EXPECT_EQ(table.cost(make(Opcode::op_nget, reg(0), reg(1), reg(3))), 2u);
  EXPECT_EQ(table.cost(make(Opcode::op_nget, reg(0), mem(1), reg(3))), 3u);
  EXPECT_EQ(table.cost(make(Opcode::op_getm, mem(0))), 3u);
  EXPECT_EQ(table.cost(make(Opcode::op_mul, reg(0), reg(3), reg(5))), 40u);
  EXPECT_EQ(table.cost(make(Opcode::op_mulm, mem(0), mem(3), mem(5))), 105u);
  // The Image Blender's: div an ALU operation (RM), nadd a register one.
  EXPECT_EQ(table.cost(make(Opcode::op_div, reg(0), reg(1), reg(3))), 2u);
  EXPECT_EQ(table.cost(make(Opcode::op_div, mem(0), mem(1), reg(3))), 3u);
  EXPECT_EQ(table.cost(make(Opcode::op_nadd, reg(0), reg(1), reg(2))), 2u);
  for (Opcode opcode : {Opcode::op_mset, Opcode::op_mclr, Opcode::op_nop, Opcode::op_halt})
    EXPECT_EQ(table.cost(make(opcode)), 1u) << op_info(opcode).mnemonic;
  for (Opcode opcode : {Opcode::op_mmov, Opcode::op_mand, Opcode::op_mor})
    EXPECT_EQ(table.cost(make_cond(opcode, Cond::hi)), 1u) << op_info(opcode).mnemonic;
  EXPECT_EQ(table.cost(loop(0, 5, 1)), 1u);
  EXPECT_EQ(table.cost(make(Opcode::op_endloop)), 0u);
  // MorphoSys's: two byte passes of an ALU slot each; the wired OR's test.
  EXPECT_EQ(table.cost(make(Opcode::op_add16, reg(0), reg(2), reg(4))), 4u);
  EXPECT_EQ(table.cost(make(Opcode::op_mov16, reg(0), reg(2))), 4u);
  EXPECT_EQ(table.cost(make_cond(Opcode::op_endloopany, Cond::nz)), 2u);
}

TEST(ArrayController, StraightLineProgramCountsEveryInstruction) {
  Program p({
      make(Opcode::op_mov, reg(1), mem(0)),           // 3
      make(Opcode::op_add, reg(2), reg(1), reg(1)),   // 2
      make(Opcode::op_mul, reg(3), reg(1), reg(2)),   // 40
      make(Opcode::op_mulm, mem(8), mem(0), mem(2)),  // 105
      make_cond(Opcode::op_mmov, Cond::z),            // 1
      make(Opcode::op_nop),                           // 1
      make(Opcode::op_halt),                          // 1
      make(Opcode::op_add, reg(2), reg(1), reg(1)),   // after the halt: never runs
  });
  p.array().set_cmem(0, 0, 3);
  const RunResult result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 3u + 2 + 40 + 105 + 1 + 1 + 1);
  EXPECT_EQ(result.instructions, 7u);
  EXPECT_EQ(p.array().reg(0, 2), 6);
  EXPECT_EQ(p.controller.activity().instruction_mix[static_cast<unsigned>(Opcode::op_add)], 1u);
}

TEST(ArrayController, LoopRunsWhileItsVariableIsNonNegativeAndAddressesMoveWithIt) {
  // r1 = 1; for (i0 = 3; i0 >= 0; i0 -= 1) { r0 += r1; [20 + i0] = r0; }
  Program p({
      make(Opcode::op_mov, reg(1), mem(0)),          // 3
      loop(0, 3, 1),                                 // 1
      make(Opcode::op_add, reg(0), reg(0), reg(1)),  // 2, 4 times
      make(Opcode::op_mov, mem(20, 1), reg(0)),      // 3, 4 times
      make(Opcode::op_endloop),                      // 0
      make(Opcode::op_halt),                         // 1
  });
  for (unsigned l = 0; l < COLUMNS * ROWS; ++l) p.array().set_cmem(l, 0, 1);
  const RunResult result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 3u + 1 + 4 * (2 + 3 + 0) + 1);
  EXPECT_EQ(result.instructions, 1u + 1 + 4 * 3 + 1);
  for (unsigned l : {0u, 95u}) {
    EXPECT_EQ(p.array().cmem(l, 23), 1);
    EXPECT_EQ(p.array().cmem(l, 22), 2);
    EXPECT_EQ(p.array().cmem(l, 21), 3);
    EXPECT_EQ(p.array().cmem(l, 20), 4);
    EXPECT_EQ(p.array().reg(l, 0), 4);
  }
}

TEST(ArrayController, LoopWithAStepAboveOne) {
  // i0 = 6, 3, 0: three passes.
  Program p({
      make(Opcode::op_mov, reg(1), mem(0)),
      loop(0, 6, 3),
      make(Opcode::op_add, reg(0), reg(0), reg(1)),
      make(Opcode::op_mov, mem(20, 1), reg(0)),
      make(Opcode::op_endloop),
      make(Opcode::op_halt),
  });
  for (unsigned l = 0; l < COLUMNS * ROWS; ++l) {
    p.array().set_cmem(l, 0, 1);
    for (unsigned a = 20; a < 28; ++a) p.array().set_cmem(l, a, 0xee);
  }
  const RunResult result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 3u + 1 + 3 * 5 + 1);
  EXPECT_EQ(p.array().cmem(7, 26), 1);
  EXPECT_EQ(p.array().cmem(7, 23), 2);
  EXPECT_EQ(p.array().cmem(7, 20), 3);
  for (unsigned a : {21u, 22u, 24u, 25u, 27u}) EXPECT_EQ(p.array().cmem(7, a), 0xee) << a;
}

TEST(ArrayController, NestedLoopsEachWithItsOwnVariable) {
  Program p({
      make(Opcode::op_mov, reg(1), mem(0)),          // 0: 3
      loop(0, 1, 1),                                 // 1: 1; i0 = 1, 0
      loop(1, 2, 1),                                 // 2: 1 per outer pass; i1 = 2, 1, 0
      make(Opcode::op_add, reg(0), reg(0), reg(1)),  // 3: 2
      make(Opcode::op_mov, mem(30, 2), reg(0)),      // 4: 3
      make(Opcode::op_endloop),                      // 5: 0
      make(Opcode::op_mov, mem(40, 1), reg(0)),      // 6: 3
      make(Opcode::op_endloop),                      // 7: 0
      make(Opcode::op_halt),                         // 8: 1
  });
  for (unsigned l = 0; l < COLUMNS * ROWS; ++l) p.array().set_cmem(l, 0, 1);
  const RunResult result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 3u + 1 + 2 * (1 + 3 * (2 + 3 + 0) + 3 + 0) + 1);
  EXPECT_EQ(result.instructions, 1u + 1 + 2 * (1 + 3 * 3 + 2) + 1);
  // Second outer pass overwrites the inner stores: 4, 5, 6 at 32, 31, 30.
  EXPECT_EQ(p.array().cmem(50, 32), 4);
  EXPECT_EQ(p.array().cmem(50, 31), 5);
  EXPECT_EQ(p.array().cmem(50, 30), 6);
  EXPECT_EQ(p.array().cmem(50, 41), 3);
  EXPECT_EQ(p.array().cmem(50, 40), 6);
  const ControllerActivity& activity = p.controller.activity();
  EXPECT_EQ(activity.word_executions[3], 6u);
  EXPECT_EQ(activity.word_executions[2], 2u);
  EXPECT_EQ(activity.word_cycles[4], 18u);
}

TEST(ArrayController, UndecodableWordStopsTheRunThere) {
  Program p({make(Opcode::op_mset), make(Opcode::op_nop)});
  ASSERT_TRUE(p.controller.write_word(1, 0x3f));  // opcode 63: none
  RunResult result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.error_pc, 1u);
  EXPECT_NE(result.error.find("unknown opcode"), std::string::npos) << result.error;
  EXPECT_EQ(result.cycles, 1u);
  // Reserved bits 63:60.
  ASSERT_TRUE(p.controller.write_word(1, encode(make(Opcode::op_nop)) | uint64_t{1} << 60));
  result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.error.find("reserved"), std::string::npos) << result.error;
  // A register beyond the CU's file (r8 of 8) is refused by the limits.
  ASSERT_TRUE(p.controller.write_word(1, encode(make(Opcode::op_mov, reg(8), reg(0)))));
  result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.error_pc, 1u);
}

TEST(ArrayController, TheImageBlendersInstructionsAreRefusedNamingTheirSwitchUnlessEnabled) {
  const Instruction div = make(Opcode::op_div, reg(0), reg(1), reg(3));
  const Instruction nadd = make(Opcode::op_nadd, reg(0), reg(1), {false, static_cast<uint16_t>(Direction::up), 0});
  for (const auto& [in, key] :
       {std::pair{div, "array.features.divide"}, std::pair{nadd, "array.features.neighbour_add"}}) {
    Program p({make(Opcode::op_mset), in, make(Opcode::op_halt)});
    RunResult result = p.controller.run(0);
    EXPECT_FALSE(result.ok);
    EXPECT_EQ(result.kind, RunError::bad_word);
    EXPECT_EQ(result.error_pc, 1u);
    EXPECT_NE(result.error.find(key), std::string::npos) << result.error;
    EXPECT_EQ(result.cycles, 1u) << "only the mset ran";
    // Enabled, the same words run: 1 + 2 + 1 cycles.
    EnabledOps enabled = j2210_ops();
    enabled[static_cast<unsigned>(in.opcode)] = true;
    p.controller.enable_ops(enabled);
    result = p.controller.run(0);
    EXPECT_TRUE(result.ok) << result.error;
    EXPECT_EQ(result.cycles, 4u);
    // And off again.
    p.controller.enable_ops(j2210_ops());
    EXPECT_FALSE(p.controller.run(0).ok);
  }
  // Each enables only its own instruction.
  EXPECT_EQ(feature_key(op_info(Opcode::op_div)), "array.features.divide");
  EXPECT_EQ(feature_key(op_info(Opcode::op_nadd)), "array.features.neighbour_add");
  EXPECT_EQ(feature_key(op_info(Opcode::op_lut)), "array.features.lut");
  EXPECT_EQ(feature_key(op_info(Opcode::op_nadds)), "array.features.neighbour_add");
  EXPECT_EQ(feature_key(op_info(Opcode::op_nadcs)), "array.features.neighbour_add");
  EXPECT_EQ(feature_key(op_info(Opcode::op_zsend)), "array.features.zsend");
  for (const Opcode opcode : {Opcode::op_add16, Opcode::op_sub16, Opcode::op_cmp16, Opcode::op_mov16})
    EXPECT_EQ(feature_key(op_info(opcode)), "array.features.wide_ops");
  EXPECT_EQ(feature_key(op_info(Opcode::op_endloopany)), "array.features.wired_or_loop");
  for (const OpInfo& info : all_ops())
    if (info.opcode != Opcode::op_div && info.opcode != Opcode::op_nadd && info.opcode != Opcode::op_lut &&
        info.opcode != Opcode::op_nadds && info.opcode != Opcode::op_nadcs && info.opcode != Opcode::op_zsend &&
        !is_pair_op(info.opcode) && info.opcode != Opcode::op_endloopany) {
      EXPECT_TRUE(info.feature.empty()) << info.mnemonic;
      EXPECT_TRUE(j2210_ops()[static_cast<unsigned>(info.opcode)]) << info.mnemonic;
    }
}

TEST(ArrayController, DelayedExecutionAddsTheChainsSkewToAProgramThatHalts) {
  // mset 1, add 2, halt 1: 4 cycles lockstep; with K = 3, 95 x 3 more,
  // counted in the halt's word and stage.
  Program p({make(Opcode::op_mset), make(Opcode::op_add, reg(0), reg(1), reg(2)), make(Opcode::op_halt)});
  RunResult result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 4u);
  p.controller.set_issue_skew(3);
  result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 4u + 95 * 3);
  const ControllerActivity& activity = p.controller.activity();
  EXPECT_EQ(activity.skew_cycles, 95u * 3);
  EXPECT_EQ(activity.cycles, 4u + 4 + 95 * 3);
  EXPECT_EQ(activity.word_cycles[2], 2u + 95 * 3);
  uint64_t stages = 0;
  for (const uint64_t cycles : activity.stage_cycles) stages += cycles;
  EXPECT_EQ(stages, activity.cycles);
  // A program that fails has no skew added.
  ASSERT_TRUE(p.controller.write_word(2, uint64_t{1} << 63));
  result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.cycles, 3u);
}

TEST(ArrayController, RowSkewAddsTheRowsSkewToAProgramThatHalts) {
  // mset 1, add 2, halt 1: 4 cycles lockstep; by row with K = 5, (4 - 1) x
  // 5 more, counted in the halt's word and stage.
  Program p({make(Opcode::op_mset), make(Opcode::op_add, reg(0), reg(1), reg(2)), make(Opcode::op_halt)});
  p.controller.set_issue_skew(IssueSkew::row, 5);
  EXPECT_EQ(p.controller.issue_skew(), IssueSkew::row);
  EXPECT_EQ(p.array().issue_skew(), IssueSkew::row);
  RunResult result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 4u + 3 * 5);
  const ControllerActivity& activity = p.controller.activity();
  EXPECT_EQ(activity.skew_cycles, 3u * 5);
  EXPECT_EQ(activity.word_cycles[2], 1u + 3 * 5);
  uint64_t stages = 0;
  for (const uint64_t cycles : activity.stage_cycles) stages += cycles;
  EXPECT_EQ(stages, activity.cycles);
  // Back to lockstep: no skew.
  p.controller.set_issue_skew(IssueSkew::none, 5);
  EXPECT_EQ(p.array().issue_skew(), IssueSkew::none);
  EXPECT_EQ(p.controller.run(0).cycles, 4u);
  EXPECT_EQ(p.controller.activity().skew_cycles, 3u * 5);
}

// Under row skew the CUs of a row look up together: ceil(24 / P) cycles, a
// stall of ceil(24 / P) - 1 in every row alike (so in the word's cost), and
// the row's lookups must end before the next row's begin: ceil(24 / P) <= K,
// else the lut is refused naming the keys.
TEST(ArrayController, UnderRowSkewARowsLookupsMustFitInTheSkew) {
  const Instruction lut = make(Opcode::op_lut, reg(0), reg(2));
  Program p({make(Opcode::op_mset), lut, lut, make(Opcode::op_halt)});
  EnabledOps enabled = j2210_ops();
  enabled[static_cast<unsigned>(Opcode::op_lut)] = true;
  p.controller.enable_ops(enabled);
  p.array().set_lut_entries(4);
  p.array().set_lut_entry(0, 0xbeef);
  p.controller.set_lut_ports(4);  // 6 cycles a row
  p.controller.set_issue_skew(IssueSkew::row, 5);
  RunResult result = p.controller.run(0);
  EXPECT_EQ(result.kind, RunError::bad_word);
  EXPECT_EQ(result.error_pc, 1u);
  for (const char* key : {"array.issue_skew", "array.lut.ports", "array.issue_skew_cycles"})
    EXPECT_NE(result.error.find(key), std::string::npos) << result.error;
  p.controller.set_issue_skew(IssueSkew::row, 6);
  result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  // 1 + 2 x (2 + 5) + 1, then (4 - 1) x 6.
  EXPECT_EQ(result.cycles, uint64_t{1 + 2 * 7 + 1 + 18});
  EXPECT_EQ(p.controller.activity().lut_stall_cycles, 2u * 5);
  EXPECT_EQ(p.array().reg(95, 0), 0xbe);
  EXPECT_EQ(p.array().reg(95, 1), 0xef);
}

// The lookup table's timing (README.md, "The lookup table"): lockstep, a lut
// takes ceil(96 / P) - 1 cycles more than its 2; under skew each lut holds a
// port for (96 - 1) x K + 1 cycles.
TEST(ArrayController, LutStallsForTheTablesPorts) {
  const Instruction lut = make(Opcode::op_lut, reg(0), reg(2));
  Program p({make(Opcode::op_mset), lut, lut, make(Opcode::op_halt)});
  RunResult result = p.controller.run(0);
  EXPECT_EQ(result.kind, RunError::bad_word);
  EXPECT_NE(result.error.find("lut is not enabled: it needs array.features.lut = true"), std::string::npos)
      << result.error;
  EnabledOps enabled = j2210_ops();
  enabled[static_cast<unsigned>(Opcode::op_lut)] = true;
  p.controller.enable_ops(enabled);
  p.array().set_lut_entries(4);
  p.array().set_lut_entry(0, 0xbeef);
  const auto run = [&](unsigned ports, unsigned skew) {
    p.controller.set_lut_ports(ports);
    p.controller.set_issue_skew(skew);
    const uint64_t stalls = p.controller.activity().lut_stall_cycles;
    const RunResult r = p.controller.run(0);
    EXPECT_TRUE(r.ok) << r.error;
    return std::pair{r.cycles, p.controller.activity().lut_stall_cycles - stalls};
  };
  // Lockstep: 1 + 2 x (2 + stall) + 1.
  EXPECT_EQ(run(1, 0), std::pair(uint64_t{1 + 2 * (2 + 95) + 1}, uint64_t{2 * 95}));
  EXPECT_EQ(run(4, 0), std::pair(uint64_t{1 + 2 * (2 + 23) + 1}, uint64_t{2 * 23}));
  EXPECT_EQ(run(96, 0), std::pair(uint64_t{1 + 2 * 2 + 1}, uint64_t{0}));
  EXPECT_EQ(p.array().reg(7, 0), 0xbe);
  EXPECT_EQ(p.array().reg(7, 1), 0xef);
  // Skew K = 1, one port: the first lut (at cycle 1) holds the port until
  // 1 + 96; the second, due at 3, waits 94 cycles. Then the skew, 95.
  EXPECT_EQ(run(1, 1), std::pair(uint64_t{1 + 2 + 94 + 2 + 1 + 95}, uint64_t{94}));
  // Two ports: no wait.
  EXPECT_EQ(run(2, 1), std::pair(uint64_t{1 + 2 + 2 + 1 + 95}, uint64_t{0}));
  // K = 2, one port: the port is held 95 x 2 + 1 = 191 cycles.
  EXPECT_EQ(run(1, 2), std::pair(uint64_t{1 + 2 + (192 - 3) + 2 + 1 + 190}, uint64_t{192 - 3}));
  // The stalls are in the profile: the words' cycles add up to the total.
  uint64_t words = 0;
  for (const uint64_t cycles : p.controller.activity().word_cycles) words += cycles;
  EXPECT_EQ(words, p.controller.activity().cycles);
  // An index beyond the table stops the program there: ERROR_CODE 6.
  p.array().set_reg(30, 3, 4);
  result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.kind, RunError::lut_index);
  EXPECT_EQ(result.error_pc, 1u);
  EXPECT_NE(result.error.find("lut index 4 in CU 30 is beyond the table's 4 entries (array.lut.entries)"),
            std::string::npos)
      << result.error;
}

TEST(ArrayController, AddressPlusLoopVariableBeyondCmemStopsTheRun) {
  // i0 = 10 first: [60 + 10] is beyond the 64 bytes; the store before runs.
  Program p({
      make(Opcode::op_mov, mem(1), reg(0)),
      loop(0, 10, 1),
      make(Opcode::op_mov, mem(60, 1), reg(0)),
      make(Opcode::op_endloop),
      make(Opcode::op_halt),
  });
  p.array().set_cmem(0, 1, 0x55);
  const RunResult result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.error_pc, 2u);
  EXPECT_NE(result.error.find("CMEM address 70"), std::string::npos) << result.error;
  EXPECT_EQ(result.cycles, 3u + 1);
  EXPECT_EQ(p.array().cmem(0, 1), 0);
  EXPECT_EQ(p.controller.activity().failed_programs, 1u);
}

TEST(ArrayController, EndloopWithNoLoopAndLoopAtTheWrongLevelAreErrors) {
  Program endloop({make(Opcode::op_nop), make(Opcode::op_endloop), make(Opcode::op_halt)});
  RunResult result = endloop.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.error_pc, 1u);
  EXPECT_NE(result.error.find("endloop with no loop"), std::string::npos) << result.error;

  Program level({loop(1, 2, 1), make(Opcode::op_endloop), make(Opcode::op_halt)});
  result = level.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.error_pc, 0u);
}

TEST(ArrayController, RunningPastProgramMemoryIsAnError) {
  // Program memory is all nop (word 0) until written: 64 nops, no halt.
  Program p({});
  const RunResult result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.error_pc, PROGRAM_WORDS);
  EXPECT_NE(result.error.find("past the end"), std::string::npos) << result.error;
  EXPECT_EQ(result.cycles, PROGRAM_WORDS);
  // An entry point beyond it fails at once.
  EXPECT_FALSE(p.controller.run(PROGRAM_WORDS + 3).ok);
}

TEST(ArrayController, MaxProgramCyclesStopsARunaway) {
  ArrayController controller(small_cmem_geometry(), CycleTable::defaults(), PROGRAM_WORDS, 100);
  ASSERT_TRUE(controller.load(0, {encode(loop(0, MAX_LOOP_START, 1)), encode(make(Opcode::op_nop)),
                                  encode(make(Opcode::op_endloop)), encode(make(Opcode::op_halt))}));
  // loop 1 cycle, then 1 per nop: the 100th nop brings the total to 101.
  const RunResult result = controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.error_pc, 1u);
  EXPECT_EQ(result.cycles, 101u);
  EXPECT_NE(result.error.find("max_program_cycles"), std::string::npos) << result.error;
}

// --- MorphoSys's loop that exits when no CU is left (array.features.wired_or_loop)

EnabledOps with_wired_or_loop() {
  EnabledOps enabled = j2210_ops();
  enabled[static_cast<unsigned>(Opcode::op_endloopany)] = true;
  return enabled;
}

// Each CU counts its own number down: r0 from CMEM byte 1, minus 1 (CMEM
// byte 0) per pass, its mask cleared when it reaches 0; the loop runs
// while a masked-in CU has not reached it, at most 101 passes.
std::vector<Instruction> countdown_program(Opcode closing) {
  return {
      make(Opcode::op_mset),                                                            // 0: 1
      make(Opcode::op_mov, reg(1), mem(0)),                                             // 1: 3
      make(Opcode::op_mov, reg(0), mem(1)),                                             // 2: 3
      loop(0, 100, 1),                                                                  // 3: 1
      make(Opcode::op_sub, reg(0), reg(0), reg(1)),                                     // 4: 2 a pass
      make_cond(Opcode::op_mand, Cond::nz),                                             // 5: 1 a pass
      closing == Opcode::op_endloopany ? make_cond(closing, Cond::nz) : make(closing),  // 6: 2 (0) a pass
      make(Opcode::op_halt),                                                            // 7: 1
  };
}

TEST(ArrayController, EndloopanyLeavesTheLoopWhenNoMaskedCuHasTheCondition) {
  Program p(countdown_program(Opcode::op_endloopany));
  p.controller.enable_ops(with_wired_or_loop());
  // Counts 1..8 by lane, and one CU with 20: twenty passes.
  for (unsigned l = 0; l < p.array().lanes(); ++l) {
    p.array().set_cmem(l, 0, 1);
    p.array().set_cmem(l, 1, static_cast<uint8_t>(l == 37 ? 20 : 1 + l % 8));
  }
  const RunResult result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 1u + 3 + 3 + 1 + 20 * (2 + 1 + 2) + 1);
  EXPECT_EQ(result.instructions, 4u + 20 * 3 + 1);
  for (unsigned l = 0; l < p.array().lanes(); ++l) {
    EXPECT_FALSE(p.array().mask(l)) << l;
    // A CU that reached 0 kept counting, below 0, until the loop ended.
    const unsigned count = l == 37 ? 20 : 1 + l % 8;
    EXPECT_EQ(p.array().reg(l, 0), static_cast<uint8_t>(count - 20)) << l;
  }
  const ControllerActivity& activity = p.controller.activity();
  EXPECT_EQ(activity.wired_or_exits, 1u);
  EXPECT_EQ(activity.wired_or_iterations_saved, 101u - 20);
  EXPECT_EQ(activity.word_executions[6], 20u);
  EXPECT_EQ(activity.word_cycles[6], 40u);
  // The profile and the stages add up to the total.
  uint64_t words = 0, stages = 0;
  for (const uint64_t cycles : activity.word_cycles) words += cycles;
  for (const uint64_t cycles : activity.stage_cycles) stages += cycles;
  EXPECT_EQ(words, activity.cycles);
  EXPECT_EQ(stages, activity.cycles);
  EXPECT_EQ(activity.cycles, result.cycles);
  // With endloop, the same program runs every one of its 101 passes.
  Program counted(countdown_program(Opcode::op_endloop));
  for (unsigned l = 0; l < counted.array().lanes(); ++l) {
    counted.array().set_cmem(l, 0, 1);
    counted.array().set_cmem(l, 1, 3);
  }
  const RunResult full = counted.controller.run(0);
  ASSERT_TRUE(full.ok) << full.error;
  EXPECT_EQ(full.cycles, 1u + 3 + 3 + 1 + 101 * (2 + 1 + 0) + 1);
  EXPECT_EQ(counted.controller.activity().wired_or_exits, 0u);
}

TEST(ArrayController, EndloopanyCountsOnlyCusWhoseMaskIsSetAndStopsAtTheCount) {
  // loop i0 = 9 .. 0 { nop } endloopany c: ten passes at most.
  Program p({loop(0, 9, 1), make(Opcode::op_nop), make_cond(Opcode::op_endloopany, Cond::c), make(Opcode::op_halt)});
  p.controller.enable_ops(with_wired_or_loop());
  // Only CU 3 has C, and its mask is clear: one pass, nine saved.
  p.array().set_flags(3, {true, false, false});
  p.array().set_mask(3, false);
  RunResult result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 1u + 1 * (1 + 2) + 1);
  EXPECT_EQ(p.controller.activity().wired_or_exits, 1u);
  EXPECT_EQ(p.controller.activity().wired_or_iterations_saved, 9u);
  // Its mask set, it keeps the loop to its count: ten passes, no early exit.
  p.array().set_mask(3, true);
  result = p.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 1u + 10 * (1 + 2) + 1);
  EXPECT_EQ(p.controller.activity().wired_or_exits, 1u);
  EXPECT_EQ(p.controller.activity().wired_or_iterations_saved, 9u);
  // No CU's mask set: the first test leaves the loop.
  for (unsigned l = 0; l < p.array().lanes(); ++l) p.array().set_mask(l, false);
  result = p.controller.run(0);
  EXPECT_EQ(result.cycles, 1u + 1 * (1 + 2) + 1);
  EXPECT_EQ(p.controller.activity().wired_or_exits, 2u);
}

TEST(ArrayController, EndloopanyIsRefusedOffUnderSkewAndOutsideALoop) {
  Program p({loop(0, 3, 1), make_cond(Opcode::op_endloopany, Cond::z), make(Opcode::op_halt)});
  RunResult result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.kind, RunError::bad_word);
  EXPECT_EQ(result.error_pc, 1u);
  EXPECT_NE(result.error.find("endloopany is not enabled: it needs array.features.wired_or_loop = true"),
            std::string::npos)
      << result.error;
  p.controller.enable_ops(with_wired_or_loop());
  EXPECT_TRUE(p.controller.run(0).ok);
  // Under delayed execution the wired OR would wait for the chain's last CU.
  p.controller.set_issue_skew(1);
  result = p.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.kind, RunError::bad_word);
  EXPECT_NE(result.error.find("endloopany under delayed execution"), std::string::npos) << result.error;
  p.controller.set_issue_skew(0);
  // With no loop running, as endloop.
  Program outside({make_cond(Opcode::op_endloopany, Cond::z), make(Opcode::op_halt)});
  outside.controller.enable_ops(with_wired_or_loop());
  result = outside.controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.kind, RunError::loop);
  EXPECT_NE(result.error.find("endloopany with no loop running"), std::string::npos) << result.error;
}

// The runaway check counts a wired-OR loop at its count, the most it runs:
// refused at START, not run, though the CUs' flags would end it at once.
TEST(ArrayController, ARunawayCountsAWiredOrLoopAtItsCount) {
  ArrayController controller(small_cmem_geometry(), CycleTable::defaults(), PROGRAM_WORDS, 100);
  controller.enable_ops(with_wired_or_loop());
  ASSERT_TRUE(controller.load(
      0, {encode(make(Opcode::op_mov, reg(0), mem(0))), encode(loop(0, 1000, 1)), encode(make(Opcode::op_nop)),
          encode(make_cond(Opcode::op_endloopany, Cond::c)), encode(make(Opcode::op_halt))}));
  controller.array().set_cmem(0, 0, 0x5a);
  // mov 3, loop 1, then 3 a pass: 32 passes end at 100, the 33rd's nop
  // passes the cap.
  const RunResult result = controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.kind, RunError::too_long);
  EXPECT_EQ(result.error_pc, 2u);
  EXPECT_EQ(result.cycles, 3u + 1 + 32 * 3 + 1);
  EXPECT_EQ(controller.array().reg(0, 0), 0) << "not run";
  EXPECT_EQ(controller.activity().wired_or_exits, 0u);
  // Within the cap, the same program leaves after one pass (no CU has C).
  controller.load(1, {encode(loop(0, 20, 1))});
  const RunResult short_run = controller.run(0);
  ASSERT_TRUE(short_run.ok) << short_run.error;
  EXPECT_EQ(short_run.cycles, 3u + 1 + 3 + 1);
  EXPECT_EQ(controller.activity().wired_or_exits, 1u);
  EXPECT_EQ(controller.activity().wired_or_iterations_saved, 20u);
}

// The AC's control flow depends on the CUs' flags: a program with
// endloopany always runs on every CU, whatever array.skip_idle_cus says.
TEST(ArrayController, AProgramWithEndloopanyRunsOnEveryCu) {
  for (const Opcode closing : {Opcode::op_endloop, Opcode::op_endloopany}) {
    ArrayController controller(small_cmem_geometry(), CycleTable::defaults(), PROGRAM_WORDS, MAX_CYCLES);
    controller.enable_ops(with_wired_or_loop());
    controller.skip_idle_cus(true);
    std::vector<uint64_t> words;
    for (const Instruction& in : countdown_program(closing)) words.push_back(encode(in));
    ASSERT_TRUE(controller.load(0, words));
    for (unsigned l = 0; l < controller.array().lanes(); ++l) {
      controller.array().set_cmem(l, 0, 1);
      controller.array().set_cmem(l, 1, static_cast<uint8_t>(1 + l % 5));
    }
    for (unsigned run = 0; run < 3; ++run) {
      // One CU's count changes: with the wired OR, that changes the passes
      // of every CU.
      controller.array().set_cmem(7, 1, static_cast<uint8_t>(5 + 4 * run));
      ASSERT_TRUE(controller.run(0).ok);
    }
    if (closing == Opcode::op_endloop) {
      EXPECT_GT(controller.lanes_skipped(), 0u);
    } else {
      EXPECT_EQ(controller.lanes_skipped(), 0u);
      EXPECT_EQ(controller.activity().wired_or_exits, 3u);
      EXPECT_EQ(controller.activity().wired_or_iterations_saved, (101u - 5) + (101 - 9) + (101 - 13));
      // CU 0 counted down 13 passes from 1 in the last run.
      EXPECT_EQ(controller.array().reg(0, 0), static_cast<uint8_t>(1 - 13));
    }
  }
}

// The AC's control flow walked step by step, written here apart from the
// controller: after each instruction, its word and the cycles and
// instructions so far, to the halt.
struct TraceStep {
  unsigned pc;
  uint64_t cycles, instructions;
};
std::vector<TraceStep> control_flow_trace(const std::vector<Instruction>& program, const CycleTable& table) {
  struct Running {
    unsigned body;
    int variable;
    unsigned step;
  };
  std::vector<TraceStep> trace;
  std::vector<Running> loops;
  uint64_t cycles = 0;
  for (unsigned pc = 0; pc < program.size();) {
    const Instruction& in = program[pc];
    cycles += table.cost(in);
    trace.push_back({pc, cycles, trace.size() + 1});
    unsigned next = pc + 1;
    if (in.opcode == Opcode::op_halt) break;
    if (in.opcode == Opcode::op_loop) loops.push_back({pc + 1, static_cast<int>(in.loop_start()), in.loop_step()});
    if (in.opcode == Opcode::op_endloop) {
      Running& loop = loops.back();
      loop.variable -= static_cast<int>(loop.step);
      if (loop.variable >= 0)
        next = loop.body;
      else
        loops.pop_back();
    }
    pc = next;
  }
  return trace;
}

// A runaway is stopped before it runs, at the word and cycle count where
// the cap stops it when run: for every cap below the program's length, the
// run's error word, cycles and instructions are the first step of the
// step-by-step walk past the cap; at or above it the program halts.
TEST(ArrayController, ARunawayStopsWhereTheCapWouldStopItWhenRun) {
  // i0 = 5, 3, 1 around a multiply, i1 = 3, 2, 1, 0 around an addition
  // with CMEM addresses plus both variables, and nops.
  const std::vector<Instruction> program = {loop(0, 5, 2),        make(Opcode::op_mul, reg(0), reg(3), reg(5)),
                                            loop(1, 3, 1),        make(Opcode::op_add, mem(10, 2), reg(1), mem(20, 1)),
                                            make(Opcode::op_nop), make(Opcode::op_endloop),
                                            make(Opcode::op_nop), make(Opcode::op_endloop),
                                            make(Opcode::op_halt)};
  const std::vector<TraceStep> trace = control_flow_trace(program, CycleTable::defaults());
  const uint64_t length = trace.back().cycles;
  ASSERT_GT(length, 40u);
  std::vector<uint64_t> words;
  words.reserve(program.size());
  for (const Instruction& in : program) words.push_back(encode(in));
  for (uint64_t cap = 1; cap <= length + 1; ++cap) {
    SCOPED_TRACE("cap " + std::to_string(cap));
    ArrayController controller(small_cmem_geometry(), CycleTable::defaults(), PROGRAM_WORDS, cap);
    ASSERT_TRUE(controller.load(0, words));
    const RunResult result = controller.run(0);
    const auto past = std::find_if(trace.begin(), trace.end(), [cap](const TraceStep& s) { return s.cycles > cap; });
    if (past == trace.end() || past->pc == program.size() - 1) {  // a halt ends the run whatever the cap
      EXPECT_TRUE(result.ok) << result.error;
      EXPECT_EQ(result.cycles, length);
      EXPECT_EQ(result.instructions, trace.size());
      continue;
    }
    EXPECT_FALSE(result.ok);
    EXPECT_EQ(result.kind, RunError::too_long);
    EXPECT_EQ(result.error_pc, past->pc);
    EXPECT_EQ(result.cycles, past->cycles);
    EXPECT_EQ(result.instructions, past->instructions);
    EXPECT_NE(result.error.find("max_program_cycles"), std::string::npos) << result.error;
    EXPECT_EQ(controller.activity().failed_programs, 1u);
  }
}

// Three nested loops of 16,384 iterations around a multiply: about
// 10^13 cycles. Under array.max_program_cycles' default, 10^9, the run
// stops at once, at the word whose cycles pass the cap, instead of
// multiplying for 10^9 cycles (7 s of wall time here, 50-90 s in a loaded
// soc_sim, the simulation held all along).
TEST(ArrayController, ARunawayIsStoppedAtOnce) {
  constexpr uint64_t CAP = 1'000'000'000;
  ArrayController controller(small_cmem_geometry(), CycleTable::defaults(), PROGRAM_WORDS, CAP);
  const std::vector<Instruction> program = {loop(0, MAX_LOOP_START, 1), loop(1, MAX_LOOP_START, 1),
                                            loop(2, MAX_LOOP_START, 1), make(Opcode::op_mul, reg(0), reg(3), reg(5)),
                                            make(Opcode::op_endloop),   make(Opcode::op_endloop),
                                            make(Opcode::op_endloop),   make(Opcode::op_halt)};
  std::vector<uint64_t> words;
  words.reserve(program.size());
  for (const Instruction& in : program) words.push_back(encode(in));
  ASSERT_TRUE(controller.load(0, words));
  const auto start = std::chrono::steady_clock::now();
  const RunResult result = controller.run(0);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 0.5);
  ASSERT_FALSE(result.ok);
  EXPECT_EQ(result.kind, RunError::too_long);
  // The word that took the count past the cap: the multiply or an endloop.
  ASSERT_GE(result.error_pc, 3u);
  ASSERT_LE(result.error_pc, 6u);
  EXPECT_GT(result.cycles, CAP);
  EXPECT_LE(result.cycles - CycleTable::defaults().cost(program[result.error_pc]), CAP);
  EXPECT_NE(result.error.find("program word " + std::to_string(result.error_pc)), std::string::npos) << result.error;
}

TEST(ArrayController, ProgramMemoryBounds) {
  ArrayController controller(small_cmem_geometry(), CycleTable::defaults(), 4, MAX_CYCLES);
  EXPECT_TRUE(controller.write_word(3, 1));
  EXPECT_FALSE(controller.write_word(4, 1));
  EXPECT_EQ(controller.word(3), 1u);
  EXPECT_FALSE(controller.load(2, {0, 0, 0}));
  EXPECT_EQ(controller.word(2), 0u);
  EXPECT_TRUE(controller.load(1, {0, 0, 1}));
}

// Skipping idle CUs: random programs (in a loop, loop variables in their
// addresses), run again and again while a few CUs' CMEM, registers, flags
// and masks change between runs, leave every CU's CMEM, registers, flags
// and mask and every count exactly as running every CU does. The first two
// programs define every register and flag before their random body, which
// reads the low half of CMEM and stores into its own quarter of the high
// half, so a CU that
// nothing changed repeats its last run and is skipped; the third is random
// throughout (registers and flags read before written) and reads a
// neighbour, so it always runs on every CU.
void skipping_idle_cus_changes_nothing(IssueSkew skew, const ArrayGeometry& geometry = small_cmem_geometry()) {
  constexpr unsigned WORDS = 512, BODY = 120, RUNS = 400, LOOP_START = 3, HALF = CMEM_BYTES / 2;
  std::mt19937_64 rng(0x5c1d);
  std::vector<uint64_t> words;
  std::vector<unsigned> entries;
  for (unsigned program = 0; program < 3; ++program) {
    const bool settled = program < 2;
    entries.push_back(static_cast<unsigned>(words.size()));
    if (settled) {
      words.push_back(encode(make(Opcode::op_mset)));
      for (unsigned r = 0; r < REGISTERS; ++r) words.push_back(encode(make(Opcode::op_mov, reg(r), mem(r))));
      words.push_back(encode(make(Opcode::op_add, reg(0), reg(0), mem(0))));  // C, Z and S
    }
    words.push_back(encode(loop(0, LOOP_START, 1)));
    for (unsigned i = 0; i < BODY;) {
      Instruction in = random_instruction(rng, REGISTERS, CMEM_BYTES).instruction;
      const bool reads_neighbour = in.opcode == Opcode::op_nget || in.opcode == Opcode::op_nadd ||
                                   in.opcode == Opcode::op_nadds || in.opcode == Opcode::op_nadcs;
      if (reads_neighbour != (!settled && i == BODY / 2)) continue;
      for (Operand* operand : {&in.d, &in.a, &in.b}) {
        if (!operand->in_cmem) continue;
        operand->loop = rng() % 3 == 0 ? 1 : 0;
        const unsigned span = !settled ? CMEM_BYTES : operand == &in.d ? HALF / 2 : HALF;
        operand->value = static_cast<uint16_t>(operand->value % (span - 3 - LOOP_START));
        if (settled && operand == &in.d)
          operand->value = static_cast<uint16_t>(operand->value + HALF + program * HALF / 2);
      }
      const Decoded decoded = decode(encode(in));
      if (!decoded.error.empty() || !check_limits(decoded.instruction, REGISTERS, CMEM_BYTES).empty()) continue;
      words.push_back(encode(in));
      ++i;
    }
    words.push_back(encode(make(Opcode::op_endloop)));
    words.push_back(encode(make(Opcode::op_halt)));
  }
  ArrayController skipping{geometry, CycleTable::defaults(), WORDS, MAX_CYCLES};
  ArrayController every{geometry, CycleTable::defaults(), WORDS, MAX_CYCLES};
  skipping.skip_idle_cus(true);
  for (ArrayController* controller : {&skipping, &every})
    controller->set_issue_skew(skew, skew == IssueSkew::none ? 0 : 3);
  for (ArrayController* controller : {&skipping, &every}) controller->enable_ops(all_enabled_ops());
  for (ArrayController* controller : {&skipping, &every}) ASSERT_TRUE(controller->load(0, words));
  CuArray& a = skipping.array();
  CuArray& b = every.array();
  for (unsigned l = 0; l < a.lanes(); ++l)
    for (unsigned address = 0; address < CMEM_BYTES; ++address) {
      const auto value = static_cast<uint8_t>(rng());
      a.set_cmem(l, address, value);
      b.set_cmem(l, address, value);
    }
  for (unsigned run = 0; run < RUNS; ++run) {
    // A few CUs change (none in one run of three): a CMEM byte, a
    // register, the flags and the mask; in one run of eight, up to 40 of
    // them, so that the CUs that run fill one, two or three blocks of the
    // trace runner's lanes.
    const unsigned changes = rng() % 8 == 0 ? static_cast<unsigned>(rng() % 41) : static_cast<unsigned>(rng() % 6 / 2);
    for (unsigned change = changes; change > 0; --change) {
      const auto lane = static_cast<unsigned>(rng() % a.lanes());
      const auto value = static_cast<uint8_t>(rng());
      switch (rng() % 4) {
        case 0:
        case 1: {
          const auto address = static_cast<unsigned>(rng() % CMEM_BYTES);
          a.set_cmem(lane, address, value);
          b.set_cmem(lane, address, value);
          break;
        }
        case 2:
          a.set_reg(lane, value % REGISTERS, value);
          b.set_reg(lane, value % REGISTERS, value);
          break;
        default: {
          const CuFlags flags{(value & 1u) != 0, (value & 2u) != 0, (value & 4u) != 0};
          a.set_flags(lane, flags);
          b.set_flags(lane, flags);
          a.set_mask(lane, (value & 8u) != 0);
          b.set_mask(lane, (value & 8u) != 0);
        }
      }
    }
    // The third program, which changes every CU, one run in ten.
    const unsigned entry = entries[rng() % 10 == 0 ? 2 : rng() % 2];
    const RunResult ra = skipping.run(entry), rb = every.run(entry);
    ASSERT_TRUE(ra.ok && rb.ok) << ra.error << rb.error;
    ASSERT_EQ(ra.cycles, rb.cycles);
    ASSERT_EQ(ra.instructions, rb.instructions);
    for (unsigned l = 0; l < a.lanes(); ++l) {
      ASSERT_EQ(a.flags(l), b.flags(l)) << "run " << run << ", lane " << l;
      ASSERT_EQ(a.mask(l), b.mask(l)) << "run " << run << ", lane " << l;
      for (unsigned r = 0; r < REGISTERS; ++r) ASSERT_EQ(a.reg(l, r), b.reg(l, r)) << "run " << run << ", r" << r;
      for (unsigned address = 0; address < CMEM_BYTES; ++address)
        ASSERT_EQ(a.cmem(l, address), b.cmem(l, address)) << "run " << run << ", lane " << l << ", " << address;
    }
    ASSERT_EQ(a.active_lanes(), b.active_lanes());
    // The lanes' activity, in all and per stage (the random instructions'
    // stages: each program changes stage many times).
    const auto expect_same = [&](const ArrayActivity& x, const ArrayActivity& y, const std::string& what) {
      EXPECT_EQ(x.lane_operations, y.lane_operations) << what;
      EXPECT_EQ(x.useful_operations, y.useful_operations) << what;
      EXPECT_EQ(x.cmem_reads, y.cmem_reads) << what;
      EXPECT_EQ(x.cmem_writes, y.cmem_writes) << what;
      EXPECT_EQ(x.neighbour_transfers, y.neighbour_transfers) << what;
    };
    expect_same(a.activity(), b.activity(), "run " + std::to_string(run));
    for (unsigned stage = 0; stage < STAGE_COUNT; ++stage)
      expect_same(skipping.activity().stage_lanes[stage], every.activity().stage_lanes[stage],
                  "run " + std::to_string(run) + ", stage " + std::to_string(stage));
    ASSERT_FALSE(::testing::Test::HasFailure()) << "run " << run;
  }
  EXPECT_EQ(skipping.activity().word_executions, every.activity().word_executions);
  EXPECT_EQ(skipping.activity().word_cycles, every.activity().word_cycles);
  EXPECT_EQ(skipping.activity().skew_cycles, every.activity().skew_cycles);
  EXPECT_EQ(skipping.activity().stage_cycles, every.activity().stage_cycles);
  EXPECT_EQ(skipping.activity().instruction_mix, every.activity().instruction_mix);
  EXPECT_EQ(skipping.activity().stage_instructions, every.activity().stage_instructions);
  EXPECT_EQ(skipping.activity().stage_mix, every.activity().stage_mix);
  unsigned stages_with_lane_work = 0;
  for (const ArrayActivity& stage : every.activity().stage_lanes) stages_with_lane_work += stage.useful_operations > 0;
  EXPECT_GE(stages_with_lane_work, 4u);
  // Both ways were taken: CUs skipped, and CUs run.
  EXPECT_GT(skipping.lanes_skipped(), skipping.lanes_run());
  EXPECT_GT(skipping.lanes_run(), 0u);
  EXPECT_EQ(every.lanes_skipped(), 0u);
}

TEST(ArrayController, SkippingIdleCusChangesNothing) {
  skipping_idle_cus_changes_nothing(IssueSkew::none);
}

TEST(ArrayController, SkippingIdleCusChangesNothingUnderRowSkew) {
  skipping_idle_cus_changes_nothing(IssueSkew::row);
}

// A grid of 12 CUs: the trace runner's block of 16 lanes is wider than the
// array.
TEST(ArrayController, SkippingIdleCusChangesNothingOnASmallGrid) {
  ArrayGeometry geometry = small_cmem_geometry();
  geometry.columns = 4;
  geometry.rows = 3;
  skipping_idle_cus_changes_nothing(IssueSkew::none, geometry);
}

// The same random flags, mask, registers and CMEM in the first `lanes`
// lanes of each of `arrays` (C and Z often both set).
void set_same_random_state(std::mt19937_64& rng, unsigned lanes, std::initializer_list<CuArray*> arrays) {
  for (unsigned l = 0; l < lanes; ++l) {
    const auto bits = rng();
    const CuFlags flags{(bits & 3u) != 0, (bits & 12u) != 0, (bits & 16u) != 0};
    for (CuArray* array : arrays) {
      array->set_flags(l, flags);
      array->set_mask(l, (bits & 32u) != 0);
    }
    for (unsigned r = 0; r < REGISTERS; ++r) {
      const auto value = static_cast<uint8_t>(rng());
      for (CuArray* array : arrays) array->set_reg(l, r, value);
    }
    for (unsigned a = 0; a < CMEM_BYTES; ++a) {
      const auto value = static_cast<uint8_t>(rng());
      for (CuArray* array : arrays) array->set_cmem(l, a, value);
    }
  }
}

// Runs `trace` on `lanes` lanes from a random state both ways, by
// execute() and by its compiled trace, and expects the same registers,
// flags, masks, CMEM and per-lane counts; returns the compiled trace's
// steps.
size_t expect_trace_runs_as_execute(std::mt19937_64& rng, unsigned lanes, const std::vector<Instruction>& trace,
                                    const std::string& where) {
  CuArray by_execute(small_cmem_geometry()), by_trace(small_cmem_geometry());
  for (CuArray* array : {&by_execute, &by_trace}) array->set_lane_count(lanes);
  set_same_random_state(rng, lanes, {&by_execute, &by_trace});
  // A few instructions executed on both first, so that the registers
  // are renamed when the trace starts (run_trace undoes it).
  for (unsigned i = 0; i < 4; ++i) {
    const Instruction& in = trace[rng() % trace.size()];
    for (CuArray* array : {&by_execute, &by_trace})
      EXPECT_EQ(array->execute(in, LoopVariables{}, 0), "") << format_instruction(in);
  }
  by_execute.count_per_lane(true);
  for (const Instruction& in : trace)
    EXPECT_EQ(by_execute.execute(in, LoopVariables{}, 0), "") << format_instruction(in);
  const CuArray::CompiledTrace compiled = by_trace.compile_trace(trace);
  by_trace.run_trace(compiled);
  for (unsigned l = 0; l < lanes; ++l) {
    EXPECT_EQ(by_trace.flags(l), by_execute.flags(l)) << where << ", lane " << l;
    EXPECT_EQ(by_trace.mask(l), by_execute.mask(l)) << where << ", lane " << l;
    for (unsigned r = 0; r < REGISTERS; ++r)
      EXPECT_EQ(by_trace.reg(l, r), by_execute.reg(l, r)) << where << ", lane " << l << ", r" << r;
    for (unsigned a = 0; a < CMEM_BYTES; ++a)
      EXPECT_EQ(by_trace.cmem(l, a), by_execute.cmem(l, a)) << where << ", lane " << l << ", address " << a;
  }
  EXPECT_EQ(by_trace.active_lanes(), by_execute.active_lanes()) << where;
  for (unsigned stage = 0; stage < STAGE_COUNT; ++stage) {
    EXPECT_EQ(by_trace.lane_useful(static_cast<Stage>(stage)), by_execute.lane_useful(static_cast<Stage>(stage)))
        << where << ", stage " << stage;
    EXPECT_EQ(by_trace.lane_stores(static_cast<Stage>(stage)), by_execute.lane_stores(static_cast<Stage>(stage)))
        << where << ", stage " << stage;
  }
  return compiled.steps.size();
}

// The trace runner (CuArray::compile_trace, run_trace) against execute():
// random traces of every lane instruction a trace may hold (their loop
// variables added to the addresses, as ArrayController::build_trace does),
// from random states in which C and Z are often both set (so that hi and ls
// differ from c and nc), leave every register, flag, mask and CMEM byte and
// every per-lane count of every stage as executing them one by one does;
// on the full grid, on 20 lanes (more than a block of 16, not a whole
// number of them) and on 16; with the registers renamed by instructions
// executed before the trace.
TEST(CuArray, ACompiledTraceRunsAsExecuteDoes) {
  constexpr unsigned TRACES = 300, LENGTH = 60;
  std::mt19937_64 rng(0x7ace);
  for (const unsigned lanes : {COLUMNS * ROWS, 20u, 16u}) {
    for (unsigned t = 0; t < TRACES; ++t) {
      std::vector<Instruction> trace;
      while (trace.size() < LENGTH) {
        RandomInstruction r = random_instruction(rng, REGISTERS, CMEM_BYTES);
        Instruction in = r.instruction;
        if (in.opcode == Opcode::op_nget || in.opcode == Opcode::op_nadd || in.opcode == Opcode::op_nadds ||
            in.opcode == Opcode::op_nadcs)
          continue;
        for (Operand* operand : {&in.d, &in.a, &in.b})
          if (operand->in_cmem && operand->loop != 0) {
            operand->value = static_cast<uint16_t>(operand->value + r.variables[operand->loop - 1]);
            operand->loop = 0;
          }
        trace.push_back(in);
      }
      const std::string where = std::to_string(lanes) + " lanes, trace " + std::to_string(t);
      expect_trace_runs_as_execute(rng, lanes, trace, where);
      ASSERT_FALSE(::testing::Test::HasFailure()) << where;
    }
  }
}

// The neighbours the compiler fuses into one step (FUSED_PAIRS in
// cu_array.cpp: add, adc, shl, shr, mov and or, into registers and CMEM,
// in twelve pairs): random traces of those instructions alone (about one
// neighbour in ten a pair), run as execute() runs them, in fewer steps
// than instructions.
TEST(CuArray, ACompiledTraceOfFusedPairsRunsAsExecuteDoes) {
  constexpr unsigned TRACES = 200, LENGTH = 40;
  std::mt19937_64 rng(0xf05e);
  const Opcode ops[] = {Opcode::op_add, Opcode::op_adc, Opcode::op_shl, Opcode::op_shr, Opcode::op_mov, Opcode::op_or};
  const auto operand = [&](bool in_cmem) {
    return in_cmem ? mem(static_cast<unsigned>(rng() % CMEM_BYTES)) : reg(static_cast<unsigned>(rng() % REGISTERS));
  };
  size_t steps = 0, instructions = 0;
  for (const unsigned lanes : {COLUMNS * ROWS, 20u}) {
    for (unsigned t = 0; t < TRACES; ++t) {
      std::vector<Instruction> trace;
      while (trace.size() < LENGTH) {
        const Opcode opcode = ops[rng() % std::size(ops)];
        const bool d_in_cmem = rng() % 3 == 0, a_in_cmem = !d_in_cmem && rng() % 3 == 0;
        const Instruction in = make(opcode, operand(d_in_cmem), operand(a_in_cmem), operand(false));
        const Decoded decoded = decode(encode(in));
        if (!decoded.error.empty() || !check_limits(decoded.instruction, REGISTERS, CMEM_BYTES).empty()) continue;
        trace.push_back(decoded.instruction);
      }
      const std::string where = std::to_string(lanes) + " lanes, trace " + std::to_string(t);
      steps += expect_trace_runs_as_execute(rng, lanes, trace, where);
      instructions += trace.size();
      ASSERT_FALSE(::testing::Test::HasFailure()) << where;
    }
  }
  EXPECT_LT(steps, instructions * 19 / 20) << "pairs were fused";
}

// Long runs of instructions between two mask changes: the runner counts
// each lane's operations and CMEM stores in a byte while their sums since
// the last widening fit one (255), widening them into the lane's counts
// when they would not. Runs of 100, 100 and 56 (a sum of 256, one past a
// byte), of 300 (more than a byte in one run), of 1, 254 and 2, each
// ended by an `mset` or an `mmov` (which leaves some lanes out), every
// instruction a store into CMEM.
TEST(CuArray, ACompiledTraceCountsRunsLongerThanAByteAsExecuteDoes) {
  std::mt19937_64 rng(0xb17e);
  for (const unsigned lanes : {COLUMNS * ROWS, 20u}) {
    std::vector<Instruction> trace;
    unsigned change = 0;
    for (const unsigned run : {100u, 100u, 56u, 300u, 1u, 254u, 2u}) {
      for (unsigned i = 0; i < run; ++i)
        trace.push_back(make(Opcode::op_mov, mem(static_cast<unsigned>(rng() % CMEM_BYTES)),
                             reg(static_cast<unsigned>(rng() % REGISTERS)), reg(0)));
      Instruction mask = make(++change % 2 == 0 ? Opcode::op_mmov : Opcode::op_mset);
      if (mask.opcode == Opcode::op_mmov) mask.a.value = static_cast<uint16_t>(Cond::s);
      trace.push_back(mask);
    }
    const std::string where = std::to_string(lanes) + " lanes";
    expect_trace_runs_as_execute(rng, lanes, trace, where);
  }
}

// A trace compiled for one geometry is refused by an array of another,
// whose rows its offsets do not name.
TEST(CuArray, ATraceCompiledForAnotherGeometryIsRefused) {
  ArrayGeometry other = small_cmem_geometry();
  other.cmem_bytes = CMEM_BYTES * 2;
  const CuArray compiler(small_cmem_geometry());
  CuArray runner(other);
  const std::vector<Instruction> trace{make(Opcode::op_add, reg(0), reg(1), mem(3))};
  const CuArray::CompiledTrace compiled = compiler.compile_trace(trace);
  EXPECT_THROW(runner.run_trace(compiled), std::logic_error);
  CuArray same(small_cmem_geometry());
  same.set_reg(0, 1, 5);
  same.set_cmem(0, 3, 7);
  same.run_trace(compiled);
  EXPECT_EQ(same.reg(0, 0), 12);
}

// A trace run on a window of 16 lanes (run_trace's first_lane, lanes):
// those lanes end as executing the trace on every lane leaves them, with
// its counts; every other lane's registers, flags, mask and CMEM are as
// before, its counts 0. Windows that are not (not at a multiple of 16, or
// past the lanes) are refused.
TEST(CuArray, ACompiledTraceRunOnAWindowOfLanesLeavesTheOthers) {
  std::mt19937_64 rng(0x3d0);
  const std::vector<Instruction> trace{
      make(Opcode::op_add, reg(0), reg(1), mem(3)), make(Opcode::op_mset),
      make(Opcode::op_adc, mem(5), reg(0), reg(2)), make(Opcode::op_shl, reg(3), reg(0), reg(0)),
      make(Opcode::op_mov, mem(9), reg(3), reg(0)), make(Opcode::op_sub, reg(4), mem(5), reg(1)),
      make(Opcode::op_or, mem(11), reg(4), mem(3))};
  CuArray by_execute(small_cmem_geometry()), by_window(small_cmem_geometry());
  const unsigned lanes = by_window.lanes(), first = 16, window = 16;
  ASSERT_GE(lanes, first + window);
  set_same_random_state(rng, lanes, {&by_execute, &by_window});
  const CuArray before = by_window;
  by_execute.count_per_lane(true);
  for (const Instruction& in : trace)
    ASSERT_EQ(by_execute.execute(in, LoopVariables{}, 0), "") << format_instruction(in);
  by_window.run_trace(by_window.compile_trace(trace), first, window);
  for (unsigned l = 0; l < lanes; ++l) {
    const CuArray& expected = l >= first && l < first + window ? by_execute : before;
    EXPECT_EQ(by_window.flags(l), expected.flags(l)) << "lane " << l;
    EXPECT_EQ(by_window.mask(l), expected.mask(l)) << "lane " << l;
    for (unsigned r = 0; r < REGISTERS; ++r) EXPECT_EQ(by_window.reg(l, r), expected.reg(l, r)) << "lane " << l;
    for (unsigned a = 0; a < CMEM_BYTES; ++a) EXPECT_EQ(by_window.cmem(l, a), expected.cmem(l, a)) << "lane " << l;
    for (unsigned stage = 0; stage < STAGE_COUNT; ++stage) {
      const auto s = static_cast<Stage>(stage);
      const bool in_window = l >= first && l < first + window;
      EXPECT_EQ(by_window.lane_useful(s)[l], in_window ? by_execute.lane_useful(s)[l] : 0u) << "lane " << l;
      EXPECT_EQ(by_window.lane_stores(s)[l], in_window ? by_execute.lane_stores(s)[l] : 0u) << "lane " << l;
    }
  }
  const CuArray::CompiledTrace compiled = by_window.compile_trace(trace);
  EXPECT_THROW(by_window.run_trace(compiled, 8, 16), std::logic_error);
  EXPECT_THROW(by_window.run_trace(compiled, lanes - 16, 32), std::logic_error);
  EXPECT_THROW(by_window.run_trace(compiled, lanes + 16, 16), std::logic_error);
}

// A program written over another at the same entry is planned and
// recorded afresh: the CUs are not skipped on the old program's record.
TEST(ArrayController, SkippingIdleCusForgetsAProgramWrittenOver) {
  const auto program = [](Opcode opcode) {
    return std::vector<uint64_t>{encode(make(Opcode::op_mset)), encode(make(Opcode::op_mov, reg(0), mem(0))),
                                 encode(make(opcode, mem(8), reg(0), mem(1))), encode(make(Opcode::op_halt))};
  };
  ArrayController skipping{small_cmem_geometry(), CycleTable::defaults(), PROGRAM_WORDS, MAX_CYCLES};
  skipping.skip_idle_cus(true);
  for (unsigned l = 0; l < skipping.array().lanes(); ++l) {
    skipping.array().set_cmem(l, 0, static_cast<uint8_t>(l));
    skipping.array().set_cmem(l, 1, 3);
  }
  ASSERT_TRUE(skipping.load(0, program(Opcode::op_add)));
  ASSERT_TRUE(skipping.run(0).ok);
  ASSERT_TRUE(skipping.run(0).ok);  // every CU skipped
  EXPECT_EQ(skipping.lanes_skipped(), skipping.array().lanes());
  ASSERT_TRUE(skipping.load(0, program(Opcode::op_sub)));
  ASSERT_TRUE(skipping.run(0).ok);
  for (unsigned l = 0; l < skipping.array().lanes(); ++l)
    EXPECT_EQ(skipping.array().cmem(l, 8), static_cast<uint8_t>(l - 3)) << "lane " << l;
}

// A CU that ran because its inputs changed is skipped at the next run
// when they hold again: its record of inputs and of the CMEM it may write
// was brought up to date (the run's lanes are moved by 16-lane chunks on
// 96 CUs, a byte at a time on 12). Lanes in three chunks.
void run_lanes_are_recorded(const ArrayGeometry& geometry, const std::vector<unsigned>& changed) {
  ArrayController skipping{geometry, CycleTable::defaults(), PROGRAM_WORDS, MAX_CYCLES};
  skipping.skip_idle_cus(true);
  CuArray& cus = skipping.array();
  for (unsigned l = 0; l < cus.lanes(); ++l) {
    cus.set_cmem(l, 0, static_cast<uint8_t>(l));
    cus.set_cmem(l, 1, 3);
  }
  ASSERT_TRUE(skipping.load(0, {encode(make(Opcode::op_mset)), encode(make(Opcode::op_mov, reg(0), mem(0))),
                                encode(make(Opcode::op_add, mem(8), reg(0), mem(1))), encode(make(Opcode::op_halt))}));
  ASSERT_TRUE(skipping.run(0).ok);  // recorded
  const uint64_t recorded = skipping.lanes_run();
  ASSERT_TRUE(skipping.run(0).ok);  // every CU skipped
  ASSERT_EQ(skipping.lanes_run(), recorded);
  ASSERT_EQ(skipping.lanes_skipped(), cus.lanes());
  for (const unsigned l : changed) cus.set_cmem(l, 0, static_cast<uint8_t>(100 + l));
  ASSERT_TRUE(skipping.run(0).ok);
  EXPECT_EQ(skipping.lanes_run(), recorded + changed.size());
  for (unsigned l = 0; l < cus.lanes(); ++l) {
    const bool was_changed = std::find(changed.begin(), changed.end(), l) != changed.end();
    EXPECT_EQ(cus.cmem(l, 8), static_cast<uint8_t>((was_changed ? 100 + l : l) + 3)) << "lane " << l;
  }
  ASSERT_TRUE(skipping.run(0).ok);
  EXPECT_EQ(skipping.lanes_run(), recorded + changed.size()) << "the changed CUs ran again";
  EXPECT_EQ(skipping.lanes_skipped(), 3 * cus.lanes() - changed.size());
}

TEST(ArrayController, ACuThatRanIsSkippedWhenItsInputsHoldAgain) {
  ASSERT_EQ(small_cmem_geometry().lanes(), 96u);
  run_lanes_are_recorded(small_cmem_geometry(), {3, 17, 18, 40});
  ArrayGeometry twelve = small_cmem_geometry();
  twelve.columns = 4;
  twelve.rows = 3;
  run_lanes_are_recorded(twelve, {1, 5, 11});
}

}  // namespace
}  // namespace tessera::ap
