// The double-precision reference of two-pass forward texture mapping
// (sw_driver/forward_texture/README.md): Eq. 3 evaluated exactly with the
// continuous filter primitive H, the borders by Eq. 1 and by Eq. 4 as the
// paper writes them (with m and n, divisions and all). Verification code
// only: the driver's fixed-point Eq. 6 is checked against it.
#pragma once

#include <vector>

#include "forward_texture/filter.h"
#include "forward_texture/matrix.h"
#include "forward_texture/warp.h"

namespace tessera::test::forward_texture {

using tessera::forward_texture::FilterKind;
using tessera::forward_texture::PassOrder;
using tessera::forward_texture::PerspectiveMatrix;

// The fixed-point matrix's exact value.
struct Matrix {
  double a, b, c, d, e, f, g, h, i;
};
Matrix to_double(const PerspectiveMatrix& m);

// H(z) of `kind` stretched to `width` pixels, and its largest slope max h.
double filter_primitive(FilterKind kind, int width, double z);
double filter_peak(FilterKind kind, int width);

// Eq. 1: the borders x(u = t, v = row + 1/2), t = 0 .. texture_width.
std::vector<double> row_borders(const Matrix& m, int row, int texture_width);
// Eq. 4: the borders y(x = column + 1/2, v = t), t = 0 .. texture_height;
// empty where G x - A = 0.
std::vector<double> column_borders(const Matrix& m, int column, int texture_height);

// Eq. 3: pixel p (centre p + 1/2) of a line of `pixel_count` is the sum over
// the texels of (H(right border - centre) - H(left border - centre)) C_t.
std::vector<double> resample_line_eq3(const std::vector<double>& texels, const std::vector<double>& borders,
                                      FilterKind kind, int width, int pixel_count);

// The two passes in double, in the given order; the intermediate image is
// kept in double. Row-major output_width x output_height, values 0 .. 255.
std::vector<double> warp_eq3(const tessera::forward_texture::Image& texture, const Matrix& m, FilterKind kind,
                             int width, int output_width, int output_height, PassOrder order);

}  // namespace tessera::test::forward_texture
