// Unit tests of the edge-function evaluator (tlm/raster/datapath/edge_function.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "raster/datapath/edge_function.h"

namespace tessera::raster {
namespace {

constexpr uint32_t px_code(double pixels) {
  return static_cast<uint32_t>(pixels * 16.0);
}

Edge make_edge(double x0, double y0, double x1, double y1) {
  return Edge{q9_4::from_raw(px_code(x0)), q9_4::from_raw(px_code(y0)), q9_4::from_raw(px_code(x1)),
              q9_4::from_raw(px_code(y1))};
}

struct Point {
  double x, y;
};

// A triangle's three edges, oriented so that the interior has E > 0 (what
// triangle setup does before rasterization).
std::array<Edge, 3> triangle_edges(Point a, Point b, Point c) {
  const double cross = (c.x - a.x) * (b.y - a.y) - (c.y - a.y) * (b.x - a.x);
  if (cross < 0) {
    std::swap(b, c);
  }
  return {make_edge(a.x, a.y, b.x, b.y), make_edge(b.x, b.y, c.x, c.y), make_edge(c.x, c.y, a.x, a.y)};
}

bool covers(const std::array<Edge, 3>& tri, unsigned px, unsigned py) {
  for (const Edge& e : tri) {
    if (!edge_inside(e, edge_value_at(e, px, py))) {
      return false;
    }
  }
  return true;
}

TEST(EdgeFunction, ValueAtPixelCentreByHand) {
  // Edge (1, 2) -> (5, 10): dx = 4, dy = 8. Pixel (3, 4) centre (3.5, 4.5):
  // E = 2.5 * 8 - 2.5 * 4 = 10 pixel^2 = 2560 in q20.8.
  const Edge e = make_edge(1, 2, 5, 10);
  EXPECT_EQ(edge_value_at(e, 3, 4).raw, 2560);
  EXPECT_EQ(edge_dx(e).raw, 64);
  EXPECT_EQ(edge_dy(e).raw, 128);
  EXPECT_EQ(edge_l1_length(e).raw, 192u);
  // Opposite direction negates E.
  EXPECT_EQ(edge_value_at(make_edge(5, 10, 1, 2), 3, 4).raw, -2560);
}

TEST(EdgeFunction, ExtremesDoNotOverflow) {
  // Longest edges with the sample at the far corner: the exact value must
  // come out, computed here in double (exact below 2^53).
  const std::array<uint32_t, 3> coords{0, 1, 8191};
  for (uint32_t x0 : coords)
    for (uint32_t y0 : coords)
      for (uint32_t x1 : coords)
        for (uint32_t y1 : coords)
          for (unsigned p : {0u, 511u, 512u}) {
            const Edge e{q9_4::from_raw(x0), q9_4::from_raw(y0), q9_4::from_raw(x1), q9_4::from_raw(y1)};
            const double sx = 16.0 * p + 8 - x0;
            const double sy = 16.0 * (512 - p) + 8 - y0;
            const double expected = sx * (double(y1) - y0) - sy * (double(x1) - x0);
            EXPECT_EQ(double(edge_value_at(e, p, 512 - p).raw), expected);
          }
}

TEST(EdgeFunction, SteppingEqualsDirectEvaluation) {
  std::mt19937 rng(1234);
  std::uniform_int_distribution<uint32_t> coord(0, 8191);
  std::uniform_int_distribution<unsigned> pixel(0, 511);
  for (int i = 0; i < 2000; ++i) {
    const Edge e{q9_4::from_raw(coord(rng)), q9_4::from_raw(coord(rng)), q9_4::from_raw(coord(rng)),
                 q9_4::from_raw(coord(rng))};
    // Walk a row and a column from a random start, including the step to 512.
    const unsigned py = pixel(rng);
    edge_value v = edge_value_at(e, 0, py);
    for (unsigned px = 0; px < 512; ++px) {
      v = edge_step_x(e, v);
      ASSERT_EQ(v, edge_value_at(e, px + 1, py)) << px;
    }
    const unsigned px = pixel(rng);
    v = edge_value_at(e, px, 0);
    for (unsigned y = 0; y < 512; ++y) {
      v = edge_step_y(e, v);
      ASSERT_EQ(v, edge_value_at(e, px, y + 1)) << y;
    }
    const EdgeEvaluation r = evaluate_edge(e, px, py, q5_16{});
    EXPECT_EQ(r.value_next_x, edge_value_at(e, px + 1, py));
    EXPECT_EQ(r.value_next_y, edge_value_at(e, px, py + 1));
  }
}

// The row masks (the traversal's batch form) against the fill rule decided
// pixel by pixel by direct evaluation: random edges and triangles, random
// rows and spans up to 64 pixels, up to pixel 512.
TEST(EdgeFunction, RowMasksEqualPixelByPixelDecisions) {
  std::mt19937 rng(4321);
  std::uniform_int_distribution<uint32_t> coord(0, 8191);
  std::uniform_int_distribution<unsigned> pixel(0, 511);
  std::uniform_int_distribution<unsigned> span(0, 64);
  const auto random_edge = [&] {
    return Edge{q9_4::from_raw(coord(rng)), q9_4::from_raw(coord(rng)), q9_4::from_raw(coord(rng)),
                q9_4::from_raw(coord(rng))};
  };
  unsigned rows_with_inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Edge e = random_edge();
    const unsigned py = pixel(rng);
    const unsigned px = pixel(rng);
    const unsigned count = std::min(span(rng), 513 - px);
    uint64_t expected = 0;
    for (unsigned k = 0; k < count; ++k)
      if (edge_inside(e, edge_value_at(e, px + k, py))) expected |= uint64_t{1} << k;
    ASSERT_EQ(edge_inside_row(e, px, py, count), expected) << i;

    // A small triangle near the row, so that the runs start and end inside
    // the span; the edges oriented as triangle setup does.
    const double cx = px + 0.37 * count, cy = py + 0.5;
    std::uniform_real_distribution<double> around(-12.0, 12.0);
    const auto clamp = [](double v) { return std::clamp(v, 0.0, 511.0); };
    const auto tri = triangle_edges({clamp(cx + around(rng)), clamp(cy + around(rng))},
                                    {clamp(cx + around(rng)), clamp(cy + around(rng))},
                                    {clamp(cx + around(rng)), clamp(cy + around(rng))});
    uint64_t expected_tri = 0;
    for (unsigned k = 0; k < count; ++k)
      if (covers(tri, px + k, py)) expected_tri |= uint64_t{1} << k;
    ASSERT_EQ(triangle_inside_row(tri[0], tri[1], tri[2], px, py, count), expected_tri) << i;
    rows_with_inside += expected_tri != 0;
  }
  EXPECT_GT(rows_with_inside, 1000u);  // the triangles do cross the rows
}

// The runs found by division (the traversal's form) against the fill rule
// decided pixel by pixel by direct evaluation, and against the walked mask:
// random triangles from slivers to the whole screen (vertices on pixel
// centres and edges through them included), random rows, spans up to the
// screen's 512 pixels.
TEST(EdgeFunction, InsideRunsEqualPixelByPixelDecisions) {
  std::mt19937 rng(8765);
  std::uniform_int_distribution<unsigned> pixel(0, 511);
  std::uniform_int_distribution<unsigned> span(0, 512);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  unsigned rows_with_inside = 0, clipped_both_sides = 0;
  for (int i = 0; i < 40000; ++i) {
    const unsigned py = pixel(rng);
    const unsigned px = pixel(rng);
    const unsigned count = std::min(span(rng), 512 - px);
    // Vertices around the row at a random scale; a quarter on pixel
    // centres (x + 1/2), where E == 0 and the tie-break decides.
    const double scale = std::pow(2.0, 10.0 * unit(rng) - 1.0);
    const double cx = px + unit(rng) * count, cy = py + 0.5;
    const bool on_centres = (i & 3) == 0;
    const auto vertex = [&] {
      double x = std::clamp(cx + scale * (2 * unit(rng) - 1), 0.0, 511.0);
      double y = std::clamp(cy + scale * (2 * unit(rng) - 1), 0.0, 511.0);
      if (on_centres) {
        x = std::floor(x) + 0.5;
        y = std::floor(y) + 0.5;
      }
      return Point{x, y};
    };
    const auto tri = triangle_edges(vertex(), vertex(), vertex());
    int first = -1, last = -1;
    for (unsigned k = 0; k < count; ++k)
      if (covers(tri, px + k, py)) {
        if (first < 0) first = int(k);
        ASSERT_EQ(last, first < int(k) ? int(k) - 1 : -1) << i << ": the inside pixels are not one run";
        last = int(k);
      }
    int64_t biased[3], step[3];
    for (unsigned k = 0; k < 3; ++k) {
      biased[k] = edge_value_at(tri[k], px, py).raw + edge_tie(tri[k]);
      step[k] = 16 * edge_dy(tri[k]).raw;
    }
    const InsideRun run = triangle_inside_run(biased, step, count);
    ASSERT_EQ(run.count, first < 0 ? 0u : unsigned(last - first + 1)) << i;
    if (first >= 0) {
      ASSERT_EQ(run.first, unsigned(first)) << i;
    }
    if (count <= 64) {
      const uint64_t mask = triangle_inside_mask(biased, step, count);
      ASSERT_EQ(mask,
                run.count == 0 ? 0 : ((run.count == 64 ? ~uint64_t{0} : (uint64_t{1} << run.count) - 1)) << run.first)
          << i;
    }
    rows_with_inside += first >= 0;
    clipped_both_sides += first > 0 && last >= 0 && unsigned(last) + 1 < count;
  }
  // The triangles do cross the rows, and often begin and end within them.
  EXPECT_GT(rows_with_inside, 10000u);
  EXPECT_GT(clipped_both_sides, 3000u);
}

TEST(EdgeFunction, TieBreakIsAntisymmetric) {
  // A sample exactly on the edge belongs to exactly one of the two directions.
  const std::vector<std::array<double, 4>> edges{
      {0.5, 0.5, 8.5, 0.5}, {0.5, 0.5, 0.5, 8.5}, {0.5, 0.5, 8.5, 8.5}, {0.5, 8.5, 8.5, 0.5}, {2.5, 0.5, 4.5, 8.5}};
  for (const auto& c : edges) {
    const Edge fwd = make_edge(c[0], c[1], c[2], c[3]);
    const Edge back = make_edge(c[2], c[3], c[0], c[1]);
    // The start vertex is a pixel centre, so that pixel's sample is on the edge.
    const auto px = static_cast<unsigned>(c[0]);
    const auto py = static_cast<unsigned>(c[1]);
    const edge_value vf = edge_value_at(fwd, px, py);
    const edge_value vb = edge_value_at(back, px, py);
    ASSERT_EQ(vf.raw, 0);
    ASSERT_EQ(vb.raw, 0);
    EXPECT_NE(edge_inside(fwd, vf), edge_inside(back, vb));
  }
  // Degenerate edge: never inside.
  const Edge dot = make_edge(3, 3, 3, 3);
  EXPECT_FALSE(edge_inside(dot, edge_value_at(dot, 2, 2)));
}

TEST(EdgeFunction, FillRuleDrawsSharedEdgesOnce) {
  // Fans of triangles around a centre vertex that lies on a pixel centre;
  // the outer vertices also lie on pixel centres, so many pixel centres sit
  // exactly on shared edges and on the shared vertex. Every pixel centre
  // strictly inside the fan's outline must be drawn exactly once, and no
  // pixel may be drawn twice anywhere.
  struct Fan {
    Point centre;
    std::vector<Point> rim;  // convex, in order
  };
  const std::vector<Fan> fans{
      {{16.5, 16.5},
       {{4.5, 4.5}, {16.5, 2.5}, {28.5, 4.5}, {30.5, 16.5}, {28.5, 28.5}, {16.5, 30.5}, {4.5, 28.5}, {2.5, 16.5}}},
      {{8.5, 8.5}, {{0.5, 0.5}, {16.5, 0.5}, {16.5, 16.5}, {0.5, 16.5}}},
      {{13.25, 9.75}, {{1.0, 1.0}, {25.5, 2.5}, {27.0, 19.0}, {3.5, 17.5}}},
  };
  for (const Fan& f : fans) {
    std::vector<std::array<Edge, 3>> tris;
    for (size_t i = 0; i < f.rim.size(); ++i) {
      tris.push_back(triangle_edges(f.centre, f.rim[i], f.rim[(i + 1) % f.rim.size()]));
    }
    // Outline oriented as the triangles are: use its own edges, E > 0 strictly.
    std::vector<Edge> outline;
    for (size_t i = 0; i < f.rim.size(); ++i) {
      const auto& t = tris[i];
      outline.push_back(t[1]);  // the rim edge of triangle (centre, a, b) after orientation
    }
    int on_edges = 0;
    for (unsigned py = 0; py < 40; ++py) {
      for (unsigned px = 0; px < 40; ++px) {
        int count = 0;
        for (const auto& t : tris) {
          count += covers(t, px, py) ? 1 : 0;
        }
        bool strictly_inside = true;
        for (const Edge& e : outline) {
          strictly_inside = strictly_inside && edge_value_at(e, px, py).raw > 0;
        }
        ASSERT_LE(count, 1) << px << "," << py;
        if (strictly_inside) {
          ASSERT_EQ(count, 1) << px << "," << py;
          for (const auto& t : tris) {
            for (const Edge& e : t) {
              on_edges += edge_value_at(e, px, py).raw == 0 ? 1 : 0;
            }
          }
        }
      }
    }
    // The test is only meaningful if samples do fall on shared edges.
    if (f.centre.x == 16.5 || f.centre.x == 8.5) {
      EXPECT_GT(on_edges, 10);
    }
  }
}

TEST(EdgeFunction, InsideAgreesWithGeometryOffTheEdges) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> pos(0.0, 64.0);
  for (int n = 0; n < 200; ++n) {
    const Point a{std::floor(pos(rng) * 16) / 16, std::floor(pos(rng) * 16) / 16};
    const Point b{std::floor(pos(rng) * 16) / 16, std::floor(pos(rng) * 16) / 16};
    const Point c{std::floor(pos(rng) * 16) / 16, std::floor(pos(rng) * 16) / 16};
    const auto tri = triangle_edges(a, b, c);
    const std::array<Point, 3> v{a, b, c};
    for (unsigned py = 0; py < 64; py += 3) {
      for (unsigned px = 0; px < 64; px += 3) {
        const double sx = px + 0.5, sy = py + 0.5;
        std::array<double, 3> s{};
        for (int i = 0; i < 3; ++i) {
          const Point p = v[i], q = v[(i + 1) % 3];
          s[i] = (sx - p.x) * (q.y - p.y) - (sy - p.y) * (q.x - p.x);
        }
        const bool all_pos = s[0] > 0 && s[1] > 0 && s[2] > 0;
        const bool all_neg = s[0] < 0 && s[1] < 0 && s[2] < 0;
        const bool any_zero = s[0] == 0 || s[1] == 0 || s[2] == 0;
        if (!any_zero) {
          EXPECT_EQ(covers(tri, px, py), all_pos || all_neg);
        }
      }
    }
  }
}

