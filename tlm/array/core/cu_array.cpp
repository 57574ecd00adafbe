#include "array/core/cu_array.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace tessera::ap {

namespace {

// Rows are padded to a multiple of this so every row starts aligned for
// the widest vector unit the compiler may use.
constexpr size_t ROW_ALIGN = 64;
// copy_row's block: a divisor of ROW_ALIGN, so that a row's copy never
// leaves it.
constexpr size_t COPY_BLOCK = 32;
static_assert(ROW_ALIGN % COPY_BLOCK == 0);

// Scratch (spare) rows: the result of the instruction before it is stored,
// the neighbour's bytes, and the multiply's three product bytes.
constexpr unsigned SCRATCH_RESULT = 0, SCRATCH_NEIGHBOUR = 1, SCRATCH_PRODUCT = 2, SCRATCH_ROWS = 5;

enum FlagRow : unsigned { flag_c = 0, flag_z = 1, flag_s = 2, flag_m = 3, flag_rows = 4 };

// The flags a lane loop writes (bits; 0: none): every flag its instruction
// sets, or, in a compiled trace, those a later instruction (or the trace's
// end) reads before another writes them (CuArray::live_flag_writes). Z and
// S are set together by every instruction that sets either.
enum FlagWrites : unsigned { writes_c = 1, writes_zs = 2, writes_all = 3, flag_write_kinds = 4 };

// The lane loops. Each writes the result into `out` (scratch, never an
// operand) and the flags of kWrites; the caller then stores `out` into the
// destination. Keeping the destination out of these loops lets the
// compiler vectorise them without checking for overlap with the sources.
template <bool kInvert, bool kCarryFromFlag, unsigned kWrites>
void add_lanes(size_t n, const uint8_t* a, const uint8_t* b, bool carry_in, uint8_t* __restrict out,
               uint8_t* __restrict c, uint8_t* __restrict z, uint8_t* __restrict s) {
  // In bytes throughout (the carry from two unsigned compares, the carry in
  // being 0 or 1), so that the vectorised loop needs no wider lanes.
  for (size_t l = 0; l < n; ++l) {
    const uint8_t x = a[l];
    const auto addend = static_cast<uint8_t>(kInvert ? ~b[l] : b[l]);
    const uint8_t carry = kCarryFromFlag ? c[l] : static_cast<uint8_t>(carry_in);
    const auto partial = static_cast<uint8_t>(x + addend);
    const auto value = static_cast<uint8_t>(partial + carry);
    out[l] = value;
    if constexpr ((kWrites & writes_c) != 0)
      c[l] = static_cast<uint8_t>((partial < x ? 1 : 0) | (value < partial ? 1 : 0));
    if constexpr ((kWrites & writes_zs) != 0) {
      z[l] = value == 0 ? 1 : 0;
      s[l] = value >> 7;
    }
  }
}

template <unsigned kWrites, class F>
void logic_lanes(size_t n, const uint8_t* a, const uint8_t* b, uint8_t* __restrict out, uint8_t* __restrict z,
                 uint8_t* __restrict s, F f) {
  for (size_t l = 0; l < n; ++l) {
    const uint8_t value = f(a[l], b[l]);
    out[l] = value;
    if constexpr ((kWrites & writes_zs) != 0) {
      z[l] = value == 0 ? 1 : 0;
      s[l] = value >> 7;
    }
  }
}

// F(a, carry) returns the shifted byte; the carry out is bit 7 or bit 0 of a.
template <bool kCarryFromTop, unsigned kWrites, class F>
void shift_lanes(size_t n, const uint8_t* a, uint8_t* __restrict out, uint8_t* __restrict c, uint8_t* __restrict z,
                 uint8_t* __restrict s, F f) {
  for (size_t l = 0; l < n; ++l) {
    const uint8_t value = f(a[l], c[l]);
    out[l] = value;
    if constexpr ((kWrites & writes_c) != 0)
      c[l] = kCarryFromTop ? static_cast<uint8_t>(a[l] >> 7) : static_cast<uint8_t>(a[l] & 1u);
    if constexpr ((kWrites & writes_zs) != 0) {
      z[l] = value == 0 ? 1 : 0;
      s[l] = value >> 7;
    }
  }
}

// The 16-bit add and subtract on register pairs (add16, sub16, cmp16): the
// sum of a:a_low and b:b_low (inverted, with a carry in, for a
// subtraction) into high:low, with the flags of all 16 bits.
template <unsigned kWrites>
void pair_add_lanes(size_t n, const uint8_t* a, const uint8_t* a_low, const uint8_t* b, const uint8_t* b_low,
                    bool subtract, uint8_t* __restrict high, uint8_t* __restrict low, uint8_t* __restrict c,
                    uint8_t* __restrict z, uint8_t* __restrict s) {
  const unsigned invert = subtract ? 0xffffu : 0u, carry_in = subtract ? 1u : 0u;
  for (size_t l = 0; l < n; ++l) {
    const unsigned x = unsigned{a[l]} << 8 | a_low[l];
    const unsigned y = (unsigned{b[l]} << 8 | b_low[l]) ^ invert;
    const unsigned sum = x + y + carry_in;
    high[l] = static_cast<uint8_t>(sum >> 8);
    low[l] = static_cast<uint8_t>(sum);
    if constexpr ((kWrites & writes_c) != 0) c[l] = static_cast<uint8_t>((sum >> 16) & 1u);
    if constexpr ((kWrites & writes_zs) != 0) {
      z[l] = (sum & 0xffffu) == 0 ? 1 : 0;
      s[l] = static_cast<uint8_t>((sum >> 15) & 1u);
    }
  }
}

// cond_holds() of every lane, as 0/1 bytes: the flag's own row for c, z
// and s, else `out`, filled by one branch-free loop per condition.
const uint8_t* condition_lanes(Cond cond, size_t n, const uint8_t* __restrict c, const uint8_t* __restrict z,
                               const uint8_t* __restrict s, uint8_t* __restrict out) {
  switch (cond) {
    case Cond::c: return c;
    case Cond::nc:
      for (size_t l = 0; l < n; ++l) out[l] = c[l] ^ 1u;
      return out;
    case Cond::z: return z;
    case Cond::nz:
      for (size_t l = 0; l < n; ++l) out[l] = z[l] ^ 1u;
      return out;
    case Cond::s: return s;
    case Cond::ns:
      for (size_t l = 0; l < n; ++l) out[l] = s[l] ^ 1u;
      return out;
    case Cond::hi:
      for (size_t l = 0; l < n; ++l) out[l] = c[l] & (z[l] ^ 1u);
      return out;
    case Cond::ls:
      for (size_t l = 0; l < n; ++l) out[l] = (c[l] ^ 1u) | z[l];
      return out;
  }
  return out;
}

// The masked store: `value` into `destination` where the lane's mask is set.
void store_masked_lanes(size_t n, const uint8_t* __restrict value, uint8_t* __restrict destination,
                        const uint8_t* __restrict mask) {
  // Branch-free, so that it vectorises: the mask's lanes are random.
  for (size_t l = 0; l < n; ++l) {
    const auto keep = static_cast<uint8_t>(mask[l] != 0 ? 0xff : 0);
    destination[l] = static_cast<uint8_t>((value[l] & keep) | (destination[l] & ~keep));
  }
}

// mul's signed 16 x 8 -> 24-bit product in 16-bit arithmetic, which the
// compiler vectorises (SSE2 multiplies 16-bit lanes, not 32-bit ones): with
// a = ah:al, a x b = (ah x b + (al x b >> 8)) x 256 + (al x b & 0xff), both
// partial products and their sum within 16 bits (al x b in [-32640, 32385],
// the sum in [-16384, 16510]), the sum being bits 8..23 of the product.
template <unsigned kWrites>
void mul_lanes(size_t n, const uint8_t* a, const uint8_t* a_low, const uint8_t* b, uint8_t* __restrict high,
               uint8_t* __restrict middle, uint8_t* __restrict low, uint8_t* __restrict c, uint8_t* __restrict z,
               uint8_t* __restrict s) {
  for (size_t l = 0; l < n; ++l) {
    // b and ah sign-extended: (x ^ 0x80) - 0x80.
    const auto factor = static_cast<int16_t>((b[l] ^ 0x80) - 0x80);
    const auto low_product = static_cast<int16_t>(a_low[l] * factor);
    const auto upper = static_cast<int16_t>(((a[l] ^ 0x80) - 0x80) * factor + (low_product >> 8));
    high[l] = static_cast<uint8_t>(static_cast<uint16_t>(upper) >> 8);
    middle[l] = static_cast<uint8_t>(upper);
    low[l] = static_cast<uint8_t>(low_product);
    if constexpr ((kWrites & writes_c) != 0) c[l] = 0;
    if constexpr ((kWrites & writes_zs) != 0) {
      z[l] = (static_cast<uint16_t>(upper) | static_cast<uint8_t>(low_product)) == 0 ? 1 : 0;
      s[l] = static_cast<uint8_t>(static_cast<uint16_t>(upper) >> 15);
    }
  }
}

// The lanes' arithmetic of one instruction, shared by the interpreter
// (CuArray::execute) and the trace runner (trace_arithmetic): the result in
// `out`, or a multiplication's 24-bit product in `high`, `middle`, `low`,
// and the flags in c, z, s, or a 16-bit operation's result in `high`,
// `middle`. `a_low` is the multiplicand's, the dividend's or a pair's low
// byte, `b_low` a pair's. Returns the rows written (1, 2 for a pair, 3 for a
// product), or 0 for an instruction that is not arithmetic (the caller's
// own: masks, nget, nadd). With kLanes not 0 the
// lane count is known to the compiler, which then unrolls the lane loops.
// Only the flags of kWrites are written (FlagWrites).
template <size_t kLanes, unsigned kWrites = writes_all>
[[gnu::always_inline]] inline unsigned arithmetic_lanes(Opcode opcode, size_t lanes, const uint8_t* a,
                                                        const uint8_t* a_low, const uint8_t* b, const uint8_t* b_low,
                                                        const uint8_t* m, uint8_t* out, uint8_t* high, uint8_t* middle,
                                                        uint8_t* low, uint8_t* c, uint8_t* z, uint8_t* s) {
  const size_t n = kLanes != 0 ? kLanes : lanes;
  switch (opcode) {
    case Opcode::op_add: add_lanes<false, false, kWrites>(n, a, b, false, out, c, z, s); return 1;
    case Opcode::op_adc: add_lanes<false, true, kWrites>(n, a, b, false, out, c, z, s); return 1;
    case Opcode::op_sub:
    case Opcode::op_cmp: add_lanes<true, false, kWrites>(n, a, b, true, out, c, z, s); return 1;
    case Opcode::op_sbc:
    case Opcode::op_cmpc: add_lanes<true, true, kWrites>(n, a, b, false, out, c, z, s); return 1;
    case Opcode::op_and: logic_lanes<kWrites>(n, a, b, out, z, s, [](uint8_t x, uint8_t y) { return x & y; }); return 1;
    case Opcode::op_or: logic_lanes<kWrites>(n, a, b, out, z, s, [](uint8_t x, uint8_t y) { return x | y; }); return 1;
    case Opcode::op_xor: logic_lanes<kWrites>(n, a, b, out, z, s, [](uint8_t x, uint8_t y) { return x ^ y; }); return 1;
    case Opcode::op_not:
      logic_lanes<kWrites>(n, a, a, out, z, s, [](uint8_t x, uint8_t) { return static_cast<uint8_t>(~x); });
      return 1;
    case Opcode::op_mov: logic_lanes<kWrites>(n, a, a, out, z, s, [](uint8_t x, uint8_t) { return x; }); return 1;
    case Opcode::op_shl:
      shift_lanes<true, kWrites>(n, a, out, c, z, s, [](uint8_t x, uint8_t) { return static_cast<uint8_t>(x << 1); });
      return 1;
    case Opcode::op_shr:
      shift_lanes<false, kWrites>(n, a, out, c, z, s, [](uint8_t x, uint8_t) { return static_cast<uint8_t>(x >> 1); });
      return 1;
    case Opcode::op_asr:
      shift_lanes<false, kWrites>(n, a, out, c, z, s,
                                  [](uint8_t x, uint8_t) { return static_cast<uint8_t>((x >> 1) | (x & 0x80u)); });
      return 1;
    case Opcode::op_rol:
      shift_lanes<true, kWrites>(n, a, out, c, z, s,
                                 [](uint8_t x, uint8_t carry) { return static_cast<uint8_t>((x << 1) | carry); });
      return 1;
    case Opcode::op_ror:
      shift_lanes<false, kWrites>(
          n, a, out, c, z, s, [](uint8_t x, uint8_t carry) { return static_cast<uint8_t>((x >> 1) | (carry << 7)); });
      return 1;
    case Opcode::op_mul:
    case Opcode::op_mulm: mul_lanes<kWrites>(n, a, a_low, b, high, middle, low, c, z, s); return 3;
    case Opcode::op_getm:
      for (size_t l = 0; l < n; ++l) out[l] = m[l] != 0 ? 0xff : 0;
      return 1;
    case Opcode::op_div:
      for (size_t l = 0; l < n; ++l) {
        // cu_div's result without its steps: below 256 x b the quotient
        // fits 8 bits, else (b = 0 included) it saturates with C set.
        const bool fits = a[l] < b[l];
        const unsigned dividend = unsigned{a[l]} << 8 | a_low[l];
        const auto value = static_cast<uint8_t>(fits ? dividend / b[l] : 0xffu);
        out[l] = value;
        if constexpr ((kWrites & writes_c) != 0) c[l] = fits ? 0 : 1;
        if constexpr ((kWrites & writes_zs) != 0) {
          z[l] = value == 0 ? 1 : 0;
          s[l] = value >> 7;
        }
      }
      return 1;
    case Opcode::op_add16:
    case Opcode::op_sub16:
    case Opcode::op_cmp16:
      pair_add_lanes<kWrites>(n, a, a_low, b, b_low, opcode != Opcode::op_add16, high, middle, c, z, s);
      return 2;
    case Opcode::op_mov16:
      for (size_t l = 0; l < n; ++l) {
        high[l] = a[l];
        middle[l] = a_low[l];
        if constexpr ((kWrites & writes_zs) != 0) {
          z[l] = (a[l] | a_low[l]) == 0 ? 1 : 0;
          s[l] = a[l] >> 7;
        }
      }
      return 2;
    default: return 0;
  }
}

}  // namespace

