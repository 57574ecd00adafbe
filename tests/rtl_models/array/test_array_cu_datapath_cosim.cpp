// Co-simulation: the array's C++ core (tlm/array/core/cu_array.h) against the
// Verilated rtl_models/array/cu_datapath.sv, one RTL instance per lane of a
// 4 x 3 grid (corners, edges and inside lanes alike), in lock step. Every
// instruction runs on the C++ array; each RTL CU gets its lane's CMEM bytes
// at the operand addresses and its neighbours' bytes from the C++ state
// before the instruction, and after it every register, C, Z, S, M and the
// CMEM write (bytes and enables, against the C++ CMEM's change) must agree.
//
// The random stream's seed is printed; TESSERA_CU_COSIM_SEED replays another.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "array/core/cu_array.h"
#include "array/datapath/cu_alu.h"
#include "array/isa/ap_isa.h"
#include "cosim/random_instruction.h"
#include "cu_datapath_adapter.h"

namespace tessera::ap {
namespace {

constexpr uint64_t RANDOM_INSTRUCTIONS = 1'000'000;
constexpr unsigned COLUMNS = 4, ROWS = 3;
// Small, so that random operands alias and stores land where later loads read.
constexpr unsigned CMEM_BYTES = 64;
constexpr uint64_t DEFAULT_SEED = 0xc0de5eed;
constexpr uint8_t ABSENT_NEIGHBOUR_JUNK = 0xa5;

ArrayGeometry cosim_geometry() {
  ArrayGeometry geometry;
  geometry.columns = COLUMNS;
  geometry.rows = ROWS;
  geometry.registers = CuDatapathRtl::REGISTERS;
  geometry.cmem_bytes = CMEM_BYTES;
  return geometry;
}

bool uses_d(const Instruction& in) {
  const OperandPattern p = op_info(in.opcode).operands;
  return p == OperandPattern::dab || p == OperandPattern::da || p == OperandPattern::d || p == OperandPattern::dna;
}
bool is_mul(Opcode opcode) {
  return opcode == Opcode::op_mul || opcode == Opcode::op_mulm;
}

// The C++ array and one RTL CU per lane, run in lock step.
class LockStep {
 public:
  LockStep() : m_array(cosim_geometry()) {
    for (unsigned lane = 0; lane < m_array.lanes(); ++lane) m_rtl.push_back(std::make_unique<CuDatapathRtl>());
  }

  CuArray& array() { return m_array; }
  const CuDatapathRtl& rtl(unsigned lane) const { return *m_rtl[lane]; }
  unsigned lanes() const { return m_array.lanes(); }
  uint64_t instructions() const { return m_instructions; }

  // Runs `in` on both sides; returns the first difference, or "".
  std::string step(const Instruction& in, const LoopVariables& variables = {}, unsigned active_loops = 0) {
    ++m_instructions;
    const auto resolve = [&](const Operand& operand) {
      return operand.in_cmem ? static_cast<int>(operand.value) + (operand.loop != 0 ? variables[operand.loop - 1] : 0)
                             : -1;
    };
    const int d_address = uses_d(in) ? resolve(in.d) : -1;
    const unsigned d_width = operand_width(in.opcode, 'd');
    const auto cmem_or_zero = [&](unsigned lane, int address) -> uint8_t {
      return address >= 0 && address < static_cast<int>(CMEM_BYTES) ? m_array.cmem(lane, address) : 0;
    };

    // What the array hands each CU, read before the instruction changes it.
    const unsigned n = lanes();
    std::vector<CuOperandBytes> operands(n);
    std::vector<CuNeighbours> neighbours(n);
    std::vector<std::array<uint8_t, 3>> d_before(n);
    std::vector<bool> mask_before(n);
    for (unsigned lane = 0; lane < n; ++lane) {
      const CuLaneInputs inputs = cu_lane_inputs(m_array, lane, in, variables);
      operands[lane] = inputs.operands;
      neighbours[lane] = inputs.neighbours;
      // Beyond the edge the byte is junk: the CU must make the 0 itself.
      for (unsigned k = 0; k < 4; ++k)
        if (!neighbours[lane].present[k]) neighbours[lane].value[k] = ABSENT_NEIGHBOUR_JUNK;
      for (unsigned i = 0; i < 3; ++i) d_before[lane][i] = cmem_or_zero(lane, d_address + static_cast<int>(i));
      mask_before[lane] = m_array.mask(lane);
    }

    const std::string error = m_array.execute(in, variables, active_loops);
    if (!error.empty()) return "the C++ array refused it: " + error;

    std::ostringstream why;
    for (unsigned lane = 0; lane < n && why.tellp() == 0; ++lane) {
      CuDatapathRtl& cu = *m_rtl[lane];
      const CuCmemWrite write = cu.execute(in, operands[lane], neighbours[lane]);
      why << "lane " << lane << " (column " << lane % COLUMNS << ", row " << lane / COLUMNS << "): ";
      const std::streampos clean = why.tellp();
      const unsigned cycles = is_mul(in.opcode) ? CuDatapathRtl::MUL_CYCLES : CuDatapathRtl::ALU_CYCLES;
      if (cu.last_cycles() != cycles) why << "rtl took " << cu.last_cycles() << " cycles, not " << cycles << "; ";
      for (unsigned r = 0; r < CuDatapathRtl::REGISTERS; ++r)
        if (cu.reg(r) != m_array.reg(lane, r))
          why << "r" << r << " rtl " << unsigned{cu.reg(r)} << " c++ " << unsigned{m_array.reg(lane, r)} << "; ";
      const CuFlags rf = cu.flags(), cf = m_array.flags(lane);
      if (!(rf == cf)) why << "flags CZS rtl " << rf.c << rf.z << rf.s << " c++ " << cf.c << cf.z << cf.s << "; ";
      if (cu.mask() != m_array.mask(lane)) why << "M rtl " << cu.mask() << " c++ " << m_array.mask(lane) << "; ";
      for (unsigned i = 0; i < 3; ++i) {
        const bool stores = d_address >= 0 && i < d_width && mask_before[lane];
        const uint8_t after = cmem_or_zero(lane, d_address + static_cast<int>(i));
        if (write.enable[i] != stores)
          why << "CMEM write enable " << i << " rtl " << write.enable[i] << " expected " << stores << "; ";
        else if (stores && write.data[i] != after)
          why << "CMEM byte d+" << i << " rtl " << unsigned{write.data[i]} << " c++ " << unsigned{after} << "; ";
        else if (!stores && d_address >= 0 && after != d_before[lane][i])
          why << "C++ CMEM byte d+" << i << " changed without a store; ";
      }
      if (why.tellp() == clean) why.str("");
    }
    if (why.tellp() == 0) return {};
    return "instruction " + std::to_string(m_instructions) + " '" + format_instruction(in) + "' (i0..i2 " +
           std::to_string(variables[0]) + " " + std::to_string(variables[1]) + " " + std::to_string(variables[2]) +
           ", " + std::to_string(active_loops) + " loops): " + why.str();
  }

