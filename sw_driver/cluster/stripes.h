// The frame buffer's division into p horizontal stripes (README.md, "The
// pipeline"): stripe s covers rows [floor(s H / p), floor((s + 1) H / p)),
// rows counted from the top. Stripes differ in height by at most one row;
// none is empty when H >= p. One 32-bit division per call.
#pragma once

#include <cstdint>

#include "cluster/records.h"
#include "cluster/stripe_layout.h"

namespace tessera::cluster {

struct RowRange {
  unsigned begin = 0, end = 0;  // [begin, end)
};

// Null when 1 <= p <= MAX_NODES and p <= H <= MAX_SCREEN; else what is wrong.
inline const char* stripe_parameters_error(unsigned screen_height, unsigned p) {
  if (p < 1 || p > MAX_NODES) return "nodes: p must be in 1 .. 128";
  if (screen_height < 1 || screen_height > MAX_SCREEN) return "screen_height: must be in 1 .. 512";
  if (screen_height < p) return "nodes: p must not exceed the screen height (a stripe has at least one row)";
  return nullptr;
}

// The platform's rule, which gathers the stripes (contract/cluster/stripe_layout.h).
inline RowRange stripe_rows(unsigned s, unsigned screen_height, unsigned p) {
  return {stripes::first_row(s, screen_height, p), stripes::first_row(s + 1, screen_height, p)};
}

// The s with floor(s H / p) <= y < floor((s + 1) H / p), y < H.
inline unsigned stripe_of_row(unsigned y, unsigned screen_height, unsigned p) {
  return stripes::owner_of_row(y, screen_height, p);
}

}  // namespace tessera::cluster