CuArray::CuArray(const ArrayGeometry& geometry)
    : m_geometry(geometry),
      m_lanes(geometry.lanes()),
      m_stride((geometry.lanes() + ROW_ALIGN - 1) / ROW_ALIGN * ROW_ALIGN),
      m_copy_bytes((geometry.lanes() + COPY_BLOCK - 1) / COPY_BLOCK * COPY_BLOCK),
      m_reg_row(geometry.cmem_bytes),
      m_flag_row(geometry.cmem_bytes + geometry.registers),
      m_scratch_row(geometry.cmem_bytes + geometry.registers + flag_rows) {
  // One guard row before and after: a neighbour read at the array's first
  // or last lane touches them (and is then masked to 0).
  m_storage.assign((size_t{m_scratch_row} + SCRATCH_ROWS + 2) * m_stride, 0);
  const auto columns = static_cast<int>(geometry.columns);
  m_neighbour_step = {-1, 1, -columns, columns};
  for (unsigned direction = 0; direction < 4; ++direction) {
    m_has_neighbour[direction].assign(m_lanes, 0);
    m_lanes_with_neighbour[direction] = 0;
    for (unsigned lane = 0; lane < m_lanes; ++lane) {
      const unsigned column = lane % geometry.columns, row = lane / geometry.columns;
      const bool has = (direction == 0 && column > 0) || (direction == 1 && column + 1 < geometry.columns) ||
                       (direction == 2 && row > 0) || (direction == 3 && row + 1 < geometry.rows);
      m_has_neighbour[direction][lane] = has ? 0xff : 0;
      m_lanes_with_neighbour[direction] += has ? 1 : 0;
    }
  }
  set_row_ring(false);
  for (const OpInfo& info : all_ops()) {
    OpLanes& op = m_op_lanes[static_cast<unsigned>(info.opcode)];
    op.d_width = static_cast<uint8_t>(operand_width(info.opcode, 'd'));
    op.a_width = static_cast<uint8_t>(operand_width(info.opcode, 'a'));
    op.b_width = static_cast<uint8_t>(operand_width(info.opcode, 'b'));
    op.uses_d = info.operands != OperandPattern::ab;
    op.uses_b = info.operands == OperandPattern::dab || info.operands == OperandPattern::ab;
    op.uses_a = info.operands != OperandPattern::d;
    const auto sets = [&](char flag) { return info.flags.find(flag) != std::string_view::npos; };
    op.writes = static_cast<uint8_t>((sets('C') ? unsigned{writes_c} : 0u) |
                                     (sets('Z') || sets('S') ? unsigned{writes_zs} : 0u));
  }
  reset();
}

