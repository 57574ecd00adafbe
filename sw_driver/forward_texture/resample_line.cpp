// Eq. 6 on one line (resample_line.h). The border position s = x - 1/2 + F/2
// puts pixel p's filter centre at p and the table's window at pixels
// floor(s) - F + 1 .. floor(s); s is rounded to 1/PHASES pixel, whose byte
// of fraction is the table row.
#include "forward_texture/resample_line.h"

#include <vector>

namespace tessera::forward_texture {

namespace {

constexpr q16_16 BORDER_LIMIT = int32_t{1} << 30;  // abs(x) < 2^14 pixels, so s + F/2 stays in q16_16
constexpr q8_8 COLOUR_MAX = 255 << Q8_8_FRACTION_BITS;

// H times dC, rounded to q8_8: abs(dC) <= 255 << 8 < 2^16 and H <= 2^15, so
// the product stays below 2^31.
q8_8 scaled(uq1_15 factor, q8_8 difference) {
  const int32_t product = static_cast<int32_t>(factor) * difference;
  return (product + (int32_t{1} << (UQ1_15_FRACTION_BITS - 1))) >> UQ1_15_FRACTION_BITS;
}

q8_8 clamped(q8_8 value) {
  return value < 0 ? 0 : (value > COLOUR_MAX ? COLOUR_MAX : value);
}

}  // namespace

std::string step_borders(const LineMapping& mapping, int texel_count, const std::string& where, q16_16* borders) {
  q12_20 numerator = mapping.numerator;
  q2_30 denominator = mapping.denominator;
  for (int t = 0; t <= texel_count; ++t) {
    q16_16 border = 0;
    if (!divide_border(numerator, denominator, border) || border <= -BORDER_LIMIT || border >= BORDER_LIMIT) {
      return where + ": border " + std::to_string(t) + " = " + format_fixed(numerator, Q12_20_FRACTION_BITS) + " / " +
             format_fixed(denominator, Q2_30_FRACTION_BITS) +
             " is beyond 16384 pixels or its denominator is not positive";
    }
    borders[t] = border;
    if (t > 0) {
      const int32_t width = border > borders[t - 1] ? border - borders[t - 1] : borders[t - 1] - border;
      if (width > Q16_16_ONE) {
        return where + ": texel " + std::to_string(t - 1) + " spans " + format_fixed(width, Q16_16_FRACTION_BITS) +
               " pixels, more than 1: magnification is not supported; upscale the texture first";
      }
    }
    // Both stay in range up to the last border: the set-up checked the
    // line's ends, and a step past the last could leave int32_t.
    if (t < texel_count) {
      numerator += mapping.numerator_step;
      denominator += mapping.denominator_step;
    }
  }
  return {};
}

void resample_line(LineView texels, const q16_16* borders, const FilterTable& table, LineView pixels) {
  const int n = texels.count;
  const bool reversed = borders[n] < borders[0];
  const int width = table.width;
  // s = x + (F - 1) / 2, then rounded to the table's phase grid.
  const q16_16 offset = (width - 1) * (Q16_16_ONE / 2) + (Q16_16_ONE >> (PHASE_BITS + 1));
  std::vector<q8_8> sums(static_cast<std::size_t>(pixels.count), 0);
  int next_open = 0;  // pixels below it are closed
  q8_8 previous = 0;  // C_{t-1}, 0 before the first texel
  for (int k = 0; k <= n; ++k) {
    const int t = reversed ? n - k : k;  // the k-th border from the left
    // The texel right of border k in left-to-right order, 0 past the end.
    const int texel = reversed ? t - 1 : t;
    const q8_8 current = (k < n) ? texels[texel] : 0;
    const q8_8 difference = previous - current;
    const q16_16 s = borders[t] + offset;
    const int pixel = s >> Q16_16_FRACTION_BITS;  // floor, arithmetic shift
    const int phase = (s >> (Q16_16_FRACTION_BITS - PHASE_BITS)) & (PHASES - 1);
    const int first = pixel - width + 1;
    // Every pixel left of the window has H = 1 from here on: what is still
    // to come adds up to C_{t-1} (the paper's step 6).
    while (next_open < pixels.count && next_open < first) {
      pixels[next_open] = clamped(sums[static_cast<std::size_t>(next_open)] + previous);
      ++next_open;
    }
    for (int j = 0; j < width; ++j) {
      const int p = first + j;
      if (p >= 0 && p < pixels.count) {
        sums[static_cast<std::size_t>(p)] += scaled(table.at(phase, j), difference);
      }
    }
    previous = current;
  }
  for (; next_open < pixels.count; ++next_open) {
    pixels[next_open] = clamped(sums[static_cast<std::size_t>(next_open)]);
  }
}

}  // namespace tessera::forward_texture