TEST(EdgeFunction, DistanceAndCoverageOfAxisAlignedEdge) {
  // Vertical edge x = 0 going up 16 pixels: interior is x > 0 and the L1
  // distance equals the Euclidean one. recip = 1/16 = 4096 in 5.16.
  const Edge e = make_edge(0, 0, 0, 16);
  const q5_16 recip = q5_16::from_raw(4096);
  EXPECT_EQ(edge_l1_length(e).raw, 256u);
  const EdgeEvaluation r = evaluate_edge(e, 2, 5, recip);
  EXPECT_EQ(r.distance.raw, 640);  // 2.5 pixels
  EXPECT_EQ(r.coverage.raw, 255u);
  // Edge at x = 0.25: pixel 0's centre is 0.25 inside: coverage 0.75 -> round(191.25) = 191.
  const Edge e2{q9_4::from_raw(4), q9_4::from_raw(0), q9_4::from_raw(4), q9_4::from_raw(256)};
  const EdgeEvaluation r2 = evaluate_edge(e2, 0, 3, recip);
  EXPECT_EQ(r2.distance.raw, 64);
  EXPECT_EQ(r2.coverage.raw, 191u);
  // Pixel centre on the edge: coverage one half -> round(127.5) = 128 (ties up).
  const Edge e3{q9_4::from_raw(8), q9_4::from_raw(0), q9_4::from_raw(8), q9_4::from_raw(256)};
  EXPECT_EQ(evaluate_edge(e3, 0, 3, recip).coverage.raw, 128u);
  // Outside by 0.5 or more: no coverage.
  EXPECT_EQ(evaluate_edge(e3, 0, 3, recip).distance.raw, 0);
  const Edge e4{q9_4::from_raw(24), q9_4::from_raw(0), q9_4::from_raw(24), q9_4::from_raw(256)};
  EXPECT_EQ(evaluate_edge(e4, 0, 3, recip).distance.raw, -256);
  EXPECT_EQ(evaluate_edge(e4, 0, 3, recip).coverage.raw, 0u);
}

