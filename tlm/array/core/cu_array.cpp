#include "array/core/cu_array.h"

#include <algorithm>
#include <cstring>

namespace tessera::ap {

namespace {

// Rows are padded to a multiple of this so every row starts aligned for
// the widest vector unit the compiler may use.
constexpr size_t ROW_ALIGN = 64;

// Scratch rows: the result of the instruction before it is stored, the
// neighbour's bytes, and the multiply's three product bytes.
constexpr unsigned SCRATCH_RESULT = 0, SCRATCH_NEIGHBOUR = 1, SCRATCH_PRODUCT = 2, SCRATCH_ROWS = 5;

enum FlagRow : unsigned { flag_c = 0, flag_z = 1, flag_s = 2, flag_m = 3, flag_rows = 4 };

// The lane loops. Each writes the result into `out` (scratch, never an
// operand) and the flags; the caller then stores `out` into the destination.
// Keeping the destination out of these loops lets the compiler vectorise
// them without checking for overlap with the sources.
template <bool kInvert, bool kCarryFromFlag>
void add_lanes(size_t n, const uint8_t* a, const uint8_t* b, bool carry_in, uint8_t* __restrict out,
               uint8_t* __restrict c, uint8_t* __restrict z, uint8_t* __restrict s) {
  for (size_t l = 0; l < n; ++l) {
    const unsigned addend = kInvert ? static_cast<uint8_t>(~b[l]) : b[l];
    const unsigned sum = unsigned{a[l]} + addend + (kCarryFromFlag ? unsigned{c[l]} : unsigned{carry_in});
    const auto value = static_cast<uint8_t>(sum);
    out[l] = value;
    c[l] = static_cast<uint8_t>(sum >> 8);
    z[l] = value == 0 ? 1 : 0;
    s[l] = value >> 7;
  }
}

template <class F>
void logic_lanes(size_t n, const uint8_t* a, const uint8_t* b, uint8_t* __restrict out, uint8_t* __restrict z,
                 uint8_t* __restrict s, F f) {
  for (size_t l = 0; l < n; ++l) {
    const uint8_t value = f(a[l], b[l]);
    out[l] = value;
    z[l] = value == 0 ? 1 : 0;
    s[l] = value >> 7;
  }
}

// F(a, carry) returns the shifted byte; the carry out is bit 7 or bit 0 of a.
template <bool kCarryFromTop, class F>
void shift_lanes(size_t n, const uint8_t* a, uint8_t* __restrict out, uint8_t* __restrict c, uint8_t* __restrict z,
                 uint8_t* __restrict s, F f) {
  for (size_t l = 0; l < n; ++l) {
    const uint8_t value = f(a[l], c[l]);
    out[l] = value;
    c[l] = kCarryFromTop ? static_cast<uint8_t>(a[l] >> 7) : static_cast<uint8_t>(a[l] & 1u);
    z[l] = value == 0 ? 1 : 0;
    s[l] = value >> 7;
  }
}

// cond_holds() of every lane, as 0/1 bytes: one branch-free loop per
// condition.
void condition_lanes(Cond cond, size_t n, const uint8_t* __restrict c, const uint8_t* __restrict z,
                     const uint8_t* __restrict s, uint8_t* __restrict out) {
  switch (cond) {
    case Cond::c: std::memcpy(out, c, n); return;
    case Cond::nc:
      for (size_t l = 0; l < n; ++l) out[l] = c[l] ^ 1u;
      return;
    case Cond::z: std::memcpy(out, z, n); return;
    case Cond::nz:
      for (size_t l = 0; l < n; ++l) out[l] = z[l] ^ 1u;
      return;
    case Cond::s: std::memcpy(out, s, n); return;
    case Cond::ns:
      for (size_t l = 0; l < n; ++l) out[l] = s[l] ^ 1u;
      return;
    case Cond::hi:
      for (size_t l = 0; l < n; ++l) out[l] = c[l] & (z[l] ^ 1u);
      return;
    case Cond::ls:
      for (size_t l = 0; l < n; ++l) out[l] = (c[l] ^ 1u) | z[l];
      return;
  }
}

void store_lanes(size_t n, const uint8_t* __restrict value, uint8_t* __restrict destination,
                 const uint8_t* __restrict mask, bool masked) {
  if (!masked) {
    std::memcpy(destination, value, n);
    return;
  }
  for (size_t l = 0; l < n; ++l) destination[l] = mask[l] != 0 ? value[l] : destination[l];
}

}  // namespace

CuArray::CuArray(const ArrayGeometry& geometry)
    : m_geometry(geometry),
      m_lanes(geometry.lanes()),
      m_stride((geometry.lanes() + ROW_ALIGN - 1) / ROW_ALIGN * ROW_ALIGN),
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
  reset();
}

