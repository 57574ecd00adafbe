#include "cluster/split.h"

#include <utility>

#include "cluster/stripes.h"
#include "renderers/common/divisor.h"

namespace tessera::cluster {

namespace {

// Largest gradient magnitude kept, in fixed-point units per pixel: reached
// only by slivers of almost no area; it keeps every product below 2^62.
constexpr int64_t MAX_GRADIENT = int64_t{1} << 40;

int32_t floor_div(int32_t a, int32_t b) {  // b > 0: one 32-bit division
  int32_t q = a / b;
  if ((a % b) != 0 && a < 0) --q;
  return q;
}

int32_t ceil_div(int32_t a, int32_t b) {
  return -floor_div(-a, b);
}

// The first row whose centre is at or below y (9.4): ceil((y - 8) / 16).
int32_t first_row_at_or_below(int32_t y) {
  return ceil_div(y - SUBPIXEL_ONE / 2, SUBPIXEL_ONE);
}

struct Edge {
  int32_t xt, yt, xb, yb;  // top to bottom, yt < yb
};

// The edge's DDA at row r (yt <= 16 r + 8 < yb, within the guard band):
// the numerator (xt - 8) d + (yc - yt) dx is below 2^14 2^15 + 2^15 2^15
// < 2^31, the denominator 16 d < 2^19.
TrapezoidEdge edge_at_row(const Edge& edge, int32_t row) {
  const int32_t d = edge.yb - edge.yt, dx = edge.xb - edge.xt, yc = row * SUBPIXEL_ONE + SUBPIXEL_ONE / 2;
  TrapezoidEdge out;
  out.denominator = SUBPIXEL_ONE * d;
  const int32_t numerator = (edge.xt - SUBPIXEL_ONE / 2) * d + (yc - edge.yt) * dx;
  out.pixel = ceil_div(numerator, out.denominator);
  out.error = out.pixel * out.denominator - numerator;
  out.step = floor_div(SUBPIXEL_ONE * dx, out.denominator);
  out.step_error = SUBPIXEL_ONE * dx - out.step * out.denominator;
  return out;
}

// An attribute's plane A(i, r) = base + i dx + r dy, exact in integers.
struct Plane {
  int64_t base = 0, dx = 0, dy = 0;

  int64_t at(int32_t i, int32_t r) const { return base + dx * i + dy * r; }
};

int64_t clamp_gradient(int64_t g) {
  return g > MAX_GRADIENT ? MAX_GRADIENT : (g < -MAX_GRADIENT ? -MAX_GRADIENT : g);
}

// The plane through the three vertex values (fixed point, below 2^30),
// gradients per pixel rounded to nearest: g = 16 N / A with N below 2^47.
Plane make_plane(const ScreenVertex* v, const int32_t value[3], const Divisor& area, bool negative) {
  const int32_t dx1 = v[1].x - v[0].x, dy1 = v[1].y - v[0].y, dx2 = v[2].x - v[0].x, dy2 = v[2].y - v[0].y;
  const int32_t d1 = value[1] - value[0], d2 = value[2] - value[0];
  int64_t nx = (int64_t{d1} * dy2 - int64_t{d2} * dy1) * SUBPIXEL_ONE;
  int64_t ny = (int64_t{d2} * dx1 - int64_t{d1} * dx2) * SUBPIXEL_ONE;
  if (negative) {
    nx = -nx;
    ny = -ny;
  }
  Plane plane;
  plane.dx = clamp_gradient(area.round_divide(nx));
  plane.dy = clamp_gradient(area.round_divide(ny));
  // A(i, r) = v0 + ((16 i + 8 - x0) dx + (16 r + 8 - y0) dy) / 16, floored:
  // the 16 i and 16 r terms divide exactly, leaving base.
  const int64_t offset = plane.dx * (SUBPIXEL_ONE / 2 - v[0].x) + plane.dy * (SUBPIXEL_ONE / 2 - v[0].y);
  plane.base = value[0] + (offset >> SUBPIXEL_BITS);
  return plane;
}

class Splitter {
 public:
  Splitter(unsigned height, unsigned p, TrapezoidSink& sink) : m_height(height), m_p(p), m_sink(sink) {}

  // The rows [begin, end) between the edges, cut at the stripes.
  void emit(int32_t begin, int32_t end, const Edge& left, const Edge& right) {
    if (begin < 0) begin = 0;
    if (end > static_cast<int32_t>(m_height)) end = static_cast<int32_t>(m_height);
    if (begin >= end) return;
    ++nonempty;
    unsigned stripe = stripe_of_row(static_cast<unsigned>(begin), m_height, m_p);
    while (begin < end) {
      int32_t piece_end = static_cast<int32_t>(stripe_rows(stripe, m_height, m_p).end);
      if (piece_end > end) piece_end = end;
      put(stripe, begin, piece_end - 1, left, right);
      begin = piece_end;
      ++stripe;
    }
  }

