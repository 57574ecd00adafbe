// See traversal.h; the fill rule and the coverage are those of
// raster/datapath/edge_function.h. Each row's edge functions are evaluated
// once at its first pixel and stepped along it (exact: edge_function.h):
// the fill rule decided 64 pixels at a time as bit masks, the coverage
// with the edge function's batch form.
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

// Fills the batch and shades it whenever it is full. Each fragment is
// counted when its batch is shaded; when a texel fetch fails the run, the
// fragments up to the failing one are counted, and the pixels visited up to
// it (the rows above its own, and its own row up to it).
class Traversal {
 public:
  Traversal(RunContext& run, const TriangleSetup& setup, const Rect& box, FragmentBatch& batch, FragmentShader& shader)
      : m_run(run), m_setup(setup), m_box(box), m_batch(batch), m_shader(shader) {
    m_batch.reset(setup.ref_x, setup.ref_y);
  }

  // Pixels px .. px + count - 1 of row py with their coverage (null: full);
  // false once the run has failed.
  bool add(int px, int py, unsigned count, const uint32_t* coverage) {
    m_run.result().span_pixels.sample(count);
    while (count > 0) {
      if (m_batch.room() == 0 && !flush()) return false;
      const unsigned n = std::min(count, m_batch.room());
      m_batch.add_run(px, py, n, coverage);
      px += static_cast<int>(n);
      count -= n;
      if (coverage != nullptr) coverage += n;
    }
    return true;
  }

  bool flush() {
    if (m_batch.empty()) return true;
    const unsigned done = m_shader.shade(m_setup, m_batch);
    if (done == m_batch.size()) {
      m_run.result().fragments += done;
      m_batch.clear();
      return true;
    }
    m_run.result().fragments += done + 1;
    const auto [px, py] = m_batch.pixel(done);
    m_failed_visits = uint64_t(m_box.y1 - 1 - py) * width() + uint64_t(px - m_box.x0) + 1;
    return false;
  }

  uint64_t width() const { return uint64_t(m_box.x1 - m_box.x0); }
  // Pixels visited: all of the box, or up to the fragment that failed.
  uint64_t visited() const { return m_run.failed() ? m_failed_visits : uint64_t(m_box.y1 - m_box.y0) * width(); }

 private:
  RunContext& m_run;
  const TriangleSetup& m_setup;
  const Rect& m_box;
  FragmentBatch& m_batch;
  FragmentShader& m_shader;
  uint64_t m_failed_visits = 0;
};

// With polygon_smooth: every pixel of a row, each edge's coverage from the
// edge function's batch form, the EASA coverage the minimum of the three;
// the runs of pixels with coverage above 0 are fragments.
bool smooth_row(Traversal& traversal, const TriangleSetup& setup, const Rect& box, int py, ShadingWorkspace& w) {
  const unsigned width = unsigned(box.x1 - box.x0);
  uint32_t* coverage = w.coverage.data();
  std::fill(coverage, coverage + width, 255u);
  for (unsigned k = 0; k < 3; ++k) {
    edge_span(setup.edges[k], unsigned(box.x0), unsigned(py), width, setup.edge_recip[k],
              {w.edge_value.data(), w.edge_value_next_y.data(), w.edge_inside.data(), w.edge_distance.data(),
               w.edge_coverage.data()});
    for (unsigned i = 0; i < width; ++i) coverage[i] = std::min(coverage[i], w.edge_coverage[i]);
  }
  for (unsigned i = 0; i < width;) {
    if (coverage[i] == 0) {
      ++i;
      continue;
    }
    unsigned end = i + 1;
    while (end < width && coverage[end] != 0) ++end;
    if (!traversal.add(box.x0 + int(i), py, end - i, coverage + i)) return false;
    i = end;
  }
  return true;
}

// Without: the run of pixels inside all three edges by the fill rule
// (triangle_inside_run), the edges' biased values at the row's first pixel
// stepped from row to row (exact, edge_function.h).
class FillRows {
 public:
  FillRows(const TriangleSetup& setup, const Rect& box) {
    for (unsigned k = 0; k < 3; ++k) {
      const Edge& e = setup.edges[k];
      m_biased[k] = edge_value_at(e, unsigned(box.x0), unsigned(box.y1 - 1)).raw + edge_tie(e);
      m_step[k] = 16 * edge_dy(e).raw;
      m_row_step[k] = 16 * edge_dx(e).raw;  // E(x, y - 1) = E(x, y) + 16 dx
    }
  }

  // The row at the current values, then the values of the row below.
  bool row(Traversal& traversal, const Rect& box, int py) {
    const InsideRun run = triangle_inside_run(m_biased, m_step, unsigned(box.x1 - box.x0));
    for (unsigned k = 0; k < 3; ++k) m_biased[k] += m_row_step[k];
    return run.count == 0 || traversal.add(box.x0 + int(run.first), py, run.count, nullptr);
  }

 private:
  int64_t m_biased[3], m_step[3], m_row_step[3];
};

}  // namespace

void traverse(RunContext& run, const TriangleSetup& setup, const Rect& box, bool smooth, ShadingWorkspace& work,
              FragmentShader& shader) {
  Traversal traversal(run, setup, box, work.batch, shader);
  FillRows fill(setup, box);
  bool going = true;
  for (int py = box.y1 - 1; py >= box.y0 && going; --py)  // top row first, as memory
    going = smooth ? smooth_row(traversal, setup, box, py, work) : fill.row(traversal, box, py);
  if (going) traversal.flush();
  run.charge(run.result().fragment_cycles, uint64_t{run.costs().fragment} * traversal.visited());
}

}  // namespace tessera::raster