void CuArray::reset() {
  std::fill(m_storage.begin(), m_storage.end(), 0);
  for (unsigned r = 0; r < m_reg_rows.size(); ++r) m_reg_rows[r] = m_reg_row + r;
  for (unsigned k = 0; k < SCRATCH_ROWS; ++k) m_spare_rows[k] = m_scratch_row + k;
  std::fill_n(row(m_flag_row + flag_m), m_lanes, 1);
  m_active = m_lanes;
  m_active_stale = false;
}

CuFlags CuArray::flags(unsigned lane) const {
  const auto flag = [&](unsigned which) { return m_storage[row_offset(m_flag_row + which) + lane] != 0; };
  return {flag(flag_c), flag(flag_z), flag(flag_s)};
}

void CuArray::set_flags(unsigned lane, const CuFlags& flags) {
  m_storage[row_offset(m_flag_row + flag_c) + lane] = flags.c ? 1 : 0;
  m_storage[row_offset(m_flag_row + flag_z) + lane] = flags.z ? 1 : 0;
  m_storage[row_offset(m_flag_row + flag_s) + lane] = flags.s ? 1 : 0;
}

void CuArray::set_mask(unsigned lane, bool mask) {
  m_storage[row_offset(m_flag_row + flag_m) + lane] = mask ? 1 : 0;
  m_active_stale = true;
}

void CuArray::add_activity(const ArrayActivity& more) {
  m_activity += more;
}

void CuArray::set_lane_count(unsigned lanes) {
  m_lanes = std::min(lanes, m_geometry.lanes());
  m_copy_bytes = std::min(m_stride, (size_t{m_lanes} + COPY_BLOCK - 1) / COPY_BLOCK * COPY_BLOCK);
  m_active_stale = true;
  if (m_count_lanes) clear_lane_counts();
}

void CuArray::count_per_lane(bool on) {
  m_count_lanes = on;
  if (on) clear_lane_counts();
}

void CuArray::clear_lane_counts() {
  for (unsigned stage = 0; stage < STAGE_COUNT; ++stage) {
    m_lane_useful[stage].assign(m_lanes, 0);
    m_lane_stores[stage].assign(m_lanes, 0);
  }
}

void CuArray::count_active() const {
  const uint8_t* m = m_storage.data() + row_offset(m_flag_row + flag_m);
  // Eight 0/1 bytes at a time: their sum is the top byte of the word times
  // 0x0101010101010101 (at most 8, so no byte overflows).
  unsigned active = 0, l = 0;
  for (; l + 8 <= m_lanes; l += 8) {
    uint64_t word;
    std::memcpy(&word, m + l, 8);
    active += static_cast<unsigned>((word * 0x0101010101010101u) >> 56);
  }
  for (; l < m_lanes; ++l) active += m[l];
  m_active = active;
  m_active_stale = false;
}

inline uint8_t* CuArray::operand_row(const Operand& operand, unsigned byte, const LoopVariables& loop_variables,
                                     unsigned active_loops) {
  if (!operand.in_cmem) return row(m_reg_rows[operand.value + byte]);
  long address = long{operand.value} + byte;
  if (operand.loop != 0) {
    if (operand.loop > active_loops) return nullptr;
    address += loop_variables[operand.loop - 1];
  }
  if (address < 0 || address >= static_cast<long>(m_geometry.cmem_bytes)) return nullptr;
  return row(static_cast<unsigned>(address));
}

std::string CuArray::operand_error(const Operand& operand, unsigned byte, const LoopVariables& loop_variables,
                                   unsigned active_loops) const {
  long address = long{operand.value} + byte;
  if (operand.loop != 0) {
    if (operand.loop > active_loops)
      return "operand uses loop variable i" + std::to_string(operand.loop - 1) + " outside its loop";
    address += loop_variables[operand.loop - 1];
  }
  return "CMEM address " + std::to_string(address) + " is beyond the " + std::to_string(m_geometry.cmem_bytes) +
         " bytes of CMEM";
}

inline void CuArray::copy_row(uint8_t* __restrict destination, const uint8_t* __restrict source) const {
  for (size_t i = 0; i < m_copy_bytes; i += COPY_BLOCK) std::memcpy(destination + i, source + i, COPY_BLOCK);
}

bool CuArray::lut_indices_fit(const uint8_t* high, const uint8_t* low, std::string& error) {
  // Every lane looks up (its registers are written, masked or not), so
  // every lane's index must lie within the table; checked before any state
  // changes.
  const auto entries = static_cast<unsigned>(m_lut.size());
  for (size_t l = 0; l < m_lanes; ++l) {
    const unsigned index = unsigned{high[l]} << 8 | low[l];
    if (index >= entries) {
      m_fault = Fault::lut_index;
      error = "lut index " + std::to_string(index) + " in CU " + std::to_string(l) + " is beyond the table's " +
              std::to_string(entries) + " entries (array.lut.entries)";
      return false;
    }
  }
  return true;
}

bool CuArray::send_pixels(const Instruction& in, const LoopVariables& loop_variables, unsigned active_loops,
                          std::string& error) {
  constexpr unsigned WIDTH = 4;
  std::array<const uint8_t*, WIDTH> a{}, b{};
  m_fault = Fault::operand;
  for (unsigned i = 0; i < WIDTH; ++i) {
    if ((a[i] = operand_row(in.a, i, loop_variables, active_loops)) == nullptr) {
      error = operand_error(in.a, i, loop_variables, active_loops);
      return false;
    }
    if ((b[i] = operand_row(in.b, i, loop_variables, active_loops)) == nullptr) {
      error = operand_error(in.b, i, loop_variables, active_loops);
      return false;
    }
  }
  const size_t n = m_lanes;
  const uint8_t* m = row(m_flag_row + flag_m);
  const auto pair = [](const uint8_t* high, const uint8_t* low, size_t l) {
    return static_cast<uint16_t>(unsigned{high[l]} << 8 | low[l]);
  };
  m_sent.clear();
  for (size_t l = 0; l < n; ++l)
    if (m[l] != 0)
      m_sent.push_back({static_cast<uint16_t>(l), pair(a[0], a[1], l), pair(a[2], a[3], l), pair(b[0], b[1], l),
                        pair(b[2], b[3], l)});
  m_activity.lane_operations += n;
  m_activity.useful_operations += m_sent.size();
  m_activity.cmem_reads += n * ((in.a.in_cmem ? WIDTH : 0) + (in.b.in_cmem ? WIDTH : 0));
  if (m_count_lanes) {
    uint32_t* lane_useful = m_lane_useful[static_cast<unsigned>(in.stage)].data();
    for (size_t l = 0; l < n; ++l) lane_useful[l] += m[l];
  }
  return true;
}

