// The arm renderer's fixed-point formats and the attribute planes its
// triangle set-up builds and its span shading steps (internal to the
// renderer; formats, rounding and the fill rule: arm_rasterizer.h).
#pragma once

#include <algorithm>
#include <cstdint>

#include "gl/renderer.h"
#include "renderers/common/fixed_math.h"

namespace tessera::arm {

// Ranges. The front end delivers 9.4 vertices in [0, 8191] (the 512-pixel
// screen, gl/geometry.h MAX_SCREEN_COORDINATE); the core takes any vertex
// with |x|, |y| <= MAX_COORDINATE = 2^14 - 1 (about +-1024 pixels) and skips
// a triangle with a vertex beyond. From that, in 9.4 units:
// - edge vectors: |dx|, |dy| <= 2^15 - 2;
// - twice the area, A = dx1 dy2 - dx2 dy1: |A| <= 2 (2^15 - 2)^2 < 2^31;
// - an edge DDA's numerator (xt - 8) d + (yt - yc) dx: |.| < 2^29 + 2^30,
//   as the walked row's centre yc lies between the edge's ends (|yt - yc|
//   <= d), and its divisor 16 d < 2^19: all int32, one 32-bit division each.
constexpr int32_t MAX_COORDINATE = (1 << 14) - 1;
// The window positions before snapping, for the attribute planes of a
// perspective textured triangle, are taken to 1/256 pixel while they lie
// within +-2^10 pixels (else the snapped vertices serve): |d| < 2^19 and
// |A| < 2^39 in those units, int64.
constexpr int UNSNAPPED_BITS = 8;
constexpr float MAX_UNSNAPPED = 1024.0f;
constexpr int COLOR_FRACTION_BITS = 16;
constexpr int DEPTH_FRACTION_BITS = 7;    // interpolant = z24 << 7 < 2^31
constexpr int Q_FRACTION_BITS = 30;       // normalised 1/w in (0, 1], as 1 .. 2^30
constexpr int ST_MAX_FRACTION_BITS = 24;  // s * width * q with F <= 24 fraction bits, |.| < 2^30
constexpr float MAX_TEXELS = 32768.0f;    // |s * width| is clamped to this
// Every plane's vertex values lie within [-2^30, 2^31) and differ by less
// than 2^31 (depth: [0, 2^31 - 128]; colour: < 2^24; q: [1, 2^30]; s q and
// t q: |.| < 2^30; fog: clamped to +-2^30), so that a difference times a
// barycentric weight (|w| < 2 in 2.30) is below 2^62.
constexpr int32_t MAX_FOG_VALUE = 1 << 30;

// One step of a span's interpolant, wrapping as the ARM's ADD does: the
// values the span's pixels use stay within their clamped range, but the
// step after its last pixel may leave int32 (a signed overflow, undefined
// in C++; the same bits on the ARM).
inline void advance(int32_t& value, int32_t delta) {
  value = int32_t(uint32_t(value) + uint32_t(delta));
}

inline int32_t floor_div(int32_t a, int32_t b) {  // b > 0: a 32-bit division
  int32_t q = a / b;
  if ((a % b) != 0 && a < 0) --q;
  return q;
}

inline int32_t ceil_div(int32_t a, int32_t b) {
  return -floor_div(-a, b);
}  // b > 0

inline bool finite(float f) {
  return f == f && f - f == 0.0f;  // not NaN, not infinite (no libm)
}

inline bool has_window_positions(const gl::Triangle& tri) {
  for (const gl::ScreenVertex& v : tri.v) {
    if (!finite(v.x_window) || !finite(v.y_window)) return false;
    if (v.x_window >= MAX_UNSNAPPED || v.x_window <= -MAX_UNSNAPPED || v.y_window >= MAX_UNSNAPPED ||
        v.y_window <= -MAX_UNSNAPPED)
      return false;
  }
  return true;
}

// Rounded to nearest, halves away from zero; |f| < 2^30.
inline int32_t round_to_int(float f) {
  return static_cast<int32_t>(f >= 0 ? f + 0.5f : f - 0.5f);
}

// llround(x / 2) for an integer x.
inline int64_t halve_rounded(int64_t x) {
  return x >= 0 ? (x + 1) >> 1 : -((-x + 1) >> 1);
}

// The frame the attribute planes are set up in: vertex 0 and the edge
// vectors to vertices 1 and 2, in units of 2^-bits pixel (bits = 4: the
// snapped 9.4 vertices; UNSNAPPED_BITS: the window positions), twice the
// area A (nonzero) and 1/|A|.
struct Basis {
  int bits = 4;
  int64_t x0 = 0, y0 = 0, dx1 = 0, dy1 = 0, dx2 = 0, dy2 = 0;
  int64_t area = 0;
  renderers::Reciprocal inverse;

