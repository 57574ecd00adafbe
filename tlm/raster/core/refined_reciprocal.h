// Division in triangle setup and in the per-pixel perspective division: the
// reciprocal unit's seed for the top bits of the normalised divisor, refined
// by two Newton-Raphson steps y <- y (2 - f y) to about 2^-28 whatever the
// method (README.md, "Reciprocal of the area"), and a quotient as one
// multiplication by the refined reciprocal, rounded to nearest, ties up.
#pragma once

#include <cstdint>

#include "raster/datapath/reciprocal.h"

namespace tessera::raster {

__extension__ typedef __int128 int128;

// 1/v = y * 2^-(30 + n), y in Q30.
struct Reciprocal {
  uint64_t y = 0;
  int n = 0;
};

// 1/v for v > 0; false when the unit flags its operand (v = 0).
bool refined_reciprocal(uint64_t v, RecipMethod method, Reciprocal& out);

// numerator / v, with r = 1/v and v's sign given apart, scaled by
// 2^-extra_shift.
int128 divide(int128 numerator, const Reciprocal& r, bool negative_divisor, int extra_shift = 0);

}  // namespace tessera::raster