void CuArray::neighbour_lanes(const Instruction& in, const uint8_t* a, const uint8_t* d, bool d_masked,
                              uint8_t* neighbour, uint8_t* out) {
  const size_t n = m_lanes;
  uint8_t* c = row(m_flag_row + flag_c);
  uint8_t* z = row(m_flag_row + flag_z);
  uint8_t* s = row(m_flag_row + flag_s);
  const uint8_t* m = row(m_flag_row + flag_m);
  const auto direction = static_cast<unsigned>(in.direction());
  const uint8_t* has = m_has_neighbour[direction].data();
  const int step = m_neighbour_step[direction];
  m_activity.neighbour_transfers += m_lanes_with_neighbour[direction];
  const bool nadd = in.opcode == Opcode::op_nadd;
  // Under lane skew left and up run before the reader, under row skew up.
  const bool earlier =
      (m_skew == IssueSkew::lane && step < 0) || (m_skew == IssueSkew::row && in.direction() == Direction::up);
  if (earlier && a == d) {
    // Delayed execution, reading an earlier lane (or row) whose operand
    // this instruction overwrites: that lane ran it already, so the lanes
    // go one by one in chain order, each reading its neighbour's new value
    // (where a masked CMEM store left the old one, the old one). Reading a
    // later lane, or an operand the instruction does not write, gives what
    // the lockstep loops below give.
    const uint8_t* result = nadd ? out : neighbour;
    for (size_t l = 0; l < n; ++l) {
      uint8_t value = 0;
      if (has[l] != 0) {
        const auto from = static_cast<size_t>(static_cast<ptrdiff_t>(l) + step);
        value = d_masked && m[from] == 0 ? d[from] : result[from];
      }
      neighbour[l] = value;
      if (nadd) add_lanes<false, false, writes_all>(1, d + l, neighbour + l, false, out + l, c + l, z + l, s + l);
    }
    return;
  }
  const uint8_t* source = a + step;
  for (size_t l = 0; l < n; ++l) neighbour[l] = source[l] & has[l];
  if (nadd) add_lanes<false, false, writes_all>(n, d, neighbour, false, out, c, z, s);
}

void CuArray::set_row_ring(bool on) {
  m_ring = on;
  const auto columns = static_cast<int>(m_geometry.columns), rows = static_cast<int>(m_geometry.rows);
  for (unsigned direction = 0; direction < 4; ++direction) {
    std::vector<int>& from = m_neighbour_lane[direction];
    from.assign(m_geometry.lanes(), -1);
    for (int lane = 0; lane < static_cast<int>(m_geometry.lanes()); ++lane) {
      const int column = lane % columns, row = lane / columns;
      switch (static_cast<Direction>(direction)) {
        case Direction::left: from[lane] = column > 0 ? lane - 1 : (on ? lane + columns - 1 : -1); break;
        case Direction::right: from[lane] = column + 1 < columns ? lane + 1 : (on ? lane - columns + 1 : -1); break;
        case Direction::up: from[lane] = row > 0 ? lane - columns : -1; break;
        case Direction::down: from[lane] = row + 1 < rows ? lane + columns : -1; break;
      }
    }
  }
}

void CuArray::neighbour_lanes_in_order(const Instruction& in, const uint8_t* a, const uint8_t* a_next, const uint8_t* d,
                                       bool d_masked, uint8_t* neighbour, uint8_t* out) {
  const size_t n = m_lanes;
  uint8_t* c = row(m_flag_row + flag_c);
  uint8_t* z = row(m_flag_row + flag_z);
  uint8_t* s = row(m_flag_row + flag_s);
  const uint8_t* m = row(m_flag_row + flag_m);
  const std::vector<int>& from_lane = m_neighbour_lane[static_cast<unsigned>(in.direction())];
  const bool select = a_next != nullptr;
  const bool with_carry = in.opcode == Opcode::op_nadcs;
  const bool adds = in.opcode != Opcode::op_nget;
  // nget's result is the neighbour's byte; every add's is `out`.
  const uint8_t* result = adds ? out : neighbour;
  uint64_t transfers = 0;
  for (size_t l = 0; l < n; ++l) {
    const int from = from_lane[l];
    const uint8_t* source = select && s[l] != 0 ? a_next : a;
    uint8_t value = 0;
    if (from >= 0) {
      ++transfers;
      const auto f = static_cast<size_t>(from);
      // Under skew an earlier lane (row skew: a lane of an earlier row) has
      // run the instruction already: where it wrote the row read, its new
      // byte (or, a masked CMEM store, the old one). A later lane, one of
      // the same row under row skew, or a row the instruction does not
      // write, gives the byte as it is.
      if (runs_before(f, l) && source == d)
        value = d_masked && m[f] == 0 ? d[f] : result[f];
      else
        value = source[f];
    }
    neighbour[l] = value;
    if (!adds) continue;
    const unsigned sum = unsigned{d[l]} + value + (with_carry ? c[l] : 0u);
    out[l] = static_cast<uint8_t>(sum);
    c[l] = static_cast<uint8_t>(sum >> 8);
    // nadd writes Z and S as add does; nadds and nadcs keep them (S is
    // their selector, and stays so for the wide sum's next byte).
    if (!select) {
      z[l] = static_cast<uint8_t>(sum) == 0 ? 1 : 0;
      s[l] = static_cast<uint8_t>((sum >> 7) & 1u);
    }
  }
  m_activity.neighbour_transfers += transfers;
}

bool CuArray::any_active_holds(Cond cond) {
  const size_t n = m_lanes;
  const uint8_t* holds = condition_lanes(cond, n, row(m_flag_row + flag_c), row(m_flag_row + flag_z),
                                         row(m_flag_row + flag_s), row(m_spare_rows[SCRATCH_RESULT]));
  const uint8_t* m = row(m_flag_row + flag_m);
  uint8_t any = 0;
  for (size_t l = 0; l < n; ++l) any |= static_cast<uint8_t>(holds[l] & m[l]);
  return any != 0;
}

std::string CuArray::execute(const Instruction& in, const LoopVariables& loop_variables, unsigned active_loops) {
  std::string error;
  execute(in, loop_variables, active_loops, error);
  return error;
}

