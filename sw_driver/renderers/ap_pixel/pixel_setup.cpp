#include "renderers/ap_pixel/pixel_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "renderers/common/wide_int.h"

namespace tessera::ap_pixel {

namespace {

using Wide = Int128;  // 2^46 edge values times 2^24 depths

int64_t floor_div(int64_t n, int64_t d) {
  if (d < 0) n = -n, d = -d;
  return n >= 0 ? n / d : -((-n + d - 1) / d);
}

int64_t ceil_div(int64_t n, int64_t d) {
  return -floor_div(-n, d);
}

// Vertices beyond this many pixels are refused, as in the other back ends:
// the clipper keeps them far inside, and the products stay in range.
constexpr int64_t COORDINATE_LIMIT = int64_t{1} << 22;  // 2^18 pixels in 1/16

}  // namespace

PixelLayout PixelLayout::of(const ap::Program& program) {
  PixelLayout layout;
  if (ap::constant_value(program, "ATTRS") != static_cast<int>(ATTRIBUTES))
    throw std::invalid_argument(program.source_name + ": the program evaluates " +
                                std::to_string(ap::constant_value(program, "ATTRS")) +
                                " attributes, the host expects " + std::to_string(ATTRIBUTES));
  layout.max_block = static_cast<unsigned>(ap::constant_value(program, "MAX_BLOCK"));
  const unsigned values = 3 * ATTRIBUTES;
  layout.c0 = ap::variable_address(program, "c0", values);
  layout.gx = ap::variable_address(program, "gx", values);
  layout.gy = ap::variable_address(program, "gy", values);
  layout.dx = ap::variable_address(program, "dx", 1);
  layout.dy = ap::variable_address(program, "dy", 1);
  layout.out = ap::variable_address(program, "out", values * layout.max_block * layout.max_block);
  if (layout.max_block + 1 > layout.entry.size())
    throw std::invalid_argument(program.source_name + ": MAX_BLOCK " + std::to_string(layout.max_block) +
                                " is beyond the host's 5");
  for (unsigned k = 1; k <= layout.max_block; ++k)
    layout.entry[k] = ap::entry_word(program, "block" + std::to_string(k));
  return layout;
}

PixelTriangle::PixelTriangle(const gl::Triangle& triangle, bool flat, unsigned tex_width, unsigned tex_height,
                             const PixelBox& box, unsigned unit)
    : m_box(box) {
  int64_t x[3], y[3];
  for (unsigned i = 0; i < 3; ++i) {
    x[i] = triangle.v[i].x;
    y[i] = triangle.v[i].y;
    if (std::llabs(x[i]) > COORDINATE_LIMIT || std::llabs(y[i]) > COORDINATE_LIMIT) return;
  }
  const int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  if (area == 0) return;
  m_area = std::llabs(area);
  // Edge i runs from vertex i to vertex i + 1; (x - px) dy - (y - py) dx is
  // negative inside a counter-clockwise triangle (positive area), so its
  // sign is flipped there. Edge i is then vertex i + 2's barycentric weight
  // times m_area.
  const int64_t sign = area > 0 ? -1 : 1;
  for (unsigned i = 0; i < 3; ++i) {
    const unsigned next = (i + 1) % 3;
    const int64_t dx = x[next] - x[i], dy = y[next] - y[i];
    Edge& edge = m_edges[i];
    edge.a = sign * dy;
    edge.b = -sign * dx;
    edge.c = sign * (y[i] * dx - x[i] * dy);
    edge.top_left = edge.a > 0 || (edge.a == 0 && edge.b < 0);
  }
  const int64_t y_lo = std::min({y[0], y[1], y[2]}), y_hi = std::max({y[0], y[1], y[2]});
  m_y_min = static_cast<int>(std::max<int64_t>(box.y0, ceil_div(y_lo - 8, 16)));
  m_y_max = static_cast<int>(std::min<int64_t>(box.y1, floor_div(y_hi - 8, 16)));
  if (m_y_min > m_y_max || box.x0 > box.x1) return;

  for (unsigned i = 0; i < 3; ++i) {
    const gl::ScreenVertex& v = triangle.v[i];
    const gl::ScreenVertex& colour = flat ? triangle.v[2] : v;
    m_x[i] = static_cast<double>(v.x) / 16.0;
    m_y[i] = static_cast<double>(v.y) / 16.0;
    m_z[i] = v.z;
    const uint8_t channels[4] = {colour.r, colour.g, colour.b, colour.a};
    for (unsigned k = 0; k < 4; ++k) m_vertex[k][i] = 256.0 * channels[k];
    m_vertex[static_cast<unsigned>(Attribute::s)][i] = static_cast<double>(v.tex[unit].s) * tex_width * 256.0;
    m_vertex[static_cast<unsigned>(Attribute::t)][i] = static_cast<double>(v.tex[unit].t) * tex_height * 256.0;
    m_vertex[static_cast<unsigned>(Attribute::z)][i] = static_cast<double>(v.z) / 256.0;
  }
  m_valid = true;
}

bool PixelTriangle::span(int j, int& first, int& last) const {
  if (!m_valid || j < m_y_min || j > m_y_max) return false;
  int64_t lo = m_box.x0, hi = m_box.x1;
  const int64_t y16 = 16 * int64_t{j} + 8;
  for (const Edge& edge : m_edges) {
    // Pixel i is inside the edge if a (16 i + 8) + k >= t.
    const int64_t k = edge.b * y16 + edge.c, t = edge.top_left ? 0 : 1;
    const int64_t n = t - k - 8 * edge.a;
    if (edge.a > 0)
      lo = std::max(lo, ceil_div(n, 16 * edge.a));
    else if (edge.a < 0)
      hi = std::min(hi, floor_div(n, 16 * edge.a));
    else if (k < t)
      return false;
  }
  if (lo > hi) return false;
  first = static_cast<int>(lo);
  last = static_cast<int>(hi);
  return true;
}

uint16_t PixelTriangle::depth16(int i, int j) const {
  const int64_t x16 = 16 * int64_t{i} + 8, y16 = 16 * int64_t{j} + 8;
  Wide sum = 0;
  for (unsigned e = 0; e < 3; ++e) {
    const Edge& edge = m_edges[e];
    sum += Wide{edge.a * x16 + edge.b * y16 + edge.c} * m_z[(e + 2) % 3];
  }
  // Inside the triangle every weight is >= 0, so the quotient is the floor.
  const auto z24 = static_cast<int64_t>(sum / m_area);
  return static_cast<uint16_t>(std::clamp<int64_t>(z24, 0, 0xffffff) >> 8);
}

TriangleValues PixelTriangle::values(int ox, int oy) const {
  TriangleValues result;
  const double x1 = m_x[1] - m_x[0], y1 = m_y[1] - m_y[0], x2 = m_x[2] - m_x[0], y2 = m_y[2] - m_y[0];
  const double det = x1 * y2 - x2 * y1;
  const double px = ox + 0.5 - m_x[0], py = oy + 0.5 - m_y[0];
  for (unsigned k = 0; k < ATTRIBUTES; ++k) {
    const std::array<double, 3>& v = m_vertex[k];
    const double gx = ((v[1] - v[0]) * y2 - (v[2] - v[0]) * y1) / det;
    const double gy = ((v[2] - v[0]) * x1 - (v[1] - v[0]) * x2) / det;
    // Colour is rounded by adding a half once, here: the host takes the
    // integer part of what the array returns.
    const double bias = k <= static_cast<unsigned>(Attribute::alpha) ? 128.0 : 0.0;
    // Non-finite texture coordinates from the application give 0.
    const double c0 = v[0] + gx * px + gy * py + bias;
    auto wrapped = [](double value) {
      return std::isfinite(value)
                 ? static_cast<uint32_t>(static_cast<int64_t>(std::fmod(std::floor(value + 0.5), 16777216.0))) &
                       0xffffffu
                 : 0u;
    };
    auto clamped = [](double value) {
      return std::isfinite(value) ? static_cast<int16_t>(std::clamp(std::floor(value + 0.5), -32768.0, 32767.0))
                                  : int16_t{0};
    };
    auto fits = [](double value) { return std::isfinite(value) && std::abs(std::floor(value + 0.5)) <= 32767.0; };
    result.c0[k] = wrapped(c0);
    result.gx[k] = clamped(gx);
    result.gy[k] = clamped(gy);
    result.clamped[k] = !fits(gx) || !fits(gy);
  }
  return result;
}

}  // namespace tessera::ap_pixel
