// The matrix checks and the per-line set-up of the two passes (matrix.h).
// Products of two entries are formed in int64_t (32 x 32 bits, one SMULL on
// the ARM922T) and brought to a common scale by shifts; every operation that
// could leave int64_t is checked, so a matrix beyond the formats' range is an
// error, never a wrapped value.
#include "forward_texture/matrix.h"

namespace tessera::forward_texture {

namespace {

// Round-half-up shift right (an arithmetic shift: floor for negatives too).
int64_t shift_right_rounded(int64_t value, int shift) {
  if (shift <= 0) {
    return value;
  }
  return (value + (int64_t{1} << (shift - 1))) >> shift;
}

bool multiply(int64_t x, int64_t y, int64_t& product) {
  return !__builtin_mul_overflow(x, y, &product);
}
bool add(int64_t x, int64_t y, int64_t& sum) {
  return !__builtin_add_overflow(x, y, &sum);
}

// x * y (raw values with x_bits and y_bits fraction bits) at 2^-COLUMN_COEFFICIENT_BITS.
bool product_at_coefficient_scale(int32_t x, int x_bits, int32_t y, int y_bits, int64_t& product) {
  const int64_t raw = int64_t{x} * int64_t{y};  // abs < 2^62
  const int bits = x_bits + y_bits;
  if (bits >= COLUMN_COEFFICIENT_BITS) {
    product = shift_right_rounded(raw, bits - COLUMN_COEFFICIENT_BITS);
    return true;
  }
  return multiply(raw, int64_t{1} << (COLUMN_COEFFICIENT_BITS - bits), product);
}

// x1 * y1 - x2 * y2 at the coefficient scale.
bool difference_of_products(int32_t x1, int x1_bits, int32_t y1, int y1_bits, int32_t x2, int x2_bits, int32_t y2,
                            int y2_bits, int64_t& difference) {
  int64_t first = 0;
  int64_t second = 0;
  return product_at_coefficient_scale(x1, x1_bits, y1, y1_bits, first) &&
         product_at_coefficient_scale(x2, x2_bits, y2, y2_bits, second) && add(first, -second, difference);
}

bool fits_int32(int64_t value) {
  return value >= INT32_MIN && value <= INT32_MAX;
}

std::string corner_name(int u, int v) {
  return "(u, v) = (" + std::to_string(u) + ", " + std::to_string(v) + ")";
}

constexpr int XY = Q12_20_FRACTION_BITS;
constexpr int W = Q2_30_FRACTION_BITS;

}  // namespace

PerspectiveMatrix with_u_and_v_swapped(const PerspectiveMatrix& m) {
  return {m.b, m.a, m.c, m.e, m.d, m.f, m.h, m.g, m.i};
}

std::string matrix_error(const PerspectiveMatrix& m, int texture_width, int texture_height) {
  // det = A (E I - F H) - B (D I - F G) + C (D H - E G); the cofactors at
  // 2^-46, brought to 2^-26 so that a product with a q12_20 entry is at 2^-46.
  int64_t cofactor_a = 0;
  int64_t cofactor_b = 0;
  int64_t cofactor_c = 0;
  int64_t terms[3] = {};
  int64_t det = 0;
  const bool in_range = difference_of_products(m.e, XY, m.i, W, m.f, XY, m.h, W, cofactor_a) &&
                        difference_of_products(m.d, XY, m.i, W, m.f, XY, m.g, W, cofactor_b) &&
                        difference_of_products(m.d, XY, m.h, W, m.e, XY, m.g, W, cofactor_c) &&
                        multiply(m.a, shift_right_rounded(cofactor_a, 20), terms[0]) &&
                        multiply(m.b, shift_right_rounded(cofactor_b, 20), terms[1]) &&
                        multiply(m.c, shift_right_rounded(cofactor_c, 20), terms[2]) && add(terms[0], -terms[1], det) &&
                        add(det, terms[2], det);
  if (!in_range) {
    return "matrix out of the fixed-point range: a 2 x 2 minor or the determinant overflows 64 bits";
  }
  const int64_t singular_below = int64_t{1} << (COLUMN_COEFFICIENT_BITS - 20);
  if (det > -singular_below && det < singular_below) {
    return "singular matrix: determinant " + format_fixed(det, COLUMN_COEFFICIENT_BITS) +
           " (its magnitude must be at least 2^-20)";
  }
  for (const int v : {0, texture_height}) {
    for (const int u : {0, texture_width}) {
      const int64_t w = int64_t{m.i} + int64_t{m.g} * u + int64_t{m.h} * v;  // abs < 2^31 (1 + 2^11)
      if (w <= 0) {
        return "denominator w = " + format_fixed(w, W) + " at texture corner " + corner_name(u, v) +
               " is not positive: the texture reaches behind the eye";
      }
      if (w >= (int64_t{1} << W) * 2) {
        return "denominator w = " + format_fixed(w, W) + " at texture corner " + corner_name(u, v) +
               " is not below 2, the range of q2_30: scale the matrix down";
      }
    }
  }
  return {};
}

std::string row_pass_line(const PerspectiveMatrix& m, int row, int texture_width, LineMapping& line) {
  // v = row + 1/2: B (2 row + 1) / 2, rounded; |B| < 2^31, 2 row + 1 < 2^11.
  const int64_t twice_v = 2 * int64_t{row} + 1;
  const int64_t numerator = m.c + shift_right_rounded(int64_t{m.b} * twice_v, 1);
  const int64_t denominator = m.i + shift_right_rounded(int64_t{m.h} * twice_v, 1);
  const int64_t numerator_end = numerator + int64_t{m.a} * texture_width;
  const int64_t denominator_end = denominator + int64_t{m.g} * texture_width;
  if (!fits_int32(numerator) || !fits_int32(numerator_end)) {
    return "row pass, row " + std::to_string(row) +
           ": numerator x w = " + format_fixed(fits_int32(numerator) ? numerator_end : numerator, XY) +
           " leaves q12_20 (abs below 2048): the texture maps too far from the origin";
  }
  if (!fits_int32(denominator) || !fits_int32(denominator_end)) {
    return "row pass, row " + std::to_string(row) + ": denominator w leaves q2_30";
  }
  line.numerator = static_cast<q12_20>(numerator);
  line.numerator_step = m.a;
  line.denominator = static_cast<q2_30>(denominator);
  line.denominator_step = m.g;
  return {};
}

std::string column_pass_setup(const PerspectiveMatrix& m, ColumnPassSetup& setup) {
  const bool in_range = difference_of_products(m.d, XY, m.b, XY, m.a, XY, m.e, XY, setup.a0) &&
                        difference_of_products(m.e, XY, m.g, W, m.d, XY, m.h, W, setup.a_step) &&
                        difference_of_products(m.d, XY, m.c, XY, m.a, XY, m.f, XY, setup.b0) &&
                        difference_of_products(m.f, XY, m.g, W, m.d, XY, m.i, W, setup.b_step) &&
                        difference_of_products(m.g, W, m.b, XY, m.a, XY, m.h, W, setup.c) &&
                        difference_of_products(m.g, W, m.c, XY, m.a, XY, m.i, W, setup.d);
  if (!in_range) {
    return "matrix out of the fixed-point range: a column pass coefficient overflows 64 bits";
  }
  return {};
}

std::string column_pass_line(const ColumnPassSetup& setup, int column, int texture_height, LineMapping& line) {
  const std::string where = "column pass, column " + std::to_string(column) + ": ";
  // x = column + 1/2: a(x) = a0 + a_step (2 column + 1) / 2, likewise b.
  const int64_t twice_x = 2 * int64_t{column} + 1;
  int64_t a = 0;
  int64_t b = 0;
  int64_t c_end = 0;
  int64_t a_end = 0;
  if (!multiply(setup.a_step, twice_x, a) || !add(setup.a0, shift_right_rounded(a, 1), a) ||
      !multiply(setup.b_step, twice_x, b) || !add(setup.b0, shift_right_rounded(b, 1), b) ||
      !multiply(setup.c, texture_height, c_end) || !multiply(a, texture_height, a_end)) {
    return where + "a coefficient overflows 64 bits";
  }
  int64_t q_start = setup.d;
  int64_t q_end = 0;
  int64_t p_end = 0;
  int64_t c = setup.c;
  if (!add(setup.d, c_end, q_end) || !add(b, a_end, p_end)) {
    return where + "a coefficient overflows 64 bits";
  }
  if (q_start == 0 || q_end == 0 || (q_start < 0) != (q_end < 0)) {
    return where + "the denominator (G B - A H) v + (G C - A I) goes from " +
           format_fixed(q_start, COLUMN_COEFFICIENT_BITS) + " to " + format_fixed(q_end, COLUMN_COEFFICIENT_BITS) +
           ": the row pass collapses a row (the other pass order avoids it)";
  }
  if (q_start < 0) {
    q_start = -q_start;
    q_end = -q_end;
    c = -c;
    a = -a;
    b = -b;
    p_end = -p_end;
  }
  // The shift that brings the larger end of q to [2^29, 2^30) (q2_30 in [1/2, 1)).
  const int64_t larger = q_start > q_end ? q_start : q_end;
  int shift = 0;
  while ((larger >> shift) >= (int64_t{1} << 30)) {
    ++shift;
  }
  if ((larger >> shift) < (int64_t{1} << 29)) {
    return where + "the denominator's larger end " + format_fixed(larger, COLUMN_COEFFICIENT_BITS) +
           " is below 2^-17: the matrix is nearly singular";
  }
  // The numerator keeps 10 fraction bits fewer (q12_20 over q2_30).
  const int numerator_shift = shift + Q2_30_FRACTION_BITS - Q12_20_FRACTION_BITS;
  const int64_t numerator = shift_right_rounded(b, numerator_shift);
  const int64_t numerator_end = shift_right_rounded(p_end, numerator_shift);
  if (!fits_int32(numerator) || !fits_int32(numerator_end)) {
    return where + "numerator y w leaves q12_20 (abs below 2048): the texture maps too far from the origin";
  }
  const int64_t numerator_step = shift_right_rounded(a, numerator_shift);
  if (!fits_int32(numerator_step)) {
    return where + "numerator step leaves q12_20";
  }
  line.numerator = static_cast<q12_20>(numerator);
  line.numerator_step = static_cast<q12_20>(numerator_step);
  line.denominator = static_cast<q2_30>(shift_right_rounded(q_start, shift));
  line.denominator_step = static_cast<q2_30>(shift_right_rounded(c, shift));
  return {};
}

}  // namespace tessera::forward_texture
