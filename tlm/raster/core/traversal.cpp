// See traversal.h; the fill rule and the coverage are those of
// raster/datapath/edge_function.h.
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

void traverse(RunContext& run, const TriangleSetup& setup, const Rect& box, bool smooth, FragmentShader& shader) {
  uint64_t visited = 0;
  for (int py = box.y1 - 1; py >= box.y0 && !run.failed(); --py) {  // top row first, as memory
    for (int px = box.x0; px < box.x1 && !run.failed(); ++px) {
      ++visited;
      unorm8 coverage = unorm8::from_raw(255);
      bool inside = true;
      unorm8 edge_cov[3];
      for (unsigned k = 0; k < 3; ++k) {
        const EdgeEvaluation e = evaluate_edge(setup.edges[k], unsigned(px), unsigned(py), setup.edge_recip[k]);
        inside = inside && e.inside;
        edge_cov[k] = e.coverage;
      }
      if (smooth) {
        coverage = triangle_coverage(edge_cov[0], edge_cov[1], edge_cov[2]);
        if (coverage.raw == 0) continue;
      } else if (!inside) {
        continue;
      }
      ++run.result().fragments;
      shader.shade(setup, px, py, coverage);
    }
  }
  run.charge(run.result().fragment_cycles, uint64_t{run.costs().fragment} * visited);
}

}  // namespace tessera::raster
