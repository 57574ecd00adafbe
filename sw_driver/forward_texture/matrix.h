// The perspective matrix and the per-line set-up of the two passes (README.md,
// "Coordinates"): for each line, the numerator and denominator of its first
// texel border and their steps per texel, from which the resampler steps
// every border with two 32-bit additions and one fixed-iteration division.
// The set-up multiplies 32-bit entries into overflow-checked 64-bit products;
// it never divides.
#pragma once

#include <string>

#include "forward_texture/fixed_point.h"

namespace tessera::forward_texture {

// (x w, y w, w) = M (u, v, 1): texel (i, j) covers [i, i+1) x [j, j+1), pixel
// (p, q) covers [p, p+1) x [q, q+1).
struct PerspectiveMatrix {
  q12_20 a = 0, b = 0, c = 0;  // x w = A u + B v + C
  q12_20 d = 0, e = 0, f = 0;  // y w = D u + E v + F
  q2_30 g = 0, h = 0, i = 0;   // w = G u + H v + I
};

// Border t of a line is numerator(t) / denominator(t), both linear in t.
struct LineMapping {
  q12_20 numerator = 0;  // at border 0
  q12_20 numerator_step = 0;
  q2_30 denominator = 0;  // at border 0, > 0
  q2_30 denominator_step = 0;
};

// The largest texture and output side.
constexpr int MAX_IMAGE_SIZE = 1024;

// The matrix with u and v swapped (its first two columns): the
// columns-first order is the rows-first order of the transposed texture
// under it.
PerspectiveMatrix with_u_and_v_swapped(const PerspectiveMatrix& m);

// Empty, or the message naming the bad value: a singular matrix (abs(det) <
// 2^-20), a denominator w not positive or not below 2 at a corner of a
// width x height texture, a product out of the set-up's range.
std::string matrix_error(const PerspectiveMatrix& m, int texture_width, int texture_height);

// The row pass (Eq. 1) of texture row `row` (v = row + 1/2): borders at u =
// 0 .. texture_width. Empty, or the message naming what left its format.
std::string row_pass_line(const PerspectiveMatrix& m, int row, int texture_width, LineMapping& line);

// The column pass (Eq. 4) multiplied through by (G x - A): y = (a(x) v +
// b(x)) / (c v + d), coefficients exact at 2^-46; column p is x = p + 1/2.
struct ColumnPassSetup {
  int64_t a0 = 0, a_step = 0;  // a(x) = a0 + x a_step
  int64_t b0 = 0, b_step = 0;
  int64_t c = 0, d = 0;
};
constexpr int COLUMN_COEFFICIENT_BITS = 46;

std::string column_pass_setup(const PerspectiveMatrix& m, ColumnPassSetup& setup);

// The column pass of intermediate column `column`: borders at v = 0 ..
// texture_height, rounded to a q12_20 numerator over a q2_30 denominator
// whose larger end is normalised to [1/2, 1).
std::string column_pass_line(const ColumnPassSetup& setup, int column, int texture_height, LineMapping& line);

}  // namespace tessera::forward_texture