  Plane planes[4];
  unsigned pieces = 0, nonempty = 0, rows = 0;

 private:
  void put(unsigned stripe, int32_t first, int32_t last, const Edge& left, const Edge& right) {
    Trapezoid t;
    t.first_row = static_cast<int16_t>(first);
    t.last_row = static_cast<int16_t>(last);
    t.left = edge_at_row(left, first);
    t.right = edge_at_row(right, first);
    TrapezoidPlane* out[4] = {&t.z, &t.red, &t.green, &t.blue};
    for (int k = 0; k < 4; ++k) {
      out[k]->start = planes[k].at(t.left.pixel, first);
      out[k]->row_step = planes[k].dy + planes[k].dx * t.left.step;
      out[k]->dx = planes[k].dx;
    }
    ++pieces;
    rows += static_cast<unsigned>(last - first + 1);
    m_sink.put(stripe, t);
  }

  unsigned m_height, m_p;
  TrapezoidSink& m_sink;
};

bool in_guard_band(const ScreenVertex& v) {
  return v.x >= -MAX_COORDINATE && v.x <= MAX_COORDINATE && v.y >= -MAX_COORDINATE && v.y <= MAX_COORDINATE;
}

}  // namespace

unsigned split_triangle(const ScreenTriangle& triangle, unsigned screen_height, unsigned p, TrapezoidSink& sink,
                        WorkCounters* counters) {
  if (stripe_parameters_error(screen_height, p) != nullptr) return 0;
  ScreenVertex v[3] = {triangle.v[0], triangle.v[1], triangle.v[2]};
  for (const ScreenVertex& vertex : v)
    if (!in_guard_band(vertex)) return 0;
  // Sorted by y: v[0] top, v[1] middle, v[2] bottom.
  if (v[1].y < v[0].y) std::swap(v[0], v[1]);
  if (v[2].y < v[1].y) std::swap(v[1], v[2]);
  if (v[1].y < v[0].y) std::swap(v[0], v[1]);
  if (counters != nullptr) ++counters->triangles_split;
  // Twice the signed area; < 0: the middle vertex lies left of the long edge.
  const int64_t area = int64_t{v[1].x - v[0].x} * (v[2].y - v[0].y) - int64_t{v[1].y - v[0].y} * (v[2].x - v[0].x);
  if (area == 0) return 0;
  const Divisor divisor(static_cast<uint32_t>(area < 0 ? -area : area));
  Splitter splitter(screen_height, p, sink);
  const int32_t z[3] = {static_cast<int32_t>(v[0].z << DEPTH_FRACTION_BITS),
                        static_cast<int32_t>(v[1].z << DEPTH_FRACTION_BITS),
                        static_cast<int32_t>(v[2].z << DEPTH_FRACTION_BITS)};
  const int32_t r[3] = {v[0].r << COLOR_FRACTION_BITS, v[1].r << COLOR_FRACTION_BITS, v[2].r << COLOR_FRACTION_BITS};
  const int32_t g[3] = {v[0].g << COLOR_FRACTION_BITS, v[1].g << COLOR_FRACTION_BITS, v[2].g << COLOR_FRACTION_BITS};
  const int32_t b[3] = {v[0].b << COLOR_FRACTION_BITS, v[1].b << COLOR_FRACTION_BITS, v[2].b << COLOR_FRACTION_BITS};
  splitter.planes[0] = make_plane(v, z, divisor, area < 0);
  splitter.planes[1] = make_plane(v, r, divisor, area < 0);
  splitter.planes[2] = make_plane(v, g, divisor, area < 0);
  splitter.planes[3] = make_plane(v, b, divisor, area < 0);

  const Edge long_edge{v[0].x, v[0].y, v[2].x, v[2].y};
  const Edge upper{v[0].x, v[0].y, v[1].x, v[1].y}, lower{v[1].x, v[1].y, v[2].x, v[2].y};
  const int32_t top = first_row_at_or_below(v[0].y), middle = first_row_at_or_below(v[1].y),
                bottom = first_row_at_or_below(v[2].y);
  const bool middle_left = area < 0;
  // The rows of a half are empty when its short edge is horizontal, so an
  // edge with yt == yb is never set up.
  splitter.emit(top, middle, middle_left ? upper : long_edge, middle_left ? long_edge : upper);
  splitter.emit(middle, bottom, middle_left ? lower : long_edge, middle_left ? long_edge : lower);
  if (counters != nullptr) {
    counters->trapezoids_nonempty += splitter.nonempty;
    counters->trapezoids_out += splitter.pieces;
    counters->trapezoid_rows_out += splitter.rows;
  }
  return splitter.pieces;
}

}  // namespace tessera::cluster