void CuArray::reset() {
  std::fill(m_storage.begin(), m_storage.end(), 0);
  std::fill_n(row(m_flag_row + flag_m), m_lanes, 1);
  m_active = m_lanes;
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
  count_active();
}

void CuArray::count_active() {
  const uint8_t* m = row(m_flag_row + flag_m);
  unsigned active = 0;
  for (unsigned l = 0; l < m_lanes; ++l) active += m[l];
  m_active = active;
}

uint8_t* CuArray::operand_row(const Operand& operand, unsigned byte, const LoopVariables& loop_variables,
                              unsigned active_loops, std::string& error) {
  if (!operand.in_cmem) return row(m_reg_row + operand.value + byte);
  long address = long{operand.value} + byte;
  if (operand.loop != 0) {
    if (operand.loop > active_loops) {
      error = "operand uses loop variable i" + std::to_string(operand.loop - 1) + " outside its loop";
      return nullptr;
    }
    address += loop_variables[operand.loop - 1];
  }
  if (address < 0 || address >= static_cast<long>(m_geometry.cmem_bytes)) {
    error = "CMEM address " + std::to_string(address) + " is beyond the " + std::to_string(m_geometry.cmem_bytes) +
            " bytes of CMEM";
    return nullptr;
  }
  return row(static_cast<unsigned>(address));
}