TEST(EdgeFunction, DistanceRoundsAndClamps) {
  // E = 1/256 pixel^2, recip = 0.5: product 2^-9 pixel, exactly half of the
  // distance LSB: ties round up to one LSB; -2^-9 rounds up to 0.
  EXPECT_EQ(edge_normalised_distance(edge_value{1}, q5_16::from_raw(1u << 15)).raw, 1);
  EXPECT_EQ(edge_normalised_distance(edge_value{-1}, q5_16::from_raw(1u << 15)).raw, 0);
  EXPECT_EQ(edge_normalised_distance(edge_value{-3}, q5_16::from_raw(1u << 15)).raw, -1);
  // Huge E with the largest reciprocal saturates both ways.
  EXPECT_EQ(edge_normalised_distance(edge_value{edge_value::MAX_RAW}, q5_16::from_raw(q5_16::MAX_RAW)).raw,
            edge_distance::MAX_RAW);
  EXPECT_EQ(edge_normalised_distance(edge_value{edge_value::MIN_RAW}, q5_16::from_raw(q5_16::MAX_RAW)).raw,
            edge_distance::MIN_RAW);
  EXPECT_EQ(edge_coverage(edge_distance{edge_distance::MAX_RAW}).raw, 255u);
  EXPECT_EQ(edge_coverage(edge_distance{edge_distance::MIN_RAW}).raw, 0u);
}

TEST(EdgeFunction, CoverageIsRoundedExactly) {
  for (int64_t d = -300; d <= 300; ++d) {
    const double c = std::clamp(0.5 + double(d) / 256.0, 0.0, 1.0);
    EXPECT_EQ(edge_coverage(edge_distance{d}).raw, static_cast<uint32_t>(std::floor(c * 255.0 + 0.5))) << d;
  }
}

TEST(EdgeFunction, TriangleCoverageIsTheMinimum) {
  EXPECT_EQ(triangle_coverage(unorm8{200}, unorm8{17}, unorm8{255}).raw, 17u);
  EXPECT_EQ(triangle_coverage(unorm8{255}, unorm8{255}, unorm8{255}).raw, 255u);
}

}  // namespace
}  // namespace tessera::raster
