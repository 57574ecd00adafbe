// Eq. 6 on one line (README.md, "Eq. 6 on one line"): the borders stepped
// from a LineMapping, F table lookups and F scalings per border, a pixel
// closed once the borders have passed its filter. 32-bit arithmetic only.
#pragma once

#include <string>

#include "forward_texture/filter.h"
#include "forward_texture/fixed_point.h"
#include "forward_texture/matrix.h"

namespace tessera::forward_texture {

// A strided view of a line of q8_8 values (a row: stride 1; a column:
// stride = the image's width).
struct LineView {
  q8_8* values = nullptr;
  int count = 0;
  int stride = 1;
  q8_8& operator[](int index) const { return values[static_cast<std::ptrdiff_t>(index) * stride]; }
};

// The borders of `texel_count` texels (texel_count + 1 values, q16_16
// pixels) of `mapping`. Empty, or the message naming the border that does
// not fit (abs(x) must stay below 2^14 pixels) or the texel wider than one
// pixel (magnification). `where` starts each message ("row pass, row 3").
std::string step_borders(const LineMapping& mapping, int texel_count, const std::string& where, q16_16* borders);

// Resamples `texels` (0 .. 255 << 8) into `pixels` by Eq. 6 with `table`,
// the borders given (step_borders; increasing or decreasing). Pixels no
// texel reaches are 0; results are clamped to 0 .. 255 << 8.
void resample_line(LineView texels, const q16_16* borders, const FilterTable& table, LineView pixels);

}  // namespace tessera::forward_texture
