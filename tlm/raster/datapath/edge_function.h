// Edge-function evaluator of the rasterizer (Pineda edge functions, EASA
// normalised distance for antialiasing coverage).
//
// Sources: J. Pineda, "A Parallel Algorithm for Polygon Rasterization",
// SIGGRAPH '88; A. Schilling, "A New Simple and Efficient Antialiasing with
// Subpixel Masks", SIGGRAPH '91 (EASA); Crisu et al., "Design Tradeoffs for
// an Embedded OpenGL-Compliant Hardware Rasterizer", equation (1).
//
// Edge function. An edge runs from (x0, y0) to (x1, y1), all unsigned 9.4.
// With dx = x1 - x0 and dy = y1 - y0 (signed 14-bit, 4 fraction bits)
//     E(x, y) = (x - x0) * dy - (y - y0) * dx
// evaluated at the pixel centre x = px + 1/2, y = py + 1/2 (9.4 code
// 16 * px + 8). E is exact: a signed 29-bit integer with 8 fraction bits
// (edge_value, q20.8). Bound: |x - x0| <= 8200 codes for px <= 512 and
// |dy| <= 8191, so |E| <= 2 * 8200 * 8191 < 2^28.
//
// Stepping. E(x + 1, y) = E + 16 * dy and E(x, y + 1) = E - 16 * dx, exactly
// equal to direct evaluation because nothing is rounded (the domain of px and
// py is 0..512, so the step from the last pixel of a 511-wide screen is in
// range too).
//
// Inside test and fill rule. The triangle's interior is the side where E > 0
// for all three edges (triangle setup orients the edges so; Crisu Fig. 3:
// the right side of each oriented edge in GL's y-up window coordinates).
// A sample with E == 0 lies on the edge and belongs to it only if
//     dy > 0, or dy == 0 and dx < 0.
// The rule is antisymmetric: the same edge walked the other way by the
// neighbouring triangle has (-dx, -dy) and takes the sample only when this one
// does not, so a shared edge's samples are drawn exactly once (OpenGL 1.2
// "Basic Polygon Rasterization"). In y-down tile/memory order this is the usual top-left rule.
// A degenerate edge (dx = dy = 0) has E == 0 everywhere and is never inside.
//
// Speed. Every function here is inline and allocation-free, and the fill
// rule is one comparison: E == 0 counts as inside exactly when the tie-break
// holds, so inside = E + tie > 0 with tie = 1 or 0 (E is an integer code).
// edge_inside_row steps E along a row of up to 64 pixels and returns the
// decisions as a bit mask; triangle_inside_mask does it for the three edges
// of a triangle at once, and triangle_inside_run finds the same run by
// division, what the core's traversal takes per row. The batch form
// (edge_span, batch.h) gives everything evaluate_edge does along a row.
//
// Normalised distance (EASA, L1 norm): d = E / (|dx| + |dy|). |dx| + |dy| is
// unsigned 10.4 (edge_l1_length, at most 16382 codes, the reciprocal unit's
// input); its reciprocal arrives as unsigned 5.16 (`recip`). The product
// E * recip is signed with 24 fraction bits; it is rounded to 8 fraction bits
// to nearest, ties towards +infinity ((p + 2^15) >> 16, arithmetic shift),
// then clamped to signed 16-bit q7.8 (edge_distance, -128 .. 128 - 2^-8 pixel).
//
// Coverage (0.8) of one edge: c = clamp(1/2 + d, 0, 1), as unorm8
// round(c * 255) with ties up: t = clamp(d_code + 128, 0, 256),
// coverage = (255 * t + 128) >> 8. A pixel's antialiasing coverage is the
// minimum over the three edges (triangle_coverage); the L1 distance is what
// Schilling's EASA uses as the area estimate.
#pragma once

#include <algorithm>
#include <cstdint>

#include "batch.h"
#include "fixed_point.h"