std::string CuArray::execute(const Instruction& in, const LoopVariables& loop_variables, unsigned active_loops) {
  const size_t n = m_lanes;
  uint8_t* c = row(m_flag_row + flag_c);
  uint8_t* z = row(m_flag_row + flag_z);
  uint8_t* s = row(m_flag_row + flag_s);
  uint8_t* m = row(m_flag_row + flag_m);
  uint8_t* out = row(m_scratch_row + SCRATCH_RESULT);

  switch (in.opcode) {
    case Opcode::op_mset:
      std::fill_n(m, n, 1);
      m_active = m_lanes;
      return {};
    case Opcode::op_mclr:
      std::fill_n(m, n, 0);
      m_active = 0;
      return {};
    case Opcode::op_mmov:
    case Opcode::op_mand:
    case Opcode::op_mor: {
      uint8_t* holds = row(m_scratch_row + SCRATCH_RESULT);
      condition_lanes(in.cond(), n, c, z, s, holds);
      if (in.opcode == Opcode::op_mmov)
        std::memcpy(m, holds, n);
      else if (in.opcode == Opcode::op_mand)
        for (size_t l = 0; l < n; ++l) m[l] &= holds[l];
      else
        for (size_t l = 0; l < n; ++l) m[l] |= holds[l];
      count_active();
      return {};
    }
    default: break;
  }

  // Resolve every operand row first, so an instruction with a bad address
  // changes nothing.
  std::string error;
  const unsigned d_width = operand_width(in.opcode, 'd'), a_width = operand_width(in.opcode, 'a');
  const OpInfo& info = op_info(in.opcode);
  const bool uses_d = info.operands != OperandPattern::ab;
  const bool uses_b = info.operands == OperandPattern::dab || info.operands == OperandPattern::ab;
  const bool uses_a = info.operands != OperandPattern::d;
  std::array<uint8_t*, 3> d_rows{}, a_rows{};
  uint8_t* b_row = nullptr;
  for (unsigned i = 0; uses_d && i < d_width; ++i)
    if ((d_rows[i] = operand_row(in.d, i, loop_variables, active_loops, error)) == nullptr) return error;
  for (unsigned i = 0; uses_a && i < a_width; ++i)
    if ((a_rows[i] = operand_row(in.a, i, loop_variables, active_loops, error)) == nullptr) return error;
  if (uses_b && (b_row = operand_row(in.b, 0, loop_variables, active_loops, error)) == nullptr) return error;

  m_activity.lane_operations += n;
  m_activity.useful_operations += m_active;
  m_activity.cmem_reads += n * ((in.a.in_cmem && uses_a ? a_width : 0) + (in.b.in_cmem && uses_b ? 1 : 0));
  const bool d_masked = in.d.in_cmem;
  const auto store = [&](const uint8_t* value, uint8_t* destination) {
    store_lanes(n, value, destination, m, d_masked);
    if (d_masked) m_activity.cmem_writes += m_active;
  };

  const uint8_t* a = a_rows[0];
  const uint8_t* b = b_row;
  switch (in.opcode) {
    case Opcode::op_add: add_lanes<false, false>(n, a, b, false, out, c, z, s); break;
    case Opcode::op_adc: add_lanes<false, true>(n, a, b, false, out, c, z, s); break;
    case Opcode::op_sub:
    case Opcode::op_cmp: add_lanes<true, false>(n, a, b, true, out, c, z, s); break;
    case Opcode::op_sbc:
    case Opcode::op_cmpc: add_lanes<true, true>(n, a, b, false, out, c, z, s); break;
    case Opcode::op_and: logic_lanes(n, a, b, out, z, s, [](uint8_t x, uint8_t y) { return x & y; }); break;
    case Opcode::op_or: logic_lanes(n, a, b, out, z, s, [](uint8_t x, uint8_t y) { return x | y; }); break;
    case Opcode::op_xor: logic_lanes(n, a, b, out, z, s, [](uint8_t x, uint8_t y) { return x ^ y; }); break;
    case Opcode::op_not:
      logic_lanes(n, a, a, out, z, s, [](uint8_t x, uint8_t) { return static_cast<uint8_t>(~x); });
      break;
    case Opcode::op_mov: logic_lanes(n, a, a, out, z, s, [](uint8_t x, uint8_t) { return x; }); break;
    case Opcode::op_shl:
      shift_lanes<true>(n, a, out, c, z, s, [](uint8_t x, uint8_t) { return static_cast<uint8_t>(x << 1); });
      break;
    case Opcode::op_shr:
      shift_lanes<false>(n, a, out, c, z, s, [](uint8_t x, uint8_t) { return static_cast<uint8_t>(x >> 1); });
      break;
    case Opcode::op_asr:
      shift_lanes<false>(n, a, out, c, z, s,
                         [](uint8_t x, uint8_t) { return static_cast<uint8_t>((x >> 1) | (x & 0x80u)); });
      break;
    case Opcode::op_rol:
      shift_lanes<true>(n, a, out, c, z, s,
                        [](uint8_t x, uint8_t carry) { return static_cast<uint8_t>((x << 1) | carry); });
      break;
    case Opcode::op_ror:
      shift_lanes<false>(n, a, out, c, z, s,
                         [](uint8_t x, uint8_t carry) { return static_cast<uint8_t>((x >> 1) | (carry << 7)); });
      break;
    case Opcode::op_mul:
    case Opcode::op_mulm: {
      uint8_t* high = row(m_scratch_row + SCRATCH_PRODUCT);
      uint8_t* middle = high + m_stride;
      uint8_t* low = middle + m_stride;
      const uint8_t* a_high = a_rows[0];
      const uint8_t* a_low = a_rows[1];
      for (size_t l = 0; l < n; ++l) {
        const auto multiplicand = static_cast<int16_t>((a_high[l] << 8) | a_low[l]);
        const auto product = static_cast<uint32_t>(int32_t{multiplicand} * int32_t{static_cast<int8_t>(b[l])});
        high[l] = static_cast<uint8_t>(product >> 16);
        middle[l] = static_cast<uint8_t>(product >> 8);
        low[l] = static_cast<uint8_t>(product);
        c[l] = 0;
        z[l] = (product & 0xffffffu) == 0 ? 1 : 0;
        s[l] = static_cast<uint8_t>((product >> 23) & 1u);
      }
      store(high, d_rows[0]);
      store(middle, d_rows[1]);
      store(low, d_rows[2]);
      return {};
    }
    case Opcode::op_nget: {
      const auto direction = static_cast<unsigned>(in.direction());
      uint8_t* neighbour = row(m_scratch_row + SCRATCH_NEIGHBOUR);
      const uint8_t* has = m_has_neighbour[direction].data();
      const uint8_t* source = a + m_neighbour_step[direction];
      for (size_t l = 0; l < n; ++l) neighbour[l] = source[l] & has[l];
      m_activity.neighbour_transfers += m_lanes_with_neighbour[direction];
      store(neighbour, d_rows[0]);
      return {};
    }
    case Opcode::op_getm:
      for (size_t l = 0; l < n; ++l) out[l] = m[l] != 0 ? 0xff : 0;
      break;
    default: return "instruction " + std::string(info.mnemonic) + " does no lane work";
  }
  if (uses_d) store(out, d_rows[0]);
  return {};
}

}  // namespace tessera::ap
