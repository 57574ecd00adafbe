// The arm renderer's scan conversion of one edge (internal to the renderer;
// the fill rule: arm_rasterizer.h).
#pragma once

#include <cstdint>

#include "renderers/arm/planes.h"

namespace tessera::arm {

// Exact DDA of one edge's crossing with the scanlines: f is the first pixel
// whose centre is at or right of the crossing, ceil((x - 8) / 16) in 9.4
// units, kept as quotient and remainder while stepping down one row.
struct EdgeWalk {
  int32_t f = 0, e = 0, q = 0, r = 0, m = 1;
  int row = 0;

  // Edge from (xt, yt) down to (xb, yb), yt > yb, at scanline j (yb < 16 j + 8
  // <= yt); the bounds are MAX_COORDINATE's.
  void init(int32_t xt, int32_t yt, int32_t xb, int32_t yb, int j) {
    const int32_t d = yt - yb, dx = xb - xt, yc = j * 16 + 8;
    m = 16 * d;
    const int32_t n = (xt - 8) * d + (yt - yc) * dx;
    f = ceil_div(n, m);
    e = f * m - n;
    q = floor_div(16 * dx, m);
    r = 16 * dx - q * m;
    row = j;
  }

  void step() {
    f += q;
    e -= r;
    if (e < 0) {
      ++f;
      e += m;
    }
    --row;
  }
};

}  // namespace tessera::arm