namespace tessera::raster {

using edge_value = SFixed<29, 8>;     // E, pixel^2, q20.8
using edge_delta = SFixed<14, 4>;     // dx or dy of an edge, q9.4 signed
using edge_distance = SFixed<16, 8>;  // normalised distance, pixel, q7.8

struct Edge {
  q9_4 x0, y0, x1, y1;
};

struct EdgeEvaluation {
  edge_value value;         // E at (px + 1/2, py + 1/2)
  edge_value value_next_x;  // E at (px + 3/2, py + 1/2), by adding 16 * dy
  edge_value value_next_y;  // E at (px + 1/2, py + 3/2), by subtracting 16 * dx
  bool inside;              // fill-rule decision at (px, py)
  q10_4 l1_length;          // |dx| + |dy|, input of the reciprocal unit
  edge_distance distance;   // E * recip, rounded and clamped
  unorm8 coverage;          // clamp(1/2 + distance), 0.8
};

// The 9.4 code of the centre of pixel p.
constexpr int64_t edge_pixel_centre(unsigned p) {
  return int64_t{16} * p + 8;
}

constexpr edge_delta edge_dx(const Edge& e) {
  return edge_delta::from_raw(int64_t{e.x1.raw} - e.x0.raw);
}

constexpr edge_delta edge_dy(const Edge& e) {
  return edge_delta::from_raw(int64_t{e.y1.raw} - e.y0.raw);
}

constexpr q10_4 edge_l1_length(const Edge& e) {
  const int64_t dx = edge_dx(e).raw;
  const int64_t dy = edge_dy(e).raw;
  return q10_4::from_raw(static_cast<uint32_t>((dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy)));
}

// Direct evaluation at the centre of pixel (px, py), px and py in 0..512.
constexpr edge_value edge_value_at(const Edge& e, unsigned px, unsigned py) {
  const int64_t rel_x = edge_pixel_centre(px) - e.x0.raw;
  const int64_t rel_y = edge_pixel_centre(py) - e.y0.raw;
  return edge_value::from_raw(rel_x * edge_dy(e).raw - rel_y * edge_dx(e).raw);
}

constexpr edge_value edge_step_x(const Edge& e, edge_value value) {
  return edge_value::from_raw(value.raw + 16 * edge_dy(e).raw);
}

constexpr edge_value edge_step_y(const Edge& e, edge_value value) {
  return edge_value::from_raw(value.raw - 16 * edge_dx(e).raw);
}

// The fill rule's tie-break as 1 (a sample on the edge belongs to it: dy > 0,
// or dy == 0 and dx < 0) or 0.
constexpr int64_t edge_tie(const Edge& e) {
  const int64_t dx = edge_dx(e).raw;
  const int64_t dy = edge_dy(e).raw;
  return int64_t{dy > 0} | (int64_t{dy == 0} & int64_t{dx < 0});
}

constexpr bool edge_inside(const Edge& e, edge_value value) {
  return value.raw + edge_tie(e) > 0;
}

// The fill-rule decisions of `count` pixels of a row, (px + i, py) for i in
// 0..count-1, as bit i of the result; count in 0..64 and px + count <= 513.
// E is evaluated once and stepped, which is exact (see above).
constexpr uint64_t edge_inside_row(const Edge& e, unsigned px, unsigned py, unsigned count) {
  const int64_t step = 16 * edge_dy(e).raw;
  int64_t biased = edge_value_at(e, px, py).raw + edge_tie(e);
  uint64_t mask = 0;
  for (unsigned i = 0; i < count; ++i) {
    mask |= uint64_t{biased > 0} << i;
    biased += step;
  }
  return mask;
}

// The same for the three edges of a triangle at once, from each edge's
// biased value E + tie at the row's first pixel and its step 16 dy: bit i
// is set when pixel i is inside all three. The inside pixels of a row form
// one run (the triangle is convex), so the walk stops at the first pixel
// outside after an inside one. A traversal steps the biased values from
// row to row itself (E(x, y - 1) = E + 16 dx), without a multiplication.
constexpr uint64_t triangle_inside_mask(const int64_t (&biased)[3], const int64_t (&step)[3], unsigned count) {
  int64_t b0 = biased[0], b1 = biased[1], b2 = biased[2];
  uint64_t mask = 0;
  for (unsigned i = 0; i < count; ++i) {
    const bool inside = (b0 > 0) & (b1 > 0) & (b2 > 0);
    if (!inside && mask != 0) break;
    mask |= uint64_t{inside} << i;
    b0 += step[0];
    b1 += step[1];
    b2 += step[2];
  }
  return mask;
}

// The same run found without walking it: each edge's inside pixels
// b + i s > 0 (b its biased value at pixel 0, s its step) are a half-line
// of i, found by one exact integer division where b and s have opposite
// signs, and the run is the intersection of the three with 0..count-1.
// Bit for bit the run of triangle_inside_mask (test_raster_edge_function
// compares them), at a cost that does not grow with the row's width.
struct InsideRun {
  unsigned first = 0, count = 0;  // count 0: no pixel inside
};

constexpr InsideRun triangle_inside_run(const int64_t (&biased)[3], const int64_t (&step)[3], unsigned count) {
  int64_t lo = 0, hi = int64_t{count} - 1;
  for (unsigned k = 0; k < 3; ++k) {
    const int64_t b = biased[k], s = step[k];
    if (s > 0) {
      if (b <= 0) lo = std::max(lo, -b / s + 1);  // the first i with b + i s > 0
    } else if (s < 0) {
      hi = b > 0 ? std::min(hi, (b - 1) / -s) : -1;  // the last i with b + i s > 0
    } else if (b <= 0) {
      hi = -1;  // parallel to the row and outside
    }
  }
  return lo <= hi ? InsideRun{unsigned(lo), unsigned(hi - lo + 1)} : InsideRun{};
}

// triangle_inside_mask of pixels (px + i, py), i in 0..count-1.
constexpr uint64_t triangle_inside_row(const Edge& e0, const Edge& e1, const Edge& e2, unsigned px, unsigned py,
                                       unsigned count) {
  const int64_t biased[3] = {edge_value_at(e0, px, py).raw + edge_tie(e0), edge_value_at(e1, px, py).raw + edge_tie(e1),
                             edge_value_at(e2, px, py).raw + edge_tie(e2)};
  const int64_t step[3] = {16 * edge_dy(e0).raw, 16 * edge_dy(e1).raw, 16 * edge_dy(e2).raw};
  return triangle_inside_mask(biased, step, count);
}

constexpr edge_distance edge_normalised_distance(edge_value value, q5_16 recip) {
  const int64_t product = value.raw * static_cast<int64_t>(recip.raw);
  const int64_t rounded = round_shift_right(product, 16);
  return edge_distance{clamp_i64(rounded, edge_distance::MIN_RAW, edge_distance::MAX_RAW)};
}

constexpr unorm8 edge_coverage(edge_distance distance) {
  const int64_t t = clamp_i64(distance.raw + 128, 0, 256);
  return unorm8::from_raw(static_cast<uint32_t>((255 * t + 128) >> 8));
}

constexpr unorm8 triangle_coverage(unorm8 c0, unorm8 c1, unorm8 c2) {
  return unorm8{std::min(c0.raw, std::min(c1.raw, c2.raw))};
}

// Everything the Verilog unit edge_function.sv computes, in one call.
constexpr EdgeEvaluation evaluate_edge(const Edge& e, unsigned px, unsigned py, q5_16 recip) {
  EdgeEvaluation r{};
  r.value = edge_value_at(e, px, py);
  r.value_next_x = edge_step_x(e, r.value);
  r.value_next_y = edge_step_y(e, r.value);
  r.inside = edge_inside(e, r.value);
  r.l1_length = edge_l1_length(e);
  r.distance = edge_normalised_distance(r.value, recip);
  r.coverage = edge_coverage(r.distance);
  return r;
}

// Batch form (batch.h): the pixels (px + i, py), i in 0..count-1, of a row
// (px + count <= 512, py <= 511), everything evaluate_edge gives, E
// evaluated once and stepped (exact, above). value holds count + 1 values,
// E at px .. px + count, so that value[i + 1] is pixel i's value_next_x;
// l1_length, the same for every pixel, is the return value.
struct EdgeSpan {
  int32_t* value;         // count + 1 entries; E fits in 29 bits
  int32_t* value_next_y;  // E at (px + i, py + 1)
  uint32_t* inside;       // 1 or 0
  int32_t* distance;      // q7.8
  uint32_t* coverage;     // 0.8
};

struct EdgeSpanKernel {
  TESSERA_BATCH_KERNEL void run(const Edge& e, unsigned px, unsigned py, unsigned count, q5_16 recip,
                                const EdgeSpan& out) {
    loop(e, static_cast<int32_t>(edge_value_at(e, px, py).raw), count, recip, out.value, out.value_next_y, out.inside,
         out.distance, out.coverage);
  }
  TESSERA_BATCH_KERNEL void loop(const Edge e, int32_t first, unsigned count, q5_16 recip, int32_t* __restrict value,
                                 int32_t* __restrict value_next_y, uint32_t* __restrict inside,
                                 int32_t* __restrict distance, uint32_t* __restrict coverage) {
    const auto step = static_cast<int32_t>(edge_step_x(e, edge_value{0}).raw);
    const auto step_y = static_cast<int32_t>(edge_step_y(e, edge_value{0}).raw);
    for (unsigned i = 0; i <= count; ++i) value[i] = first + static_cast<int32_t>(i) * step;
    for (unsigned i = 0; i < count; ++i) {
      const edge_value v{first + static_cast<int32_t>(i) * step};
      value_next_y[i] = static_cast<int32_t>(v.raw) + step_y;
      inside[i] = edge_inside(e, v) ? 1u : 0u;
      const edge_distance d = edge_normalised_distance(v, recip);
      distance[i] = static_cast<int32_t>(d.raw);
      coverage[i] = edge_coverage(d).raw;
    }
  }
};

q10_4 edge_span(const Edge& e, unsigned px, unsigned py, unsigned count, q5_16 recip, const EdgeSpan& out,
                BatchIsa isa = best_batch_isa());

}  // namespace tessera::raster
