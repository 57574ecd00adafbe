#include "renderers/ap_pixel/pixel_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <stdexcept>
#include <string>

#include "ap_programs/ap_pixel.h"
#include "ap_programs/ap_pixel_study.h"
#include "renderers/common/named_choice.h"
#include "renderers/common/texel_fixed.h"

namespace tessera::ap_pixel {

// The ranges below follow from the vertices' bound, |x|, |y| <= 2^14
// (COORDINATE_LIMIT), and the box's pixel centres, within a 512-pixel frame
// (at most 8184 sixteenths): every point involved lies in a square of side
// 2^15, so differences are at most 2^15 and twice the area of a triangle of
// such points (the doubled area, an edge function's value, a barycentric
// numerator) at most 2^30 in magnitude.

namespace {

int32_t magnitude(int32_t v) {
  return v < 0 ? -v : v;
}

// floor(n / 16): an arithmetic shift (GCC and clang shift signed values
// arithmetically).
int32_t floor16(int32_t n) {
  return n >> 4;
}

}  // namespace

ProgramVariant program_variant(const std::string& name, const std::string& key) {
  return renderers::named_choice<ProgramVariant>(name, PROGRAM_VARIANT_NAMES, key, "array program");
}

const char* program_variant_name(ProgramVariant variant) {
  return PROGRAM_VARIANT_NAMES[static_cast<unsigned>(variant)];
}

const ap::Program& program_of(ProgramVariant variant) {
  return variant == ProgramVariant::study ? ap::programs::ap_pixel_study() : ap::programs::ap_pixel();
}

PixelLayout PixelLayout::of(const ap::Program& program, ProgramVariant variant) {
  PixelLayout layout;
  layout.variant = variant;
  layout.value_bytes = variant == ProgramVariant::study ? 2 : 3;
  layout.gradient_offset = variant == ProgramVariant::study ? 0 : 1;
  if (ap::constant_value(program, "ATTRS") != static_cast<int>(ATTRIBUTES))
    throw std::invalid_argument(program.source_name + ": the program evaluates " +
                                std::to_string(ap::constant_value(program, "ATTRS")) +
                                " attributes, the host expects " + std::to_string(ATTRIBUTES));
  layout.max_block = static_cast<unsigned>(ap::constant_value(program, "MAX_BLOCK"));
  const unsigned values = layout.value_bytes * ATTRIBUTES;
  layout.c0 = ap::variable_address(program, "c0", values);
  layout.gx = ap::variable_address(program, "gx", values);
  layout.gy = ap::variable_address(program, "gy", values);
  layout.dx = ap::variable_address(program, "dx", 1);
  layout.dy = ap::variable_address(program, "dy", 1);
  layout.out = ap::variable_address(program, "out", values * layout.max_block * layout.max_block);
  layout.scratch =
      ap::variable_address(program, variant == ProgramVariant::study ? "t" : "partial", layout.value_bytes);
  if (layout.max_block + 1 > layout.entry.size())
    throw std::invalid_argument(program.source_name + ": MAX_BLOCK " + std::to_string(layout.max_block) +
                                " is beyond the host's 5");
  for (unsigned k = 1; k <= layout.max_block; ++k)
    layout.entry[k] = ap::entry_word(program, "block" + std::to_string(k));
  if (variant == ProgramVariant::study)
    for (unsigned n = 1; n <= ATTRIBUTES; ++n)
      layout.shade_entry[n] = ap::entry_word(program, "shade" + std::to_string(n));
  for (const auto& [name, variable] : program.variables)
    layout.cmem_bytes = std::max(layout.cmem_bytes, unsigned{variable.address} + variable.size);
  return layout;
}

PixelTriangle::PixelTriangle(const gl::Triangle& triangle, bool flat, unsigned tex_width, unsigned tex_height,
                             const PixelBox& box, unsigned unit)
    : m_box(box) {
  for (unsigned i = 0; i < 3; ++i) {
    m_x[i] = triangle.v[i].x;
    m_y[i] = triangle.v[i].y;
    if (magnitude(m_x[i]) > COORDINATE_LIMIT || magnitude(m_y[i]) > COORDINATE_LIMIT) return;
  }
  const int32_t x1 = m_x[1] - m_x[0], y1 = m_y[1] - m_y[0], x2 = m_x[2] - m_x[0], y2 = m_y[2] - m_y[0];
  const int64_t area = int64_t{x1} * y2 - int64_t{y1} * x2;  // |area| <= 2^30
  if (area == 0) return;
  m_area = static_cast<uint32_t>(area < 0 ? -area : area);
  m_area_divisor = Divisor(m_area);
  m_area_sign = area < 0 ? -1 : 1;
  // Edge i runs from vertex i to vertex i + 1; (x - px) dy - (y - py) dx is
  // negative inside a counter-clockwise triangle (positive area), so its
  // sign is flipped there. Edge i is then vertex i + 2's barycentric weight
  // times m_area.
  const int32_t sign = area > 0 ? -1 : 1;
  for (unsigned i = 0; i < 3; ++i) {
    const unsigned next = (i + 1) % 3;
    const int32_t dx = m_x[next] - m_x[i], dy = m_y[next] - m_y[i];
    Edge& edge = m_edges[i];
    edge.a = sign * dy;  // |a|, |b| <= 2^15
    edge.b = -sign * dx;
    // The value at (0, 0): twice the area of (origin, vertex i, vertex i +
    // 1), at most 2^30.
    edge.c = static_cast<int32_t>(sign * (int64_t{m_y[i]} * dx - int64_t{m_x[i]} * dy));
    edge.top_left = edge.a > 0 || (edge.a == 0 && edge.b < 0);
    if (edge.a != 0) edge.over_16a = Divisor(static_cast<uint32_t>(16 * magnitude(edge.a)));
  }
  const int32_t y_lo = std::min({m_y[0], m_y[1], m_y[2]}), y_hi = std::max({m_y[0], m_y[1], m_y[2]});
  m_y_min = static_cast<int>(std::max<int32_t>(box.y0, -floor16(-(y_lo - 8))));
  m_y_max = static_cast<int>(std::min<int32_t>(box.y1, floor16(y_hi - 8)));
  if (m_y_min > m_y_max || box.x0 > box.x1) return;

  // The planes in 2^-fraction units of their 16.8 codes: colour channel c
  // is the code 256 c (65536 c, fraction 8), depth the code z24 / 256 (z24,
  // fraction 8), s and t the codes of texels x 256 (1/4096 texel, fraction
  // 4; renderers/common/texel_fixed.h, the 16.8 code wrapping every 2^16
  // texels). Texture coordinates that are not finite give 0, counted as
  // clamped (the host shades such a triangle itself).
  const auto plane = [](int32_t v0, int32_t v1, int32_t v2, unsigned fraction) {
    return Plane{v0, v1 - v0, v2 - v0, fraction};
  };
  const gl::ScreenVertex* colour[3] = {&triangle.v[0], &triangle.v[1], &triangle.v[2]};
  if (flat) colour[0] = colour[1] = colour[2] = &triangle.v[2];
  for (unsigned k = 0; k < 4; ++k) {
    int32_t v[3];
    for (unsigned i = 0; i < 3; ++i) {
      const uint8_t channels[4] = {colour[i]->r, colour[i]->g, colour[i]->b, colour[i]->a};
      v[i] = int32_t{channels[k]} << 16;
    }
    m_planes[k] = plane(v[0], v[1], v[2], 8);
  }
  for (unsigned i = 0; i < 3; ++i) m_z[i] = triangle.v[i].z;
  m_planes[static_cast<unsigned>(Attribute::z)] =
      plane(static_cast<int32_t>(m_z[0]), static_cast<int32_t>(m_z[1]), static_cast<int32_t>(m_z[2]), 8);
  const unsigned sizes[2] = {tex_width, tex_height};
  bool not_finite[2] = {false, false};
  for (unsigned k = 0; k < 2; ++k) {
    float st[3];
    bool finite = true;
    for (unsigned i = 0; i < 3; ++i) {
      st[i] = k == 0 ? triangle.v[i].tex[unit].s : triangle.v[i].tex[unit].t;
      finite = finite && std::isfinite(st[i]);
    }
    int32_t v[3] = {0, 0, 0};
    if (finite) renderers::texel_fixed(st, static_cast<float>(sizes[k]) * 4096.0f, 28, v);
    not_finite[k] = !finite;
    m_planes[static_cast<unsigned>(Attribute::s) + k] = plane(v[0], v[1], v[2], 4);
  }

  // The gradients per pixel right and up: 16 cx / area and 16 cy / area in
  // 2^-fraction code units, with cx = d1 y2 - d2 y1 and cy = d2 x1 - d1 x2
  // (|d| < 2^30, so |16 cx| < 2^50), rounded to 8.8 (halves up) and
  // clamped to 16 bits.
  for (unsigned k = 0; k < ATTRIBUTES; ++k) {
    const Plane& p = m_planes[k];
    const int64_t cx = int64_t{p.d1} * y2 - int64_t{p.d2} * y1;
    const int64_t cy = int64_t{p.d2} * x1 - int64_t{p.d1} * x2;
    const auto gradient = [&](int64_t numerator, bool& clamped) {
      const int64_t code =
          (m_area_divisor.floor_divide(16 * m_area_sign * numerator).quotient + (int64_t{1} << (p.fraction - 1))) >>
          p.fraction;
      clamped = clamped || code > 32767 || code < -32767;
      return static_cast<int16_t>(std::clamp<int64_t>(code, -32768, 32767));
    };
    bool clamped = false;
    m_gradients.gx[k] = gradient(cx, clamped);
    m_gradients.gy[k] = gradient(cy, clamped);
    m_gradients.clamped[k] = clamped;
  }
  // Coordinates that are not finite cannot be drawn by the array either.
  for (unsigned k = 0; k < 2; ++k)
    if (not_finite[k]) m_gradients.clamped[static_cast<unsigned>(Attribute::s) + k] = true;
  m_valid = true;
}

bool PixelTriangle::span(int j, int& first, int& last) const {
  if (!m_valid || j < m_y_min || j > m_y_max) return false;
  int32_t lo = m_box.x0, hi = m_box.x1;
  const int32_t y16 = 16 * j + 8;
  for (const Edge& edge : m_edges) {
    // Pixel i is inside the edge if a (16 i + 8) + k >= t, k = E at (0,
    // y16): |k| <= 2^30.
    const int32_t k = edge.b * y16 + edge.c, t = edge.top_left ? 0 : 1;
    const int32_t n = t - k - 8 * edge.a;
    // i >= n / (16 a) for a > 0, i <= n / (16 a) for a < 0, by the
    // triangle's Divisor of 16 |a|: no division in the span loop.
    if (edge.a > 0)
      lo = std::max<int32_t>(lo, static_cast<int32_t>(-edge.over_16a.floor_divide(-int64_t{n}).quotient));
    else if (edge.a < 0)
      hi = std::min<int32_t>(hi, static_cast<int32_t>(edge.over_16a.floor_divide(-int64_t{n}).quotient));
    else if (k < t)
      return false;
  }
  if (lo > hi) return false;
  first = static_cast<int>(lo);
  last = static_cast<int>(hi);
  return true;
}

uint16_t PixelTriangle::depth16(int i, int j) const {
  const int32_t x16 = 16 * i + 8, y16 = 16 * j + 8;
  // Each edge's value is a barycentric weight times the area (<= 2^30), so
  // the sum of the three products with 24-bit depths stays below 2^56.
  int64_t sum = 0;
  for (unsigned e = 0; e < 3; ++e) {
    const Edge& edge = m_edges[e];
    sum += int64_t{edge.a * x16 + edge.b * y16 + edge.c} * static_cast<int32_t>(m_z[(e + 2) % 3]);
  }
  // Inside the triangle every weight is >= 0, so the quotient is the floor.
  const int64_t z24 = m_area_divisor.floor_divide(sum).quotient;
  return static_cast<uint16_t>(std::clamp<int64_t>(z24, 0, 0xffffff) >> 8);
}

TriangleValues PixelTriangle::values(int ox, int oy) const {
  TriangleValues result = m_gradients;
  // The barycentric numerators of the origin's centre (|w| <= 2^30).
  const int32_t dx = 16 * ox + 8 - m_x[0], dy = 16 * oy + 8 - m_y[0];
  const int32_t x1 = m_x[1] - m_x[0], y1 = m_y[1] - m_y[0], x2 = m_x[2] - m_x[0], y2 = m_y[2] - m_y[0];
  const auto w1 = static_cast<int32_t>(int64_t{y2} * dx - int64_t{x2} * dy);
  const auto w2 = static_cast<int32_t>(int64_t{x1} * dy - int64_t{y1} * dx);
  for (unsigned k = 0; k < ATTRIBUTES; ++k) {
    const Plane& p = m_planes[k];
    // value x area: |v0| < 2^29 and |d| < 2^30 give less than 2^62.
    const int64_t n =
        int64_t{p.v0} * (m_area_sign * static_cast<int32_t>(m_area)) + int64_t{p.d1} * w1 + int64_t{p.d2} * w2;
    const int64_t code =
        (m_area_divisor.floor_divide(m_area_sign * n).quotient + (int64_t{1} << (p.fraction - 1))) >> p.fraction;
    // Colour is rounded by adding a half once, here: the host takes the
    // integer part of what the array returns.
    const int64_t bias = k <= static_cast<unsigned>(Attribute::alpha) ? 128 : 0;
    result.c0[k] = static_cast<uint32_t>(code + bias) & 0xffffffu;
  }
  return result;
}

}  // namespace tessera::ap_pixel
