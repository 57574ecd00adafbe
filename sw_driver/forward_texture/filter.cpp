// The filter tables (filter.h). With w = (z + F/2) / F the position across
// the support in [0, 1], the box's primitive is H = w and the tent's is
// 2 w^2 below w = 1/2 and 1 - 2 (1 - w)^2 above. A table entry's w is
// N / (PHASES F) with N = phase + PHASES (F - 1 - j), an integer in
// [0, PHASES F], so both are ratios of small integers: N <= 2048, N^2 < 2^22.
#include "forward_texture/filter.h"

namespace tessera::forward_texture {

namespace {

// H at w = n / (PHASES * width), in uq1_15.
uint32_t primitive_at(FilterKind kind, uint32_t n, uint32_t width) {
  const uint32_t span = PHASES * width;  // <= 2048
  if (kind == FilterKind::box) {
    // 2^15 n / (2^8 F) = 2^7 n / F, exact when F divides 2^7 n; rounded otherwise.
    return (n * 128u * 2u + width) / (2u * width);
  }
  // Tent: 2 w^2 = 2 n^2 / span^2, in uq1_15: 2^16 n^2 / (2^16 F^2) = n^2 / F^2.
  const uint32_t square_of_width = width * width;
  if (2u * n <= span) {
    return (n * n * 2u + square_of_width) / (2u * square_of_width);
  }
  const uint32_t rest = span - n;
  return UQ1_15_ONE - (rest * rest * 2u + square_of_width) / (2u * square_of_width);
}

}  // namespace

const char* filter_name(FilterKind kind) {
  return kind == FilterKind::box ? "box" : "tent";
}

std::string filter_width_error(int width) {
  if (width >= 1 && width <= MAX_FILTER_WIDTH) {
    return {};
  }
  return "filter width F = " + std::to_string(width) + " is out of range: the filter table holds widths 1 .. " +
         std::to_string(MAX_FILTER_WIDTH);
}

FilterTable make_filter_table(FilterKind kind, int width) {
  FilterTable table;
  table.kind = kind;
  table.width = width;  // kept when out of range, so that the error can name it
  if (!filter_width_error(width).empty()) {
    return table;
  }
  table.values.resize(static_cast<std::size_t>(PHASES) * width);
  const auto unsigned_width = static_cast<uint32_t>(width);
  for (int phase = 0; phase < PHASES; ++phase) {
    for (int j = 0; j < width; ++j) {
      const auto n = static_cast<uint32_t>(phase + PHASES * (width - 1 - j));
      table.values[static_cast<std::size_t>(phase) * width + j] =
          static_cast<uq1_15>(primitive_at(kind, n, unsigned_width));
    }
  }
  return table;
}

}  // namespace tessera::forward_texture