  // False when the area is zero.
  bool init(int fraction_bits, const int64_t x[3], const int64_t y[3]) {
    bits = fraction_bits;
    x0 = x[0];
    y0 = y[0];
    dx1 = x[1] - x[0];
    dy1 = y[1] - y[0];
    dx2 = x[2] - x[0];
    dy2 = y[2] - y[0];
    area = dx1 * dy2 - dx2 * dy1;
    if (area == 0) return false;
    inverse = renderers::make_reciprocal(uint64_t(area < 0 ? -area : area));
    return true;
  }

  // N / A scaled by 2^k, for a numerator N (|N| < 2^62).
  int64_t over_area(int64_t n, int k) const { return renderers::scaled_quotient(area < 0 ? -n : n, inverse, k); }

  // The barycentric weights of vertices 1 and 2 at the centre of pixel (i,
  // j), in 2.30: w = E / A with E the edge function, both in [0, 1] for a
  // centre inside the triangle (every span's first pixel: the fill rule
  // puts its centre inside the snapped triangle, within 1/32 pixel of the
  // unsnapped one), clamped to +-2 otherwise. |E| < 2^38 (a centre within
  // 2^10 pixels of vertex 0, an edge shorter than 2^11 pixels).
  void weights(int i, int j, int32_t w[2]) const {
    const int64_t x = (2 * int64_t{i} + 1) * (int64_t{1} << (bits - 1)) - x0;
    const int64_t y = (2 * int64_t{j} + 1) * (int64_t{1} << (bits - 1)) - y0;
    const int64_t e[2] = {x * dy2 - y * dx2, y * dx1 - x * dy1};
    for (int k = 0; k < 2; ++k) {
      const int64_t v = over_area(e[k], 30);
      w[k] = int32_t(std::clamp<int64_t>(v, -(int64_t{1} << 31) + 1, (int64_t{1} << 31) - 1));
    }
  }

  // The numerators of an attribute's gradients: d/dx = nx 2^bits / A, d/dy
  // = ny 2^bits / A per pixel, for vertex differences |d1|, |d2| < 2^31:
  // |n| < 2^51.
  void numerators(int64_t d1, int64_t d2, int64_t* nx, int64_t* ny) const {
    *nx = d1 * dy2 - d2 * dy1;
    *ny = d2 * dx1 - d1 * dx2;
  }
};

// One attribute's plane in fixed point: the value at vertex 0 and the
// differences to vertices 1 and 2, evaluated at a span's first pixel from
// the barycentric weights there: v0 + floor((d1 w1 + d2 w2) / 2^30), each
// product below 2^62. Values inside the triangle are convex combinations of
// the vertex values, so every start value is clamped to [lo, hi] and nudged
// so that stepping to the span's end stays there. The step per pixel is the
// x gradient rounded to nearest (halves away from zero) and clamped to
// +-(hi - lo).
//
// The planes the perspective divide reads (q, s q, t q: |values| < 2^30)
// are also kept with FINE_BITS more fraction bits (start_fine, step_fine:
// value 2^29, below 2^59; the start is (v0 2^29 + d1 w1 / 2 + d2 w2 / 2),
// each term below 2^61), stepped by 64-bit adds (ADDS, ADC), so that a
// rounded step's error (half a unit per pixel, 256 units over a 512-pixel
// span) does not add up: where 1/w falls 1000 times across a triangle,
// 256 units of s q moved u by several texels.
constexpr int FINE_BITS = 29;

struct Plane {
  int32_t v0 = 0, d1 = 0, d2 = 0;
  int32_t lo = 0, hi = 0, step = 0;
  int64_t step_fine = 0;  // the x gradient in 2^-FINE_BITS units, for fine planes

