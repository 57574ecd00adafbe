// The prefilters h and their primitive H = integral of h, tabulated for the
// Eq. 6 resampler (README.md, "Filters and the table"): a filter of width F
// pixels has PHASES rows, one per border phase in 1/PHASES pixel, each
// holding the F values H(phase + F/2 - 1 - j), j = 0 .. F-1, in uq1_15.
#pragma once

#include <string>
#include <vector>

#include "forward_texture/fixed_point.h"

namespace tessera::forward_texture {

enum class FilterKind { box, tent };

constexpr int PHASE_BITS = 8;
constexpr int PHASES = 1 << PHASE_BITS;
constexpr int MAX_FILTER_WIDTH = 8;

struct FilterTable {
  FilterKind kind = FilterKind::box;
  int width = 0;               // F, in pixels
  std::vector<uq1_15> values;  // PHASES rows of `width` values

  uq1_15 at(int phase, int j) const { return values[static_cast<std::size_t>(phase) * width + j]; }
};

const char* filter_name(FilterKind kind);

// Empty when `width` is a filter width the table holds (1 .. MAX_FILTER_WIDTH),
// else the message naming it.
std::string filter_width_error(int width);

// The table of `kind` stretched to `width` pixels, in integer arithmetic:
// exact for the box, rounded to the nearest uq1_15 for the tent. When
// filter_width_error(width) is not empty the table has no values (and the
// warp refuses it, naming the width).
FilterTable make_filter_table(FilterKind kind, int width);

}  // namespace tessera::forward_texture