bool CuArray::execute(const Instruction& in, const LoopVariables& loop_variables, unsigned active_loops,
                      std::string& error) {
  const size_t n = m_lanes;
  uint8_t* c = row(m_flag_row + flag_c);
  uint8_t* z = row(m_flag_row + flag_z);
  uint8_t* s = row(m_flag_row + flag_s);
  uint8_t* m = row(m_flag_row + flag_m);
  uint8_t* out = row(m_spare_rows[SCRATCH_RESULT]);

  switch (in.opcode) {
    case Opcode::op_mset:
      std::fill_n(m, n, 1);
      m_active = m_lanes;
      m_active_stale = false;
      return true;
    case Opcode::op_mclr:
      std::fill_n(m, n, 0);
      m_active = 0;
      m_active_stale = false;
      return true;
    case Opcode::op_mmov:
    case Opcode::op_mand:
    case Opcode::op_mor: {
      const uint8_t* holds = condition_lanes(in.cond(), n, c, z, s, out);
      if (in.opcode == Opcode::op_mmov)
        copy_row(m, holds);
      else if (in.opcode == Opcode::op_mand)
        for (size_t l = 0; l < n; ++l) m[l] &= holds[l];
      else
        for (size_t l = 0; l < n; ++l) m[l] |= holds[l];
      m_active_stale = true;
      return true;
    }
    default: break;
  }

  if (in.opcode == Opcode::op_zsend) return send_pixels(in, loop_variables, active_loops, error);

  // Resolve every operand row first, so an instruction with a bad address
  // changes nothing.
  const OpLanes& op = m_op_lanes[static_cast<unsigned>(in.opcode) & 63u];
  const unsigned d_width = op.d_width, a_width = op.a_width;
  const bool uses_d = op.uses_d, uses_a = op.uses_a, uses_b = op.uses_b;
  std::array<uint8_t*, 3> d_rows{}, a_rows{};
  std::array<uint8_t*, 2> b_rows{};
  const unsigned b_width = std::min<unsigned>(op.b_width, 2);
  m_fault = Fault::operand;
  for (unsigned i = 0; uses_d && i < d_width; ++i)
    if ((d_rows[i] = operand_row(in.d, i, loop_variables, active_loops)) == nullptr) {
      error = operand_error(in.d, i, loop_variables, active_loops);
      return false;
    }
  for (unsigned i = 0; uses_a && i < a_width; ++i)
    if ((a_rows[i] = operand_row(in.a, i, loop_variables, active_loops)) == nullptr) {
      error = operand_error(in.a, i, loop_variables, active_loops);
      return false;
    }
  for (unsigned i = 0; uses_b && i < b_width; ++i)
    if ((b_rows[i] = operand_row(in.b, i, loop_variables, active_loops)) == nullptr) {
      error = operand_error(in.b, i, loop_variables, active_loops);
      return false;
    }

  if (in.opcode == Opcode::op_lut && !lut_indices_fit(a_rows[0], a_rows[1], error)) return false;

  m_activity.lane_operations += n;
  const unsigned active_lanes = active();
  m_activity.useful_operations += active_lanes;
  uint32_t* lane_useful = m_count_lanes ? m_lane_useful[static_cast<unsigned>(in.stage)].data() : nullptr;
  uint32_t* lane_stores = m_count_lanes ? m_lane_stores[static_cast<unsigned>(in.stage)].data() : nullptr;
  if (m_count_lanes)
    for (size_t l = 0; l < n; ++l) lane_useful[l] += m[l];
  m_activity.cmem_reads += n * ((in.a.in_cmem && uses_a ? a_width : 0) + (in.b.in_cmem && uses_b ? b_width : 0));
  const bool d_masked = in.d.in_cmem;
  // Byte `byte` of d from spare row `spare`: a masked store into CMEM, or
  // the spare row renamed to the register.
  const auto store = [&](unsigned spare, unsigned byte, uint8_t* destination) {
    const uint8_t* value = row(m_spare_rows[spare]);
    if (d_masked) {
      store_masked_lanes(n, value, destination, m);
      m_activity.cmem_writes += active_lanes;
      if (m_count_lanes)
        for (size_t l = 0; l < n; ++l) lane_stores[l] += m[l];
    } else if (const unsigned r = in.d.value + byte; r < m_geometry.registers) {
      std::swap(m_reg_rows[r], m_spare_rows[spare]);
    } else {
      copy_row(destination, value);
    }
  };

  const uint8_t* a = a_rows[0];
  const bool selects = in.opcode == Opcode::op_nadds || in.opcode == Opcode::op_nadcs;
  if (in.opcode == Opcode::op_nget || in.opcode == Opcode::op_nadd || selects) {
    uint8_t* neighbour = row(m_spare_rows[SCRATCH_NEIGHBOUR]);
    if (m_ring || selects)
      neighbour_lanes_in_order(in, a, selects ? a_rows[1] : nullptr, d_rows[0], d_masked, neighbour, out);
    else
      neighbour_lanes(in, a, d_rows[0], d_masked, neighbour, out);
    // nget stores the neighbour's byte; the adds d plus it.
    store(in.opcode == Opcode::op_nget ? SCRATCH_NEIGHBOUR : SCRATCH_RESULT, 0, d_rows[0]);
    return true;
  }
  if (in.opcode == Opcode::op_lut) {
    uint8_t* high = row(m_spare_rows[SCRATCH_PRODUCT]);
    uint8_t* low = row(m_spare_rows[SCRATCH_PRODUCT + 1]);
    for (size_t l = 0; l < n; ++l) {
      const uint16_t entry = m_lut[unsigned{a_rows[0][l]} << 8 | a_rows[1][l]];
      high[l] = static_cast<uint8_t>(entry >> 8);
      low[l] = static_cast<uint8_t>(entry);
    }
    store(SCRATCH_PRODUCT, 0, d_rows[0]);
    store(SCRATCH_PRODUCT + 1, 1, d_rows[1]);
    return true;
  }
  uint8_t* high = row(m_spare_rows[SCRATCH_PRODUCT]);
  uint8_t* middle = row(m_spare_rows[SCRATCH_PRODUCT + 1]);
  uint8_t* low = row(m_spare_rows[SCRATCH_PRODUCT + 2]);
  const unsigned written =
      arithmetic_lanes<0>(in.opcode, n, a, a_rows[1], b_rows[0], b_rows[1], m, out, high, middle, low, c, z, s);
  if (written == 0) {
    error = "instruction " + std::string(op_info(in.opcode).mnemonic) + " does no lane work";
    return false;
  }
  if (written == 2) {
    if (uses_d) {
      store(SCRATCH_PRODUCT, 0, d_rows[0]);
      store(SCRATCH_PRODUCT + 1, 1, d_rows[1]);
    }
    return true;
  }
  if (written == 3) {
    store(SCRATCH_PRODUCT, 0, d_rows[0]);
    store(SCRATCH_PRODUCT + 1, 1, d_rows[1]);
    store(SCRATCH_PRODUCT + 2, 2, d_rows[2]);
    return true;
  }
  if (uses_d) store(SCRATCH_RESULT, 0, d_rows[0]);
  return true;
}