  void setup(const int32_t v[3], const Basis& basis, bool fine = false) {
    v0 = v[0];
    d1 = v[1] - v[0];
    d2 = v[2] - v[0];
    lo = std::min({v[0], v[1], v[2]});
    hi = std::max({v[0], v[1], v[2]});
    int64_t nx, ny;
    basis.numerators(d1, d2, &nx, &ny);
    const int64_t range = int64_t{hi} - lo;
    step = int32_t(std::clamp<int64_t>(halve_rounded(basis.over_area(nx, basis.bits + 1)), -range, range));
    if (fine) {
      const int64_t fine_range = range << FINE_BITS;  // < 2^60
      step_fine =
          std::clamp<int64_t>(halve_rounded(basis.over_area(nx, basis.bits + FINE_BITS + 1)), -fine_range, fine_range);
    }
  }

  // Value at the first pixel of a span of n pixels, whose weights are w.
  int32_t start(const int32_t w[2], int n) const {
    const int64_t v = int64_t{v0} + ((int64_t{d1} * w[0] + int64_t{d2} * w[1]) >> 30);
    int64_t s = std::clamp<int64_t>(v, lo, hi);
    const int64_t end = s + int64_t{step} * (n - 1);
    if (end < lo) s += lo - end;
    if (end > hi) s -= end - hi;
    return int32_t(std::clamp<int64_t>(s, lo, hi));
  }

  // The same in 2^-FINE_BITS units, stepped by step_fine.
  int64_t start_fine(const int32_t w[2], int n) const {
    // Scaled by a multiply: lo, hi and v0 may be negative, and a left shift
    // of a negative value is undefined (the same bits on the ARM).
    constexpr int64_t FINE_UNIT = int64_t{1} << FINE_BITS;
    const int64_t low = int64_t{lo} * FINE_UNIT, high = int64_t{hi} * FINE_UNIT;
    const int64_t v = int64_t{v0} * FINE_UNIT + ((int64_t{d1} * w[0]) >> 1) + ((int64_t{d2} * w[1]) >> 1);
    int64_t s = std::clamp<int64_t>(v, low, high);
    // |step_fine| (n - 1) stays below 2^62 unless the step is far beyond
    // the span's reach (a sliver's): then the start is only clamped.
    const uint64_t magnitude = uint64_t(step_fine < 0 ? -step_fine : step_fine);
    if (n > 1 && renderers::bit_length64(magnitude) + renderers::bit_length(uint32_t(n - 1)) <= 62) {
      const int64_t end = s + step_fine * (n - 1);
      if (end < low) s += low - end;
      if (end > high) s -= end - high;
    }
    return std::clamp<int64_t>(s, low, high);
  }
};

// The gradients of a texture unit's s q, t q and of q, for its level of
// detail: g = gradient 2^-exponent, |g| < 2^30, one exponent for the six so
// that the pixel's derivatives of u = (s q) / q keep their ratio.
struct LodGradients {
  int32_t sx = 0, sy = 0, tx = 0, ty = 0, qx = 0, qy = 0;
  int exponent = 0;
  bool moves = false;  // a texture that does not move has lambda = -inf

  void setup(const Plane& sq, const Plane& tq, const Plane& q, const Basis& basis) {
    int64_t n[6];
    basis.numerators(sq.d1, sq.d2, &n[0], &n[1]);
    basis.numerators(tq.d1, tq.d2, &n[2], &n[3]);
    basis.numerators(q.d1, q.d2, &n[4], &n[5]);
    unsigned longest = 0;
    for (int64_t v : n) longest = std::max(longest, renderers::bit_length64(uint64_t(v < 0 ? -v : v)));
    moves = longest != 0;
    if (!moves) return;
    // |n 2^(bits + k) / A| < 2^(longest + bits + k - length(A) + 1) = 2^29.
    const int area_length = int(renderers::bit_length64(uint64_t(basis.area < 0 ? -basis.area : basis.area)));
    const int k = 28 - int(longest) - basis.bits + area_length;
    exponent = k;
    int32_t* out[6] = {&sx, &sy, &tx, &ty, &qx, &qy};
    for (int i = 0; i < 6; ++i) {
      const int64_t g = basis.over_area(n[i], basis.bits + k);
      *out[i] = int32_t(std::clamp<int64_t>(g, -(int64_t{1} << 30), int64_t{1} << 30));
    }
  }
};

}  // namespace tessera::arm
