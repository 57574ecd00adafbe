// What the forward texture mapping tests share: fixed-point matrices from
// doubles, and the bound within which Eq. 6 in fixed point must agree with
// Eq. 3 in double (sw_driver/forward_texture/README.md, "Fixed-point formats
// and their bounds", "Filters and the table").
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "forward_texture/eq3_reference.h"
#include "forward_texture/matrix.h"

namespace tessera::forward_texture::testing {

inline int32_t to_fixed(double value, int fraction_bits) {
  return static_cast<int32_t>(std::lround(std::ldexp(value, fraction_bits)));
}

inline PerspectiveMatrix fixed_matrix(double a, double b, double c, double d, double e, double f, double g, double h,
                                      double i) {
  return {to_fixed(a, 20), to_fixed(b, 20), to_fixed(c, 20), to_fixed(d, 20), to_fixed(e, 20),
          to_fixed(f, 20), to_fixed(g, 30), to_fixed(h, 30), to_fixed(i, 30)};
}

// How far a fixed-point border may be from the exact one: the phase grid's
// rounding (2^-9) plus the border's own error (the division's 2^-16, the
// column pass's rounded coefficients: 2^-10, ColumnPassBordersFollowEq4).
constexpr double BORDER_ERROR = 1.0 / 512 + 1.0 / 1024;
constexpr double TABLE_VALUE_ERROR = 1.0 / 65536;  // half an uq1_15 step
constexpr double PRODUCT_ERROR = 1.0 / 512;        // half a q8_8 step, per scaled difference

// Per pixel: how far Eq. 6 in fixed point may be from Eq. 3 in double on a
// line whose texels are `texels` (exact) give or take `input_error`. Every
// border within F/2 + BORDER_ERROR of the pixel's centre moves H by at most
// max(h) BORDER_ERROR plus the table's rounding, times its difference dC,
// and adds one rounded product; the input's error passes through weights
// that sum to at most 1.
inline std::vector<double> eq6_error_bound(const std::vector<double>& texels, const std::vector<double>& borders,
                                           FilterKind kind, int width, int pixel_count, double input_error) {
  const double per_unit = tessera::test::forward_texture::filter_peak(kind, width) * BORDER_ERROR + TABLE_VALUE_ERROR;
  std::vector<double> bound(static_cast<std::size_t>(pixel_count), input_error);
  for (int p = 0; p < pixel_count; ++p) {
    for (std::size_t t = 0; t < borders.size(); ++t) {
      if (std::abs(borders[t] - (p + 0.5)) >= width / 2.0 + BORDER_ERROR) {
        continue;
      }
      const double previous = t > 0 ? texels[t - 1] : 0.0;
      const double current = t < texels.size() ? texels[t] : 0.0;
      bound[static_cast<std::size_t>(p)] += (std::abs(previous - current) + 2 * input_error) * per_unit + PRODUCT_ERROR;
    }
  }
  return bound;
}

}  // namespace tessera::forward_texture::testing
