// A rectangle of pixels in GL window coordinates (row 0 at the bottom),
// x0 <= x < x1 and y0 <= y < y1: a tile, a scissor box, a traversal box.
#pragma once

#include <algorithm>

namespace tessera::raster {

struct Rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool empty() const { return x0 >= x1 || y0 >= y1; }
  Rect intersect(const Rect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
  bool contains(const Rect& o) const { return o.x0 >= x0 && o.y0 >= y0 && o.x1 <= x1 && o.y1 <= y1; }
};

}  // namespace tessera::raster
