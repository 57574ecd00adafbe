// See traversal.h; the fill rule and the coverage are those of
// raster/datapath/edge_function.h. Each row's edge functions are evaluated
// once at its first pixel and stepped along it (exact: edge_function.h), the
// fill rule decided 64 pixels at a time as bit masks.
#include "raster/core/traversal.h"

#include <algorithm>

#include "raster/datapath/edge_function.h"

namespace tessera::raster {

Rect traversal_box(const TriangleVertices& v, bool smooth, const Rect& tile, const DrawState& state) {
  const uint32_t min_x = std::min({v[0].x, v[1].x, v[2].x}), max_x = std::max({v[0].x, v[1].x, v[2].x});
  const uint32_t min_y = std::min({v[0].y, v[1].y, v[2].y}), max_y = std::max({v[0].y, v[1].y, v[2].y});
  const int margin = smooth ? 1 : 0;
  Rect box{(int(min_x) + 7) / 16 - margin, (int(min_y) + 7) / 16 - margin, (int(max_x) - 8) / 16 + 1 + margin,
           (int(max_y) - 8) / 16 + 1 + margin};
  if (int(max_x) < 8) box.x1 = margin;
  if (int(max_y) < 8) box.y1 = margin;
  box = box.intersect(tile);
  if (state.scissor) box = box.intersect(state.scissor_box);
  return box;
}

namespace {

// With polygon_smooth: every pixel of a row, each edge stepped along it, the
// EASA coverage the minimum of the three; a pixel with coverage 0 makes no
// fragment. Returns the pixels visited (fewer than the row when shading
// fails, counting the pixel that failed).
uint64_t traverse_row_smooth(RunContext& run, const TriangleSetup& setup, const Rect& box, int py,
                             FragmentShader& shader) {
  int64_t value[3], step[3];
  for (unsigned k = 0; k < 3; ++k) {
    value[k] = edge_value_at(setup.edges[k], unsigned(box.x0), unsigned(py)).raw;
    step[k] = 16 * edge_dy(setup.edges[k]).raw;
  }
  for (int px = box.x0; px < box.x1; ++px) {
    unorm8 cover[3];
    for (unsigned k = 0; k < 3; ++k) {
      cover[k] = edge_coverage(edge_normalised_distance(edge_value{value[k]}, setup.edge_recip[k]));
      value[k] += step[k];
    }
    const unorm8 coverage = triangle_coverage(cover[0], cover[1], cover[2]);
    if (coverage.raw == 0) continue;
    ++run.result().fragments;
    shader.shade(setup, px, py, coverage);
    if (run.failed()) return uint64_t(px) - uint64_t(box.x0) + 1;
  }
  return uint64_t(box.x1) - uint64_t(box.x0);
}

// Without: the three edges' fill-rule decisions for up to 64 pixels at a
// time (triangle_inside_row), and a fragment for every pixel inside all three.
uint64_t traverse_row(RunContext& run, const TriangleSetup& setup, const Rect& box, int py, FragmentShader& shader) {
  constexpr unsigned CHUNK = 64;
  const unorm8 full = unorm8::from_raw(255);
  for (int x0 = box.x0; x0 < box.x1; x0 += int(CHUNK)) {
    const unsigned count = std::min(CHUNK, unsigned(box.x1 - x0));
    uint64_t inside =
        triangle_inside_row(setup.edges[0], setup.edges[1], setup.edges[2], unsigned(x0), unsigned(py), count);
    while (inside != 0) {
      const int px = x0 + __builtin_ctzll(inside);
      inside &= inside - 1;
      ++run.result().fragments;
      shader.shade(setup, px, py, full);
      if (run.failed()) return uint64_t(px) - uint64_t(box.x0) + 1;
    }
  }
  return uint64_t(box.x1) - uint64_t(box.x0);
}

}  // namespace

void traverse(RunContext& run, const TriangleSetup& setup, const Rect& box, bool smooth, FragmentShader& shader) {
  uint64_t visited = 0;
  for (int py = box.y1 - 1; py >= box.y0 && !run.failed(); --py) {  // top row first, as memory
    if (box.x0 >= box.x1) continue;
    visited += smooth ? traverse_row_smooth(run, setup, box, py, shader) : traverse_row(run, setup, box, py, shader);
  }
  run.charge(run.result().fragment_cycles, uint64_t{run.costs().fragment} * visited);
}

}  // namespace tessera::raster