 private:
  CuArray m_array;
  std::vector<std::unique_ptr<CuDatapathRtl>> m_rtl;
  uint64_t m_instructions = 0;
};

uint64_t seed_from_environment() {
  const char* text = std::getenv("TESSERA_CU_COSIM_SEED");
  return text != nullptr ? std::strtoull(text, nullptr, 0) : DEFAULT_SEED;
}

TEST(CuDatapathCosim, RandomInstructionsMatchTheCoreInEveryLane) {
  const uint64_t seed = seed_from_environment();
  std::printf("cu_datapath cosim: seed 0x%llx (TESSERA_CU_COSIM_SEED to replay another)\n",
              static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  LockStep lock_step;
  CuArray& array = lock_step.array();
  const auto scramble_cmem = [&](unsigned bytes) {
    for (unsigned i = 0; i < bytes; ++i)
      array.set_cmem(static_cast<unsigned>(rng() % array.lanes()), static_cast<unsigned>(rng() % CMEM_BYTES),
                     static_cast<uint8_t>(rng()));
  };
  scramble_cmem(CMEM_BYTES * array.lanes() * 4);
  std::array<uint64_t, OPCODE_COUNT> mix{};
  uint64_t masked_lanes = 0;
  for (uint64_t i = 0; i < RANDOM_INSTRUCTIONS; ++i) {
    // CMEM is the array's, not the CU's: refresh some of it now and then so
    // that stores do not converge its contents.
    if (i % 256 == 0) scramble_cmem(16);
    const RandomInstruction r = random_instruction(rng, CuDatapathRtl::REGISTERS, CMEM_BYTES);
    ++mix[static_cast<unsigned>(r.instruction.opcode)];
    masked_lanes += array.lanes() - array.active_lanes();
    const std::string why = lock_step.step(r.instruction, r.variables, r.active_loops);
    if (!why.empty()) {
      ADD_FAILURE() << "seed 0x" << std::hex << seed << std::dec << ", first mismatch: " << why;
      break;
    }
  }
  std::printf(
      "cu_datapath cosim: %llu random instructions x %u lanes, %.1f %% lane-instructions masked\n",
      static_cast<unsigned long long>(lock_step.instructions()), lock_step.lanes(),
      100.0 * static_cast<double>(masked_lanes) / static_cast<double>(lock_step.instructions() * lock_step.lanes()));
  EXPECT_EQ(lock_step.instructions(), RANDOM_INSTRUCTIONS);
  for (Opcode opcode : LANE_OPCODES)
    EXPECT_GT(mix[static_cast<unsigned>(opcode)], RANDOM_INSTRUCTIONS / 50) << op_info(opcode).mnemonic;
}

// The lane `direction` of `lane` from the grid's coordinates (row 0 at the
// top), or -1 beyond the grid's edge.
int neighbour_of(unsigned lane, Direction direction) {
  const unsigned column = lane % COLUMNS, row = lane / COLUMNS;
  if (direction == Direction::left && column > 0) return static_cast<int>(lane) - 1;
  if (direction == Direction::right && column < COLUMNS - 1) return static_cast<int>(lane) + 1;
  if (direction == Direction::up && row > 0) return static_cast<int>(lane - COLUMNS);
  if (direction == Direction::down && row < ROWS - 1) return static_cast<int>(lane + COLUMNS);
  return -1;
}

// The directed cases: each runs through the lock step (the RTL agrees with
// the core in every lane) and then checks the values worked out by hand.
class CuDatapathDirected : public ::testing::Test {
 protected:
  void run(const Instruction& in, const LoopVariables& variables = {}, unsigned active_loops = 0) {
    const std::string why = m_lock_step.step(in, variables, active_loops);
    ASSERT_TRUE(why.empty()) << why;
  }
  // Loads `value` into register `r` of every lane through CMEM scratch byte 63.
  void load(unsigned r, uint8_t value) {
    for (unsigned lane = 0; lane < lanes(); ++lane) array().set_cmem(lane, SCRATCH, value);
    run(make(Opcode::op_mov, reg(r), mem(SCRATCH)));
  }
  // Loads a big-endian value of `bytes` bytes into r, r + 1, ...
  void load_wide(unsigned r, uint32_t value, unsigned bytes) {
    for (unsigned i = 0; i < bytes; ++i) load(r + i, static_cast<uint8_t>(value >> (8 * (bytes - 1 - i))));
  }
  uint32_t wide(unsigned lane, unsigned r, unsigned bytes) const {
    uint32_t value = 0;
    for (unsigned i = 0; i < bytes; ++i) value = value << 8 | m_lock_step.rtl(lane).reg(r + i);
    return value;
  }
  CuFlags rtl_flags(unsigned lane = 0) const { return m_lock_step.rtl(lane).flags(); }
  CuArray& array() { return m_lock_step.array(); }
  unsigned lanes() const { return m_lock_step.lanes(); }
  const CuDatapathRtl& rtl(unsigned lane) const { return m_lock_step.rtl(lane); }

  static constexpr unsigned SCRATCH = CMEM_BYTES - 1;
  LockStep m_lock_step;
};

CuFlags czs(bool c, bool z, bool s) {
  return {c, z, s};
}

TEST_F(CuDatapathDirected, CarriesRunThrough16And24BitAddAndSubtractChains) {
  // 0x12ffff + 0x000001 = 0x130000: the carry crosses two bytes.
  load_wide(0, 0x12ffff, 3);
  load_wide(3, 0x000001, 3);
  run(make(Opcode::op_add, reg(2), reg(2), reg(5)));
  run(make(Opcode::op_adc, reg(1), reg(1), reg(4)));
  run(make(Opcode::op_adc, reg(0), reg(0), reg(3)));
  EXPECT_EQ(wide(0, 0, 3), 0x130000u);
  EXPECT_EQ(rtl_flags(), czs(false, false, false));
  // 0xffffff + 1 wraps to 0 with a carry out; Z is the top byte's.
  load_wide(0, 0xffffff, 3);
  run(make(Opcode::op_add, reg(2), reg(2), reg(5)));
  run(make(Opcode::op_adc, reg(1), reg(1), reg(4)));
  run(make(Opcode::op_adc, reg(0), reg(0), reg(3)));
  EXPECT_EQ(wide(0, 0, 3), 0u);
  EXPECT_EQ(rtl_flags(), czs(true, true, false));
  // 16 bits: 0x7fff + 0x0001 = 0x8000, S from the high byte.
  load_wide(0, 0x7fff, 2);
  load_wide(2, 0x0001, 2);
  run(make(Opcode::op_add, reg(1), reg(1), reg(3)));
  run(make(Opcode::op_adc, reg(0), reg(0), reg(2)));
  EXPECT_EQ(wide(0, 0, 2), 0x8000u);
  EXPECT_EQ(rtl_flags(), czs(false, false, true));
  // 0x100000 - 1 = 0x0fffff: the borrow crosses two bytes, none leaves.
  load_wide(0, 0x100000, 3);
  load_wide(3, 0x000001, 3);
  run(make(Opcode::op_sub, reg(2), reg(2), reg(5)));
  run(make(Opcode::op_sbc, reg(1), reg(1), reg(4)));
  run(make(Opcode::op_sbc, reg(0), reg(0), reg(3)));
  EXPECT_EQ(wide(0, 0, 3), 0x0fffffu);
  EXPECT_EQ(rtl_flags(), czs(true, false, false));
  // 0 - 1 = 0xffffff with a borrow out (C clear).
  load_wide(0, 0, 3);
  run(make(Opcode::op_sub, reg(2), reg(2), reg(5)));
  run(make(Opcode::op_sbc, reg(1), reg(1), reg(4)));
  run(make(Opcode::op_sbc, reg(0), reg(0), reg(3)));
  EXPECT_EQ(wide(0, 0, 3), 0xffffffu);
  EXPECT_EQ(rtl_flags(), czs(false, false, true));
  // 16 bits in CMEM, stored: 0x01f0 + 0x0020 = 0x0210 at [8..9].
  for (unsigned lane = 0; lane < lanes(); ++lane) {
    array().set_cmem(lane, 4, 0x01);
    array().set_cmem(lane, 5, 0xf0);
    array().set_cmem(lane, 6, 0x00);
    array().set_cmem(lane, 7, 0x20);
  }
  run(make(Opcode::op_add, mem(9), mem(5), mem(7)));
  run(make(Opcode::op_adc, mem(8), mem(4), mem(6)));
  for (unsigned lane = 0; lane < lanes(); ++lane) {
    EXPECT_EQ(array().cmem(lane, 8), 0x02);
    EXPECT_EQ(array().cmem(lane, 9), 0x10);
  }
}

TEST_F(CuDatapathDirected, SixteenBitComparesSetCarryForUnsignedGreaterOrEqual) {
  struct Case {
    uint16_t a, b;
    CuFlags after;  // after cmp low, cmpc high
  };
  const std::array<Case, 6> cases{{
      {0x1234, 0x1235, czs(false, false, true)},  // low borrows: 0x12 - 0x12 - 1 = 0xff
      {0x1235, 0x1234, czs(true, true, false)},   // high 0x12 - 0x12 = 0
      {0x1234, 0x1234, czs(true, true, false)},   // equal
      {0x0100, 0x00ff, czs(true, true, false)},   // borrow from the low byte: 1 - 0 - 1 = 0
      {0x00ff, 0x0100, czs(false, false, true)},  // 0 - 1: borrow out
      {0x8000, 0x7fff, czs(true, true, false)},   // unsigned, not signed
  }};
  for (const Case& c : cases) {
    load_wide(0, c.a, 2);
    load_wide(2, c.b, 2);
    run(make(Opcode::op_cmp, {}, reg(1), reg(3)));
    run(make(Opcode::op_cmpc, {}, reg(0), reg(2)));
    EXPECT_EQ(rtl_flags(), c.after) << std::hex << c.a << " vs " << c.b;
    EXPECT_EQ(wide(0, 0, 2), c.a) << "compares write nothing";
  }
}

TEST_F(CuDatapathDirected, EveryShiftAndRotateIncludingMultiByteThroughCarry) {
  struct Case {
    Opcode opcode;
    uint8_t a;
    bool carry_in;
    uint8_t result;
    bool carry_out;
  };
  const std::array<Case, 10> cases{{
      {Opcode::op_shl, 0x81, true, 0x02, true},
      {Opcode::op_shl, 0x40, false, 0x80, false},
      {Opcode::op_shr, 0x81, true, 0x40, true},
      {Opcode::op_shr, 0x02, false, 0x01, false},
      {Opcode::op_asr, 0x81, false, 0xc0, true},
      {Opcode::op_asr, 0x7e, true, 0x3f, false},
      {Opcode::op_rol, 0x81, true, 0x03, true},
      {Opcode::op_rol, 0x40, false, 0x80, false},
      {Opcode::op_ror, 0x81, true, 0xc0, true},
      {Opcode::op_ror, 0x02, false, 0x01, false},
  }};
  for (const Case& c : cases) {
    // C from a shift of a known byte: shl 0x80 sets it, shl 0 clears it.
    load(1, c.carry_in ? 0x80 : 0x00);
    run(make(Opcode::op_shl, reg(7), reg(1)));
    load(0, c.a);
    run(make(c.opcode, reg(2), reg(0)));
    EXPECT_EQ(rtl(0).reg(2), c.result) << op_info(c.opcode).mnemonic << " " << unsigned{c.a};
    EXPECT_EQ(rtl_flags().c, c.carry_out) << op_info(c.opcode).mnemonic << " " << unsigned{c.a};
  }
  // 24-bit left shift, low byte first: 0x800001 << 1 = 0x000002, C = 1.
  load_wide(0, 0x800001, 3);
  run(make(Opcode::op_shl, reg(2), reg(2)));
  run(make(Opcode::op_rol, reg(1), reg(1)));
  run(make(Opcode::op_rol, reg(0), reg(0)));
  EXPECT_EQ(wide(0, 0, 3), 0x000002u);
  EXPECT_TRUE(rtl_flags().c);
  // 16-bit logical right shift, high byte first: 0x8181 >> 1 = 0x40c0, C = 1.
  load_wide(0, 0x8181, 2);
  run(make(Opcode::op_shr, reg(0), reg(0)));
  run(make(Opcode::op_ror, reg(1), reg(1)));
  EXPECT_EQ(wide(0, 0, 2), 0x40c0u);
  EXPECT_TRUE(rtl_flags().c);
  // 16-bit arithmetic right shift: 0x8102 >> 1 = 0xc081, C = 0.
  load_wide(0, 0x8102, 2);
  run(make(Opcode::op_asr, reg(0), reg(0)));
  run(make(Opcode::op_ror, reg(1), reg(1)));
  EXPECT_EQ(wide(0, 0, 2), 0xc081u);
  EXPECT_FALSE(rtl_flags().c);
  // The same shift in CMEM, in place.
  for (unsigned lane = 0; lane < lanes(); ++lane) {
    array().set_cmem(lane, 10, 0x81);
    array().set_cmem(lane, 11, 0x02);
  }
  run(make(Opcode::op_asr, mem(10), mem(10)));
  run(make(Opcode::op_ror, mem(11), mem(11)));
  EXPECT_EQ(array().cmem(5, 10), 0xc0);
  EXPECT_EQ(array().cmem(5, 11), 0x81);
}

// The six flag combinations a result can have (Z and S never both: a zero
// byte has bit 7 clear), all from one shl of a per-lane byte: lane l gets
// case l % 6. HOLDS gives each condition's truth per case, written from the
// condition table of ap_cond.def.
struct FlagCase {
  uint8_t shifted;  // shl of this byte sets the flags below
  CuFlags flags;
};
constexpr std::array<FlagCase, 6> FLAG_CASES{{
    {0x01, {false, false, false}},  // 0x02
    {0x40, {false, false, true}},   // 0x80
    {0x81, {true, false, false}},   // 0x02, bit 7 out
    {0xc0, {true, false, true}},    // 0x80, bit 7 out
    {0x80, {true, true, false}},    // 0x00, bit 7 out
    {0x00, {false, true, false}},   // 0x00
}};
// HOLDS[cond][case], conditions in code order c nc z nz s ns hi ls.
constexpr std::array<std::array<bool, 6>, 8> HOLDS{{
    {false, false, true, true, true, false},   // c
    {true, true, false, false, false, true},   // nc
    {false, false, false, false, true, true},  // z
    {true, true, true, true, false, false},    // nz
    {false, true, false, true, false, false},  // s
    {true, false, true, false, true, true},    // ns
    {false, false, true, true, false, false},  // hi: C and not Z
    {true, true, false, false, true, true},    // ls: not C, or Z
}};

TEST_F(CuDatapathDirected, MaskInstructionsWithEveryCondition) {
  for (unsigned lane = 0; lane < lanes(); ++lane) array().set_cmem(lane, 0, FLAG_CASES[lane % 6].shifted);
  run(make(Opcode::op_shl, reg(0), mem(0)));
  for (unsigned lane = 0; lane < lanes(); ++lane) ASSERT_EQ(rtl_flags(lane), FLAG_CASES[lane % 6].flags) << lane;
  const auto expect_mask = [&](const std::string& what, auto expected) {
    for (unsigned lane = 0; lane < lanes(); ++lane) EXPECT_EQ(rtl(lane).mask(), expected(lane % 6)) << what << lane;
  };
  run(make(Opcode::op_mclr));
  expect_mask("mclr, lane ", [](unsigned) { return false; });
  run(make(Opcode::op_mset));
  expect_mask("mset, lane ", [](unsigned) { return true; });
  for (unsigned x = 0; x < COND_COUNT; ++x) {
    const auto cx = static_cast<Cond>(x);
    const std::string name(cond_name(cx));
    run(make_cond(Opcode::op_mmov, cx));
    expect_mask("mmov " + name + ", lane ", [&](unsigned c) { return HOLDS[x][c]; });
    for (unsigned y = 0; y < COND_COUNT; ++y) {
      const auto cy = static_cast<Cond>(y);
      const std::string both = name + " then " + std::string(cond_name(cy)) + ", lane ";
      run(make_cond(Opcode::op_mmov, cx));
      run(make_cond(Opcode::op_mand, cy));
      expect_mask("mand " + both, [&](unsigned c) { return HOLDS[x][c] && HOLDS[y][c]; });
      run(make_cond(Opcode::op_mmov, cx));
      run(make_cond(Opcode::op_mor, cy));
      expect_mask("mor " + both, [&](unsigned c) { return HOLDS[x][c] || HOLDS[y][c]; });
    }
  }
  // The mask instructions leave the flags alone.
  for (unsigned lane = 0; lane < lanes(); ++lane) EXPECT_EQ(rtl_flags(lane), FLAG_CASES[lane % 6].flags) << lane;
}

TEST_F(CuDatapathDirected, StoresLandOnlyWhereTheMaskIsSetRegistersAlways) {
  // M set in the lanes of cases 2, 3, 4 (C set).
  for (unsigned lane = 0; lane < lanes(); ++lane) array().set_cmem(lane, 0, FLAG_CASES[lane % 6].shifted);
  run(make(Opcode::op_shl, reg(0), mem(0)));
  run(make_cond(Opcode::op_mmov, Cond::c));
  for (unsigned lane = 0; lane < lanes(); ++lane) {
    for (unsigned address = 10; address < 20; ++address) array().set_cmem(lane, address, 0xee);
    array().set_cmem(lane, 1, static_cast<uint8_t>(lane));
  }
  load(1, 0x21);
  load(2, 0x10);
  run(make(Opcode::op_mov, mem(10), reg(1)));
  run(make(Opcode::op_add, mem(11), reg(1), reg(2)));
  run(make(Opcode::op_getm, mem(12)));
  run(make_nget(mem(13), Direction::left, reg(1)));
  for (unsigned lane = 0; lane < lanes(); ++lane) {
    array().set_cmem(lane, 20, 0x01);
    array().set_cmem(lane, 21, 0x02);
    array().set_cmem(lane, 22, 0x03);
  }
  run(make(Opcode::op_mulm, mem(14), mem(20), mem(22)));
  // A load into a register happens in every lane, masked or not.
  run(make(Opcode::op_mov, reg(6), mem(1)));
  run(make(Opcode::op_getm, reg(7)));
  for (unsigned lane = 0; lane < lanes(); ++lane) {
    const unsigned c = lane % 6;
    const bool stores = c == 2 || c == 3 || c == 4;
    const auto expect = [&](unsigned address, uint8_t value) {
      EXPECT_EQ(array().cmem(lane, address), stores ? value : 0xee) << "lane " << lane << " address " << address;
    };
    expect(10, 0x21);
    expect(11, 0x31);
    expect(12, 0xff);
    expect(13, lane % COLUMNS == 0 ? 0x00 : 0x21);
    expect(14, 0x00);  // 0x0102 x 3 = 0x000306
    expect(15, 0x03);
    expect(16, 0x06);
    expect(17, 0xee);
    EXPECT_EQ(rtl(lane).reg(6), lane) << lane;
    EXPECT_EQ(rtl(lane).reg(7), stores ? 0xff : 0x00) << lane;
  }
}

TEST_F(CuDatapathDirected, MultiplyCornerValuesInRegistersAndCmem) {
  struct Case {
    int16_t a;
    int8_t b;
    uint32_t product;  // 24-bit two's complement, by hand
  };
  const std::array<Case, 14> cases{{
      {-32768, -128, 0x400000},  // 4194304, the largest product
      {-32768, 127, 0xc08000},   // -4161536
      {32767, -128, 0xc00080},   // -4194176
      {32767, 127, 0x3f7f81},    // 4161409
      {0, -128, 0x000000},
      {-32768, 0, 0x000000},
      {1, -128, 0xffff80},
      {1, 127, 0x00007f},
      {-1, -1, 0x000001},
      {-1, 1, 0xffffff},
      {-32768, -1, 0x008000},
      {127, -128, 0xffc080},  // -16256
      {127, 127, 0x003f01},   // 16129
      {-1, 127, 0xffff81},
  }};
  for (const Case& c : cases) {
    const auto a = static_cast<uint16_t>(c.a);
    const auto b = static_cast<uint8_t>(c.b);
    const CuFlags flags = czs(false, c.product == 0, (c.product & 0x800000u) != 0);
    load_wide(3, a, 2);
    load(5, b);
    run(make(Opcode::op_mul, reg(0), reg(3), reg(5)));
    EXPECT_EQ(wide(0, 0, 3), c.product) << c.a << " x " << int{c.b};
    EXPECT_EQ(rtl_flags(), flags) << c.a << " x " << int{c.b};
    EXPECT_EQ(rtl(0).last_cycles(), CuDatapathRtl::MUL_CYCLES);
    for (unsigned lane = 0; lane < lanes(); ++lane) {
      array().set_cmem(lane, 30, static_cast<uint8_t>(a >> 8));
      array().set_cmem(lane, 31, static_cast<uint8_t>(a));
      array().set_cmem(lane, 32, b);
    }
    // The loop variable moves the product to [40 + 4].
    LoopVariables variables{4, 0, 0};
    run(make(Opcode::op_mulm, mem(40, 1), mem(30), mem(32)), variables, 1);
    const uint32_t stored =
        uint32_t{array().cmem(7, 44)} << 16 | uint32_t{array().cmem(7, 45)} << 8 | uint32_t{array().cmem(7, 46)};
    EXPECT_EQ(stored, c.product) << c.a << " x " << int{c.b};
  }
}

TEST_F(CuDatapathDirected, NeighbourReadsAtEveryEdgeAndCornerAreZeroBeyondTheGrid) {
  // Register 1 holds lane + 1 and CMEM [20 + 2] holds 0x40 + lane, so that
  // every value read from a neighbour names it and none is 0.
  for (unsigned lane = 0; lane < lanes(); ++lane) {
    array().set_cmem(lane, 0, static_cast<uint8_t>(lane + 1));
    array().set_cmem(lane, 22, static_cast<uint8_t>(0x40 + lane));
  }
  run(make(Opcode::op_mov, reg(1), mem(0)));
  for (unsigned k = 0; k < 4; ++k) {
    const auto direction = static_cast<Direction>(k);
    run(make_nget(reg(2), direction, reg(1)));
    run(make_nget(reg(3), direction, mem(20, 1)), {2, 0, 0}, 1);
    run(make_nget(mem(24), direction, mem(22)));
    for (unsigned lane = 0; lane < lanes(); ++lane) {
      const int other = neighbour_of(lane, direction);
      const std::string where = std::string(direction_name(direction)) + " of lane " + std::to_string(lane);
      EXPECT_EQ(rtl(lane).reg(2), other < 0 ? 0 : other + 1) << where;
      EXPECT_EQ(rtl(lane).reg(3), other < 0 ? 0 : 0x40 + other) << where;
      EXPECT_EQ(array().cmem(lane, 24), other < 0 ? 0 : 0x40 + other) << where;
    }
  }
}

// The Image Blender's instructions (array.features.divide, .neighbour_add):
// values and flags by hand, the RTL's in one edge each.
TEST_F(CuDatapathDirected, DivideSaturatesWhereTheQuotientDoesNotFitInRegistersAndCmem) {
  struct Case {
    uint16_t dividend;
    uint8_t divisor;
    uint8_t quotient;
    CuFlags flags;
  };
  const std::array<Case, 7> cases{{
      {0x1234, 0x56, 0x36, czs(false, false, false)},  // 4660 / 86 = 54.19
      {0x0380, 0x07, 0x80, czs(false, false, true)},   // 896 / 7 = 128
      {0xfeff, 0xff, 0xff, czs(false, false, true)},   // 255.99: fits
      {0x0003, 0x07, 0x00, czs(false, true, false)},
      {0x0100, 0x01, 0xff, czs(true, false, true)},  // 256: saturated
      {0xff00, 0xff, 0xff, czs(true, false, true)},  // 256: saturated
      {0x0005, 0x00, 0xff, czs(true, false, true)},  // by zero: saturated
  }};
  for (const Case& c : cases) {
    load_wide(3, c.dividend, 2);
    load(5, c.divisor);
    run(make(Opcode::op_div, reg(0), reg(3), reg(5)));
    EXPECT_EQ(rtl(0).reg(0), c.quotient) << std::hex << c.dividend << " / " << unsigned{c.divisor};
    EXPECT_EQ(rtl_flags(), c.flags) << std::hex << c.dividend << " / " << unsigned{c.divisor};
    EXPECT_EQ(rtl(0).last_cycles(), CuDatapathRtl::ALU_CYCLES);
    // The dividend in CMEM, moved by the loop variable to [30 + 2].
    for (unsigned lane = 0; lane < lanes(); ++lane) {
      array().set_cmem(lane, 32, static_cast<uint8_t>(c.dividend >> 8));
      array().set_cmem(lane, 33, static_cast<uint8_t>(c.dividend));
    }
    run(make(Opcode::op_div, mem(40), mem(30, 1), reg(5)), {2, 0, 0}, 1);
    EXPECT_EQ(array().cmem(7, 40), c.quotient) << std::hex << c.dividend << " / " << unsigned{c.divisor};
  }
}

TEST_F(CuDatapathDirected, NeighbourAddAddsTheNeighboursByteToDAndZeroBeyondTheGrid) {
  // r1 = lane + 1 and r2 = 0xf0 in every CU: nadd r2, dir, r1 = 0xf0 + the
  // neighbour's lane + 1 (at most 12: no carry), 0xf0 beyond the grid.
  for (unsigned lane = 0; lane < lanes(); ++lane) array().set_cmem(lane, 0, static_cast<uint8_t>(lane + 1));
  run(make(Opcode::op_mov, reg(1), mem(0)));
  for (unsigned k = 0; k < 4; ++k) {
    const auto direction = static_cast<Direction>(k);
    load(2, 0xf0);
    run(make(Opcode::op_nadd, reg(2), reg(1), {false, static_cast<uint16_t>(direction), 0}));
    for (unsigned lane = 0; lane < lanes(); ++lane) {
      const int other = neighbour_of(lane, direction);
      const std::string where = std::string(direction_name(direction)) + " of lane " + std::to_string(lane);
      EXPECT_EQ(rtl(lane).reg(2), 0xf0 + (other < 0 ? 0 : other + 1)) << where;
      EXPECT_EQ(rtl_flags(lane), czs(false, false, true)) << where;
    }
  }
  // 0xf0 + 0x10 = 0x100: 0 with C and Z, in the CUs with a left neighbour.
  load(1, 0x10);
  load(2, 0xf0);
  run(make(Opcode::op_nadd, reg(2), reg(1), {false, static_cast<uint16_t>(Direction::left), 0}));
  EXPECT_EQ(rtl(1).reg(2), 0x00);
  EXPECT_EQ(rtl_flags(1), czs(true, true, false));
  EXPECT_EQ(rtl(0).reg(2), 0xf0);
  EXPECT_EQ(rtl_flags(0), czs(false, false, true));
}

TEST_F(CuDatapathDirected, NaddsAndNadcsAddTheNeighboursAOrAPlusOneByTheirSAndKeepZAndS) {
  // The neighbours' bytes at [0] and [1] (and in r1, r2): lane + 1 and
  // 0x80 + lane + 1. d = 0xf0 at [8] (CMEM) or in r3. C set by a compare of
  // equals, then S set in the even lanes by a mov of 0x80 (0x01 in the odd).
  for (unsigned lane = 0; lane < lanes(); ++lane) {
    array().set_cmem(lane, 0, static_cast<uint8_t>(lane + 1));
    array().set_cmem(lane, 1, static_cast<uint8_t>(0x80 + lane + 1));
    array().set_cmem(lane, 2, lane % 2 == 0 ? 0x80 : 0x01);
  }
  run(make(Opcode::op_mov, reg(1), mem(0)));
  run(make(Opcode::op_mov, reg(2), mem(1)));
  for (const Opcode opcode : {Opcode::op_nadds, Opcode::op_nadcs}) {
    for (unsigned k = 0; k < 4; ++k) {
      const auto direction = static_cast<Direction>(k);
      for (const bool in_cmem : {false, true}) {
        for (unsigned lane = 0; lane < lanes(); ++lane) array().set_cmem(lane, 8, 0xf0);
        load(3, 0xf0);
        run(make(Opcode::op_cmp, mem(2), mem(2)));
        run(make(Opcode::op_mov, reg(4), mem(2)));
        const Operand d = in_cmem ? mem(8) : reg(3);
        run(make(opcode, d, in_cmem ? mem(0) : reg(1), {false, static_cast<uint16_t>(direction), 0}));
        for (unsigned lane = 0; lane < lanes(); ++lane) {
          const int other = neighbour_of(lane, direction);
          const bool s = lane % 2 == 0;
          const unsigned value = other < 0 ? 0 : (s ? 0x80u : 0u) + static_cast<unsigned>(other) + 1;
          const unsigned sum = 0xf0 + value + (opcode == Opcode::op_nadcs ? 1 : 0);
          const std::string where = std::string(op_info(opcode).mnemonic) + " " +
                                    std::string(direction_name(direction)) + " of lane " + std::to_string(lane);
          EXPECT_EQ(in_cmem ? array().cmem(lane, 8) : rtl(lane).reg(3), sum & 0xffu) << where;
          // C the carry; Z and S as the mov of 0x80 or 0x01 left them.
          EXPECT_EQ(rtl_flags(lane), czs(sum > 0xff, false, s)) << where;
        }
      }
    }
  }
}

// MorphoSys's 16-bit operations on register pairs: carries and borrows
// across the bytes, Z of all 16 bits, S bit 15, C kept by mov16, nothing
// written by cmp16, d equal to a source; the CMEM write enables stay low.
TEST_F(CuDatapathDirected, PairOperationsCarryAcrossTheBytesWithFlagsOfAll16Bits) {
  load_wide(0, 0x00ff, 2);
  load_wide(2, 0x0001, 2);
  run(make(Opcode::op_add16, reg(4), reg(0), reg(2)));
  EXPECT_EQ(wide(0, 4, 2), 0x0100u);
  EXPECT_EQ(rtl_flags(), czs(false, false, false));
  // 0xffff + 1: 0 with the carry out, into the first pair itself.
  load_wide(0, 0xffff, 2);
  run(make(Opcode::op_add16, reg(0), reg(0), reg(2)));
  EXPECT_EQ(wide(0, 0, 2), 0u);
  EXPECT_EQ(rtl_flags(), czs(true, true, false));
  // 0x0012: the high byte is 0, Z is clear (an adc's Z would be set).
  load_wide(0, 0x0010, 2);
  load_wide(2, 0x0002, 2);
  run(make(Opcode::op_add16, reg(6), reg(0), reg(2)));
  EXPECT_EQ(wide(0, 6, 2), 0x0012u);
  EXPECT_EQ(rtl_flags(), czs(false, false, false));
  // 0x0100 - 0x0001 = 0x00ff, no borrow; 0x0001 - 0x0100 borrows, S set.
  load_wide(0, 0x0100, 2);
  load_wide(2, 0x0001, 2);
  run(make(Opcode::op_sub16, reg(4), reg(0), reg(2)));
  EXPECT_EQ(wide(0, 4, 2), 0x00ffu);
  EXPECT_EQ(rtl_flags(), czs(true, false, false));
  run(make(Opcode::op_sub16, reg(4), reg(2), reg(0)));
  EXPECT_EQ(wide(0, 4, 2), 0xff01u);
  EXPECT_EQ(rtl_flags(), czs(false, false, true));
  // cmp16 of equal pairs: Z and C, nothing written.
  load_wide(4, 0x1234, 2);
  load_wide(6, 0x1234, 2);
  run(make(Opcode::op_cmp16, {}, reg(4), reg(6)));
  EXPECT_EQ(wide(0, 4, 2), 0x1234u);
  EXPECT_EQ(rtl_flags(), czs(true, true, false));
  // mov16 keeps C: set by the compare, then 0x8000 moved.
  load_wide(0, 0x8000, 2);
  run(make(Opcode::op_cmp16, {}, reg(4), reg(6)));
  run(make(Opcode::op_mov16, reg(2), reg(0)));
  EXPECT_EQ(wide(0, 2, 2), 0x8000u);
  EXPECT_EQ(rtl_flags(), czs(true, false, true));
  for (unsigned lane = 0; lane < lanes(); ++lane) EXPECT_EQ(rtl_flags(lane), czs(true, false, true));
}

TEST(CuDatapathRtl, ArrayControllerOpcodesAreNoOpsForTheCu) {
  CuDatapathRtl cu;
  CuOperandBytes bytes;
  bytes.a = {0x12, 0x34};
  bytes.b = 0x56;
  CuNeighbours neighbours;
  neighbours.value = {1, 2, 3, 4};
  neighbours.present = {true, true, true, true};
  cu.execute(make(Opcode::op_mov, reg(0), mem(0)), bytes, neighbours);
  cu.execute(make(Opcode::op_shl, reg(1), reg(0)), bytes, neighbours);
  const CuFlags flags = cu.flags();
  EXPECT_EQ(flags, czs(false, false, false));
  for (const Opcode opcode : {Opcode::op_nop, Opcode::op_halt, Opcode::op_loop, Opcode::op_endloop}) {
    const CuCmemWrite write = cu.execute(make(opcode, mem(1), mem(2), mem(3)), bytes, neighbours);
    EXPECT_EQ(cu.last_cycles(), 1u) << op_info(opcode).mnemonic;
    EXPECT_EQ(write.enable, (std::array<bool, 3>{false, false, false})) << op_info(opcode).mnemonic;
    EXPECT_EQ(cu.reg(0), 0x12);
    EXPECT_EQ(cu.reg(1), 0x24);
    EXPECT_EQ(cu.flags(), flags);
    EXPECT_TRUE(cu.mask());
  }
  // A code with no instruction behind it is a no-op as well.
  Instruction unknown = make(Opcode::op_nop);
  unknown.opcode = static_cast<Opcode>(0x3f);
  cu.execute(unknown, bytes, neighbours);
  EXPECT_EQ(cu.reg(1), 0x24);
  EXPECT_EQ(cu.flags(), flags);
}

}  // namespace
}  // namespace tessera::ap