namespace {

// The trace runner (CuArray::run_trace): lanes in blocks of TRACE_BLOCK,
// each block's loops unrolled into a few vector operations. Rows are
// ROW_ALIGN bytes apart, so the lanes rounded up to a block stay within
// their rows (the bytes past the lanes are padding, which no lane reads).
constexpr size_t TRACE_BLOCK = 16;
static_assert(ROW_ALIGN % TRACE_BLOCK == 0);

// A step's handler: the arithmetic's by opcode, destination and the flags
// it writes, then the stage and mask changes, then the fused pairs.
enum class TraceDest : unsigned { none, reg, cmem, kinds };
constexpr unsigned TRACE_OPCODES = 64;  // the word's 6-bit field
constexpr unsigned TRACE_STAGE = TRACE_OPCODES * static_cast<unsigned>(TraceDest::kinds) * flag_write_kinds;
constexpr unsigned TRACE_MSET = TRACE_STAGE + 1, TRACE_MCLR = TRACE_STAGE + 2, TRACE_MMOV = TRACE_STAGE + 3,
                   TRACE_MAND = TRACE_STAGE + 4, TRACE_MOR = TRACE_STAGE + 5, TRACE_PAIRS = TRACE_STAGE + 6;
// An arithmetic instruction's handler: by opcode, destination and the flags
// it writes (FlagWrites, the lowest digit: handler / flag_write_kinds is the
// instruction's kind whatever it writes).
constexpr unsigned arithmetic_handler(Opcode opcode, TraceDest dest, unsigned writes) {
  return ((static_cast<unsigned>(opcode) & (TRACE_OPCODES - 1)) * static_cast<unsigned>(TraceDest::kinds) +
          static_cast<unsigned>(dest)) *
             flag_write_kinds +
         writes;
}

// Two neighbouring instructions of one byte each that the compiler makes
// one step (one dispatch instead of two): the neighbours most frequent in
// `ap-tile`'s traces (add then adc of a 16-bit sum, shifts in a row, moves
// around them). The step holds the first's operands in a, b, d[0] and the
// second's in a_low, b_low, d[1].
struct FusedPair {
  Opcode first;
  TraceDest first_dest;
  Opcode second;
  TraceDest second_dest;
};
constexpr std::array<FusedPair, 12> FUSED_PAIRS = {{
    {Opcode::op_add, TraceDest::reg, Opcode::op_adc, TraceDest::reg},
    {Opcode::op_shl, TraceDest::reg, Opcode::op_shl, TraceDest::reg},
    {Opcode::op_adc, TraceDest::reg, Opcode::op_add, TraceDest::reg},
    {Opcode::op_mov, TraceDest::cmem, Opcode::op_add, TraceDest::reg},
    {Opcode::op_adc, TraceDest::reg, Opcode::op_mov, TraceDest::reg},
    {Opcode::op_mov, TraceDest::reg, Opcode::op_mov, TraceDest::reg},
    {Opcode::op_shr, TraceDest::reg, Opcode::op_shr, TraceDest::reg},
    {Opcode::op_mov, TraceDest::reg, Opcode::op_shl, TraceDest::reg},
    {Opcode::op_or, TraceDest::reg, Opcode::op_mov, TraceDest::cmem},
    {Opcode::op_mov, TraceDest::cmem, Opcode::op_mov, TraceDest::cmem},
    {Opcode::op_mov, TraceDest::cmem, Opcode::op_mov, TraceDest::reg},
    {Opcode::op_adc, TraceDest::reg, Opcode::op_adc, TraceDest::reg},
}};
// A pair's handlers: one per pair and flags written by each of its two.
constexpr unsigned PAIR_HANDLERS = flag_write_kinds * flag_write_kinds;
constexpr unsigned TRACE_HANDLERS = TRACE_PAIRS + FUSED_PAIRS.size() * PAIR_HANDLERS;
// The pair's handler for two arithmetic handlers, or 0.
constexpr unsigned fused_handler(unsigned first, unsigned second) {
  for (unsigned i = 0; i < FUSED_PAIRS.size(); ++i) {
    const FusedPair& pair = FUSED_PAIRS[i];
    if (first / flag_write_kinds == arithmetic_handler(pair.first, pair.first_dest, 0) / flag_write_kinds &&
        second / flag_write_kinds == arithmetic_handler(pair.second, pair.second_dest, 0) / flag_write_kinds)
      return TRACE_PAIRS + i * PAIR_HANDLERS + first % flag_write_kinds * flag_write_kinds + second % flag_write_kinds;
  }
  return 0;
}

// One block of lanes as a vector of the compiler's (GCC's and Clang's
// vector extension): the block's loops written as vector operations, which
// the compiler does not turn back into lane-by-lane code with overlap
// checks, as it did with the loops of the lane helpers inlined here.
using BlockBytes = uint8_t __attribute__((vector_size(TRACE_BLOCK)));

inline BlockBytes load_block(const uint8_t* p) {
  BlockBytes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store_block(uint8_t* p, BlockBytes v) {
  std::memcpy(p, &v, sizeof v);
}

// store_masked_lanes for one block.
inline void store_masked_block(const uint8_t* value, uint8_t* destination, const uint8_t* mask) {
  const auto keep = reinterpret_cast<BlockBytes>(load_block(mask) != 0);
  store_block(destination, (load_block(value) & keep) | (load_block(destination) & ~keep));
}

using BlockWords = uint32_t __attribute__((vector_size(TRACE_BLOCK)));

// A block's 16 bytes widened to words by interleaving with zeros (what the
// processor's unpack instructions do), four lanes to a vector:
// f(quarter, words) for each quarter of the block.
template <class F>
inline void for_each_widened_quarter(const uint8_t* bytes, F f) {
  using Halves = uint16_t __attribute__((vector_size(TRACE_BLOCK)));
  const BlockBytes values = load_block(bytes), zero_bytes{};
  const Halves zero_halves{};
  const auto low = reinterpret_cast<Halves>(
      __builtin_shufflevector(values, zero_bytes, 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23));
  const auto high = reinterpret_cast<Halves>(
      __builtin_shufflevector(values, zero_bytes, 8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31));
  f(0, reinterpret_cast<BlockWords>(__builtin_shufflevector(low, zero_halves, 0, 8, 1, 9, 2, 10, 3, 11)));
  f(1, reinterpret_cast<BlockWords>(__builtin_shufflevector(low, zero_halves, 4, 12, 5, 13, 6, 14, 7, 15)));
  f(2, reinterpret_cast<BlockWords>(__builtin_shufflevector(high, zero_halves, 0, 8, 1, 9, 2, 10, 3, 11)));
  f(3, reinterpret_cast<BlockWords>(__builtin_shufflevector(high, zero_halves, 4, 12, 5, 13, 6, 14, 7, 15)));
}

// counts[4 quarter .. 4 quarter + 3] += words.
inline void add_quarter(uint32_t* counts, unsigned quarter, BlockWords words) {
  BlockWords sum;
  std::memcpy(&sum, counts + 4 * quarter, sizeof sum);
  sum += words;
  std::memcpy(counts + 4 * quarter, &sum, sizeof sum);
}

// A trace's per-lane counts at a mask or stage change, for one block: the
// lane operations and the CMEM stores since the last change, where the
// lane's mask (0/1 bytes) is set.
inline void count_masked_block(uint32_t operations, uint32_t stores, const uint8_t* m, uint32_t* useful,
                               uint32_t* stored) {
  for_each_widened_quarter(m, [&](unsigned quarter, BlockWords lanes) {
    add_quarter(useful, quarter, -lanes & operations);
    add_quarter(stored, quarter, -lanes & stores);
  });
}

// counts[l] += bytes[l] for one block.
inline void add_bytes_block(const uint8_t* bytes, uint32_t* counts) {
  for_each_widened_quarter(bytes, [&](unsigned quarter, BlockWords values) { add_quarter(counts, quarter, values); });
}

struct TraceRun {
  uint8_t* base;
  size_t lanes, blocked;  // the lanes, and rounded up to TRACE_BLOCK
  uint8_t *c, *z, *s, *m, *out, *high, *middle, *low;
  std::array<uint32_t*, STAGE_COUNT> useful_by_stage, stores_by_stage;
  uint32_t *useful, *stores;  // the current stage's
  // The counts since they were last widened into useful and stores, a byte
  // per lane (CuArray's m_trace_counts), and their sums over the changes:
  // at most COUNT_BYTE_MAX, so that no lane's byte overflows.
  uint8_t *useful_bytes, *stores_bytes;
  uint32_t pending_operations, pending_stores;
};
constexpr uint32_t COUNT_BYTE_MAX = 255;

// The byte counts added to the current stage's counts, and cleared.
void widen_counts(TraceRun& run) {
  if (run.pending_operations == 0 && run.pending_stores == 0) return;
  size_t l = 0;
  for (; l + TRACE_BLOCK <= run.lanes; l += TRACE_BLOCK) {
    add_bytes_block(run.useful_bytes + l, run.useful + l);
    add_bytes_block(run.stores_bytes + l, run.stores + l);
  }
  for (; l < run.lanes; ++l) {
    run.useful[l] += run.useful_bytes[l];
    run.stores[l] += run.stores_bytes[l];
  }
  std::memset(run.useful_bytes, 0, run.blocked);
  std::memset(run.stores_bytes, 0, run.blocked);
  run.pending_operations = run.pending_stores = 0;
}

// The counts per lane since the last change, where the lane's mask is set:
// into the byte counts (a vector operation for 16 lanes) while their sums
// stay within a byte, widened when they would not.
void count_trace_lanes(TraceRun& run, uint32_t operations, uint32_t stores) {
  if (operations == 0 && stores == 0) return;
  if (operations > COUNT_BYTE_MAX - run.pending_operations || stores > COUNT_BYTE_MAX - run.pending_stores) {
    widen_counts(run);
    if (operations > COUNT_BYTE_MAX || stores > COUNT_BYTE_MAX) {
      size_t l = 0;
      for (; l + TRACE_BLOCK <= run.lanes; l += TRACE_BLOCK)
        count_masked_block(operations, stores, run.m + l, run.useful + l, run.stores + l);
      for (; l < run.lanes; ++l) {
        run.useful[l] += operations * run.m[l];
        run.stores[l] += stores * run.m[l];
      }
      return;
    }
  }
  run.pending_operations += operations;
  run.pending_stores += stores;
  const BlockBytes zero{};
  const BlockBytes added_operations = zero + static_cast<uint8_t>(operations);
  const BlockBytes added_stores = zero + static_cast<uint8_t>(stores);
  const uint8_t* const m = run.m;
  uint8_t* const useful = run.useful_bytes;
  uint8_t* const stored = run.stores_bytes;
  for (size_t l = 0; l < run.blocked; l += TRACE_BLOCK) {
    const BlockBytes set = zero - load_block(m + l);  // the 0/1 mask as 0x00/0xff
    store_block(useful + l, load_block(useful + l) + (set & added_operations));
    store_block(stored + l, load_block(stored + l) + (set & added_stores));
  }
}

// One block's result row into its destination: under the mask into CMEM,
// whole into a register's row.
template <TraceDest kDest>
inline void store_result_block(const uint8_t* value, uint8_t* destination, const uint8_t* m) {
  if constexpr (kDest == TraceDest::cmem)
    store_masked_block(value, destination, m);
  else if constexpr (kDest == TraceDest::reg)
    std::memcpy(destination, value, TRACE_BLOCK);
}

// The rows a block's arithmetic reads and writes, and the blocks' end,
// read from the run once per step into locals: a byte stored through a
// row may alias any object as far as the compiler knows, so that it would
// load the run's pointers (and the step's offsets) again after each store.
struct BlockRows {
  uint8_t *base, *m, *out, *high, *middle, *low, *c, *z, *s;
  size_t blocked;
};
inline BlockRows block_rows(const TraceRun& run) {
  return {run.base, run.m, run.out, run.high, run.middle, run.low, run.c, run.z, run.s, run.blocked};
}

// One block of a one-byte instruction: its result into its destination.
template <Opcode kOpcode, TraceDest kDest, unsigned kWrites>
[[gnu::always_inline]] inline void one_byte_block(const BlockRows& r, size_t l, uint32_t a, uint32_t b, uint32_t d) {
  uint8_t* const base = r.base;
  arithmetic_lanes<TRACE_BLOCK, kWrites>(kOpcode, TRACE_BLOCK, base + a + l, base + a + l, base + b + l, base + b + l,
                                         r.m + l, r.out + l, r.high + l, r.middle + l, r.low + l, r.c + l, r.z + l,
                                         r.s + l);
  store_result_block<kDest>(r.out + l, base + d + l, r.m + l);
}

template <unsigned kPairHandler>
void trace_pair(const CuArray::TraceStep& step, TraceRun& run) {
  constexpr FusedPair PAIR = FUSED_PAIRS[kPairHandler / PAIR_HANDLERS];
  constexpr unsigned FIRST_WRITES = kPairHandler % PAIR_HANDLERS / flag_write_kinds,
                     SECOND_WRITES = kPairHandler % flag_write_kinds;
  const BlockRows r = block_rows(run);
  const uint32_t a = step.a, b = step.b, d = step.d[0], a2 = step.a_low, b2 = step.b_low, d2 = step.d[1];
  for (size_t l = 0; l < r.blocked; l += TRACE_BLOCK) {
    one_byte_block<PAIR.first, PAIR.first_dest, FIRST_WRITES>(r, l, a, b, d);
    one_byte_block<PAIR.second, PAIR.second_dest, SECOND_WRITES>(r, l, a2, b2, d2);
  }
}

template <unsigned kOpcode, TraceDest kDest, unsigned kWrites>
void trace_arithmetic(const CuArray::TraceStep& step, TraceRun& run) {
  constexpr auto OPCODE = static_cast<Opcode>(kOpcode);
  const BlockRows r = block_rows(run);
  uint8_t* const base = r.base;
  const uint32_t a = step.a, a_low = step.a_low, b = step.b, b_low = step.b_low;
  const std::array<uint32_t, 3> d = step.d;
  for (size_t l = 0; l < r.blocked; l += TRACE_BLOCK) {
    const unsigned written = arithmetic_lanes<TRACE_BLOCK, kWrites>(
        OPCODE, TRACE_BLOCK, base + a + l, base + a_low + l, base + b + l, base + b_low + l, r.m + l, r.out + l,
        r.high + l, r.middle + l, r.low + l, r.c + l, r.z + l, r.s + l);
    if constexpr (kDest != TraceDest::none) {
      const std::array<const uint8_t*, 3> values = written == 1
                                                       ? std::array<const uint8_t*, 3>{r.out, nullptr, nullptr}
                                                       : std::array<const uint8_t*, 3>{r.high, r.middle, r.low};
      for (unsigned byte = 0; byte < written; ++byte)
        store_result_block<kDest>(values[byte] + l, base + d[byte] + l, r.m + l);
    }
  }
}

void trace_stage(const CuArray::TraceStep& step, TraceRun& run) {
  count_trace_lanes(run, step.operations, step.stores);
  widen_counts(run);
  run.useful = run.useful_by_stage[step.stage];
  run.stores = run.stores_by_stage[step.stage];
}

// condition_lanes for one block.
inline BlockBytes condition_block(Cond cond, const uint8_t* c, const uint8_t* z, const uint8_t* s) {
  const BlockBytes one = load_block(c) * 0 + 1;
  switch (cond) {
    case Cond::c: return load_block(c);
    case Cond::nc: return load_block(c) ^ one;
    case Cond::z: return load_block(z);
    case Cond::nz: return load_block(z) ^ one;
    case Cond::s: return load_block(s);
    case Cond::ns: return load_block(s) ^ one;
    case Cond::hi: return load_block(c) & (load_block(z) ^ one);
    case Cond::ls: return (load_block(c) ^ one) | load_block(z);
  }
  return load_block(c);
}

template <unsigned kHandler>
void trace_mask(const CuArray::TraceStep& step, TraceRun& run) {
  count_trace_lanes(run, step.operations, step.stores);
  const BlockRows r = block_rows(run);
  const auto cond = static_cast<Cond>(step.cond);
  for (size_t l = 0; l < r.blocked; l += TRACE_BLOCK) {
    uint8_t* m = r.m + l;
    if constexpr (kHandler == TRACE_MSET || kHandler == TRACE_MCLR) {
      std::memset(m, kHandler == TRACE_MSET ? 1 : 0, TRACE_BLOCK);
    } else {
      const BlockBytes holds = condition_block(cond, r.c + l, r.z + l, r.s + l);
      if constexpr (kHandler == TRACE_MMOV)
        store_block(m, holds);
      else if constexpr (kHandler == TRACE_MAND)
        store_block(m, load_block(m) & holds);
      else
        store_block(m, load_block(m) | holds);
    }
  }
}

using TraceHandler = void (*)(const CuArray::TraceStep&, TraceRun&);

// The flags as bits of a live set (what a later step may still read).
constexpr unsigned LIVE_C = 1, LIVE_Z = 2, LIVE_S = 4, LIVE_ALL = 7;
// The flags a mask condition reads (condition_block).
constexpr unsigned condition_reads(Cond cond) {
  switch (cond) {
    case Cond::c:
    case Cond::nc: return LIVE_C;
    case Cond::z:
    case Cond::nz: return LIVE_Z;
    case Cond::s:
    case Cond::ns: return LIVE_S;
    case Cond::hi:
    case Cond::ls: return LIVE_C | LIVE_Z;
  }
  return LIVE_ALL;
}
// The flags an instruction's lanes read (arithmetic_lanes): the carry in of
// adc, sbc, cmpc, rol and ror; every flag for an instruction not listed.
constexpr unsigned instruction_reads(Opcode opcode) {
  switch (opcode) {
    case Opcode::op_adc:
    case Opcode::op_sbc:
    case Opcode::op_cmpc:
    case Opcode::op_rol:
    case Opcode::op_ror: return LIVE_C;
    case Opcode::op_nop:
    case Opcode::op_add:
    case Opcode::op_sub:
    case Opcode::op_cmp:
    case Opcode::op_and:
    case Opcode::op_or:
    case Opcode::op_xor:
    case Opcode::op_not:
    case Opcode::op_mov:
    case Opcode::op_shl:
    case Opcode::op_shr:
    case Opcode::op_asr:
    case Opcode::op_mul:
    case Opcode::op_mulm:
    case Opcode::op_getm:
    case Opcode::op_div:
    case Opcode::op_add16:
    case Opcode::op_sub16:
    case Opcode::op_cmp16:
    case Opcode::op_mov16: return 0;
    default: return LIVE_ALL;
  }
}

template <unsigned kHandler>
constexpr TraceHandler trace_handler() {
  constexpr unsigned KINDS = static_cast<unsigned>(TraceDest::kinds);
  if constexpr (kHandler < TRACE_STAGE)
    return &trace_arithmetic<kHandler / flag_write_kinds / KINDS,
                             static_cast<TraceDest>(kHandler / flag_write_kinds % KINDS), kHandler % flag_write_kinds>;
  else if constexpr (kHandler == TRACE_STAGE)
    return &trace_stage;
  else if constexpr (kHandler >= TRACE_PAIRS)
    return &trace_pair<kHandler - TRACE_PAIRS>;
  else
    return &trace_mask<kHandler>;
}

template <unsigned... kHandlers>
constexpr std::array<TraceHandler, sizeof...(kHandlers)> trace_handlers(std::integer_sequence<unsigned, kHandlers...>) {
  return {trace_handler<kHandlers>()...};
}

constexpr std::array<TraceHandler, TRACE_HANDLERS> TRACE_TABLE =
    trace_handlers(std::make_integer_sequence<unsigned, TRACE_HANDLERS>{});

}  // namespace

std::vector<uint8_t> CuArray::live_flag_writes(const std::vector<Instruction>& trace) const {
  // Backwards from the trace's end, where every flag is live (the flags are
  // the lanes' state after the trace): an instruction's flag is live when a
  // later instruction or mask condition reads it before another sets it.
  std::vector<uint8_t> writes(trace.size(), 0);
  unsigned live = LIVE_ALL;
  for (size_t i = trace.size(); i-- > 0;) {
    const Instruction& in = trace[i];
    switch (in.opcode) {
      case Opcode::op_mset:
      case Opcode::op_mclr: continue;
      case Opcode::op_mmov:
      case Opcode::op_mand:
      case Opcode::op_mor: live |= condition_reads(in.cond()); continue;
      default: break;
    }
    const unsigned sets = m_op_lanes[static_cast<unsigned>(in.opcode) & 63u].writes;
    unsigned kept = 0;
    if ((sets & writes_c) != 0) {
      if ((live & LIVE_C) != 0) kept |= writes_c;
      live &= ~LIVE_C;
    }
    if ((sets & writes_zs) != 0) {
      if ((live & (LIVE_Z | LIVE_S)) != 0) kept |= writes_zs;
      live &= ~(LIVE_Z | LIVE_S);
    }
    writes[i] = static_cast<uint8_t>(kept);
    live |= instruction_reads(in.opcode);
  }
  return writes;
}

CuArray::CompiledTrace CuArray::compile_trace(const std::vector<Instruction>& trace) const {
  CompiledTrace compiled;
  compiled.steps.reserve(trace.size());
  const auto offset = [&](unsigned row_index) { return static_cast<uint32_t>(row_offset(row_index)); };
  // A register in its own row (run_trace undoes the renaming).
  const auto operand = [&](const Operand& o, unsigned byte) {
    return o.in_cmem ? offset(o.value + byte) : offset(m_reg_row + o.value + byte);
  };
  const uint32_t unused = offset(m_scratch_row + SCRATCH_NEIGHBOUR);  // a row the arithmetic never writes
  Stage stage = trace.empty() ? Stage{} : trace.front().stage;
  compiled.first_stage = static_cast<uint8_t>(stage);
  uint32_t operations = 0, stores = 0;
  const auto change = [&](unsigned handler) {
    TraceStep step;
    step.handler = static_cast<uint16_t>(handler);
    step.operations = operations;
    step.stores = stores;
    operations = stores = 0;
    return step;
  };
  const std::vector<uint8_t> writes = live_flag_writes(trace);
  for (size_t i = 0; i < trace.size(); ++i) {
    const Instruction& in = trace[i];
    if (in.stage != stage) {
      TraceStep step = change(TRACE_STAGE);
      stage = in.stage;
      step.stage = static_cast<uint8_t>(stage);
      compiled.steps.push_back(step);
    }
    unsigned mask_handler = 0;
    switch (in.opcode) {
      case Opcode::op_mset: mask_handler = TRACE_MSET; break;
      case Opcode::op_mclr: mask_handler = TRACE_MCLR; break;
      case Opcode::op_mmov: mask_handler = TRACE_MMOV; break;
      case Opcode::op_mand: mask_handler = TRACE_MAND; break;
      case Opcode::op_mor: mask_handler = TRACE_MOR; break;
      default: break;
    }
    if (mask_handler != 0) {
      TraceStep step = change(mask_handler);
      step.cond = static_cast<uint8_t>(in.cond());
      compiled.steps.push_back(step);
      continue;
    }
    ++operations;
    const OpLanes& op = m_op_lanes[static_cast<unsigned>(in.opcode) & 63u];
    const TraceDest dest = !op.uses_d ? TraceDest::none : in.d.in_cmem ? TraceDest::cmem : TraceDest::reg;
    TraceStep step;
    step.handler = static_cast<uint16_t>(arithmetic_handler(in.opcode, dest, writes[i]));
    step.a = op.uses_a ? operand(in.a, 0) : unused;
    step.a_low = op.uses_a && op.a_width > 1 ? operand(in.a, 1) : unused;
    step.b = op.uses_b ? operand(in.b, 0) : unused;
    step.b_low = op.uses_b && op.b_width > 1 ? operand(in.b, 1) : unused;
    for (unsigned byte = 0; byte < step.d.size(); ++byte)
      step.d[byte] = op.uses_d && byte < op.d_width ? operand(in.d, byte) : unused;
    if (dest == TraceDest::cmem) stores += op.d_width;
    // Fused with the step before when the two are a pair of FUSED_PAIRS
    // (a stage or mask change between them is a step of its own).
    if (!compiled.steps.empty() && compiled.steps.back().handler < TRACE_STAGE) {
      TraceStep& before = compiled.steps.back();
      if (const unsigned pair = fused_handler(before.handler, step.handler)) {
        before.handler = static_cast<uint16_t>(pair);
        before.a_low = step.a;
        before.b_low = step.b;
        before.d[1] = step.d[0];
        continue;
      }
    }
    compiled.steps.push_back(step);
  }
  compiled.tail_operations = operations;
  compiled.tail_stores = stores;
  compiled.storage_bytes = m_storage.size();
  compiled.stride = m_stride;
  return compiled;
}

void CuArray::unrename_registers() {
  const unsigned registers = m_geometry.registers;
  bool renamed = false;
  for (unsigned r = 0; r < registers; ++r) renamed = renamed || m_reg_rows[r] != m_reg_row + r;
  if (!renamed) return;
  std::vector<uint8_t> values(size_t{registers} * m_stride);
  for (unsigned r = 0; r < registers; ++r) std::memcpy(&values[r * m_stride], row(m_reg_rows[r]), m_stride);
  for (unsigned r = 0; r < m_reg_rows.size(); ++r) m_reg_rows[r] = m_reg_row + r;
  for (unsigned k = 0; k < SCRATCH_ROWS; ++k) m_spare_rows[k] = m_scratch_row + k;
  for (unsigned r = 0; r < registers; ++r) std::memcpy(row(m_reg_row + r), &values[r * m_stride], m_stride);
}

void CuArray::run_trace(const CompiledTrace& trace) {
  run_trace(trace, 0, m_lanes);
}

void CuArray::run_trace(const CompiledTrace& trace, unsigned first_lane, unsigned lanes) {
  if (trace.storage_bytes != m_storage.size() || trace.stride != m_stride)
    throw std::logic_error("CuArray::run_trace: the trace was compiled for an array of another geometry");
  if (first_lane % TRACE_BLOCK != 0 || first_lane > m_lanes || lanes > m_lanes - first_lane)
    throw std::logic_error("CuArray::run_trace: lanes " + std::to_string(first_lane) + " .. " +
                           std::to_string(uint64_t{first_lane} + lanes) + " (exclusive) are no window of the " +
                           std::to_string(m_lanes) + " lanes starting at a multiple of " + std::to_string(TRACE_BLOCK));
  clear_lane_counts();
  unrename_registers();
  // Every row through the window's first lane: the trace's offsets are
  // rows', and a step's lane l is the window's.
  TraceRun run{};
  run.base = m_storage.data() + first_lane;
  run.lanes = lanes;
  run.blocked = (lanes + TRACE_BLOCK - 1) / TRACE_BLOCK * TRACE_BLOCK;
  run.c = row(m_flag_row + flag_c) + first_lane;
  run.z = row(m_flag_row + flag_z) + first_lane;
  run.s = row(m_flag_row + flag_s) + first_lane;
  run.m = row(m_flag_row + flag_m) + first_lane;
  run.out = row(m_scratch_row + SCRATCH_RESULT) + first_lane;
  run.high = row(m_scratch_row + SCRATCH_PRODUCT) + first_lane;
  run.middle = row(m_scratch_row + SCRATCH_PRODUCT + 1) + first_lane;
  run.low = row(m_scratch_row + SCRATCH_PRODUCT + 2) + first_lane;
  for (unsigned stage = 0; stage < STAGE_COUNT; ++stage) {
    run.useful_by_stage[stage] = m_lane_useful[stage].data() + first_lane;
    run.stores_by_stage[stage] = m_lane_stores[stage].data() + first_lane;
  }
  run.useful = run.useful_by_stage[trace.first_stage];
  run.stores = run.stores_by_stage[trace.first_stage];
  m_trace_counts.assign(2 * run.blocked, 0);
  run.useful_bytes = m_trace_counts.data();
  run.stores_bytes = m_trace_counts.data() + run.blocked;
  for (const TraceStep& step : trace.steps) TRACE_TABLE[step.handler](step, run);
  count_trace_lanes(run, trace.tail_operations, trace.tail_stores);
  widen_counts(run);
  m_active_stale = true;
}

}  // namespace tessera::ap
