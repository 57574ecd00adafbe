#include "renderers/ap_tile/tile_setup.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>

#include "renderers/common/wide_int.h"

namespace tessera::ap_tile {

namespace {

using Wide = Int128;  // products of 2^23 coordinates and 2^46 areas

// n / d rounded to nearest, halves away from zero: round(-q) = -round(q), so
// two triangles that share an edge get exactly opposite edge values.
int64_t round_div(Wide n, Wide d) {
  if (d < 0) n = -n, d = -d;
  const Wide q = (n >= 0 ? n + d / 2 : n - d / 2) / d;
  return static_cast<int64_t>(q);
}

int64_t floor_div(int64_t n, int64_t d) {
  return n >= 0 ? n / d : -((-n + d - 1) / d);
}

// Vertices beyond this many pixels are refused, as in the arm back end: the
// clipper keeps them far inside, and the products below stay in range.
constexpr int64_t COORDINATE_LIMIT = int64_t{1} << 22;  // 2^18 pixels in 1/16

uint16_t variable(const ap::Program& program, const char* name, unsigned size) {
  return ap::variable_address(program, name, size);
}

int constant(const ap::Program& program, const char* name) {
  return ap::constant_value(program, name);
}

void put16(uint8_t* at, uint16_t value) {
  at[0] = static_cast<uint8_t>(value >> 8);
  at[1] = static_cast<uint8_t>(value);
}

void put24(uint8_t* at, uint32_t value) {
  at[0] = static_cast<uint8_t>(value >> 16);
  at[1] = static_cast<uint8_t>(value >> 8);
  at[2] = static_cast<uint8_t>(value);
}

uint8_t flag(bool value) {
  return value ? 0xff : 0x00;
}

}  // namespace

CmemLayout CmemLayout::of(const ap::Program& program) {
  CmemLayout layout;
  layout.tile_width = static_cast<unsigned>(constant(program, "TILE_W"));
  layout.tile_height = static_cast<unsigned>(constant(program, "TILE_H"));
  const unsigned pixels = layout.tile_width * layout.tile_height;
  for (auto [field, name] : {std::pair{&CmemLayout::chi, "chi"},
                             {&CmemLayout::clo, "clo"},
                             {&CmemLayout::zhi, "zhi"},
                             {&CmemLayout::zlo, "zlo"},
                             {&CmemLayout::shi, "shi"},
                             {&CmemLayout::slo, "slo"},
                             {&CmemLayout::thi, "thi"},
                             {&CmemLayout::tlo, "tlo"},
                             {&CmemLayout::tid, "tid"},
                             {&CmemLayout::we, "we"}})
    layout.*field = variable(program, name, pixels);
  struct Field {
    uint16_t CmemLayout::*member;
    const char* name;
    unsigned size;
  };
  const Field record[] = {
      {&CmemLayout::live, "live", 1}, {&CmemLayout::e0, "e0", 6},        {&CmemLayout::edu, "edu", 6},
      {&CmemLayout::edv, "edv", 6},   {&CmemLayout::z0, "z0", 3},        {&CmemLayout::zdu, "zdu", 3},
      {&CmemLayout::zdv, "zdv", 3},   {&CmemLayout::c0, "c0", 6},        {&CmemLayout::cdu, "cdu", 6},
      {&CmemLayout::cdv, "cdv", 6},   {&CmemLayout::st0, "st0", 4},      {&CmemLayout::stdu, "stdu", 4},
      {&CmemLayout::stdv, "stdv", 4}, {&CmemLayout::tex, "tex", 1},      {&CmemLayout::zlequal, "zlequal", 1},
      {&CmemLayout::zoff, "zoff", 1}, {&CmemLayout::zwrite, "zwrite", 1}};
  unsigned first = ~0u, end = 0, bytes = 0;
  for (const Field& field : record) {
    layout.*field.member = variable(program, field.name, field.size);
    first = std::min<unsigned>(first, layout.*field.member);
    end = std::max<unsigned>(end, layout.*field.member + field.size);
    bytes += field.size;
  }
  if (end - first != bytes)
    throw std::invalid_argument(program.source_name +
                                ": the triangle record (live .. zwrite) is not contiguous in CMEM");
  layout.record_first = static_cast<uint16_t>(first);
  layout.record_bytes = static_cast<uint16_t>(bytes);
  layout.yc = variable(program, "yc", layout.tile_height);
  layout.zero = variable(program, "zero", 1);
  layout.clear_c = variable(program, "clear_c", 2);
  layout.clear_z = variable(program, "clear_z", 2);
  return layout;
}

void encode_record(const TileRecord& record, const CmemLayout& layout, uint8_t* bytes) {
  auto at = [&](uint16_t address) { return bytes + (address - layout.record_first); };
  *at(layout.live) = flag(record.live);
  for (unsigned e = 0; e < 3; ++e) {
    put16(at(layout.e0) + 2 * e, static_cast<uint16_t>(record.e0[e]));
    put16(at(layout.edu) + 2 * e, static_cast<uint16_t>(record.edu[e]));
    put16(at(layout.edv) + 2 * e, static_cast<uint16_t>(record.edv[e]));
    put16(at(layout.c0) + 2 * e, record.c0[e]);
    put16(at(layout.cdu) + 2 * e, record.cdu[e]);
    put16(at(layout.cdv) + 2 * e, record.cdv[e]);
  }
  put24(at(layout.z0), record.z0);
  put24(at(layout.zdu), record.zdu);
  put24(at(layout.zdv), record.zdv);
  for (unsigned k = 0; k < 2; ++k) {
    put16(at(layout.st0) + 2 * k, record.st0[k]);
    put16(at(layout.stdu) + 2 * k, record.stdu[k]);
    put16(at(layout.stdv) + 2 * k, record.stdv[k]);
  }
  *at(layout.tex) = record.tex;
  *at(layout.zlequal) = flag(record.zlequal);
  *at(layout.zoff) = flag(record.zoff);
  *at(layout.zwrite) = flag(record.zwrite);
}

TriangleSetup::TriangleSetup(const gl::Triangle& triangle, const DrawFlags& flags, const FrameGeometry& frame)
    : m_frame(frame), m_flags(flags) {
  for (unsigned i = 0; i < 3; ++i) {
    m_x[i] = triangle.v[i].x;
    m_y[i] = triangle.v[i].y;
    if (std::llabs(m_x[i]) > COORDINATE_LIMIT || std::llabs(m_y[i]) > COORDINATE_LIMIT) return;
  }
  m_area = (m_x[1] - m_x[0]) * (m_y[2] - m_y[0]) - (m_y[1] - m_y[0]) * (m_x[2] - m_x[0]);
  if (m_area == 0) return;
  // Edge i runs from vertex i to vertex i + 1; the raw function
  // (x - px) dy - (y - py) dx is negative inside a counter-clockwise
  // triangle (positive area), so its sign is flipped there.
  const int sign = m_area > 0 ? -1 : 1;
  for (unsigned i = 0; i < 3; ++i) {
    Edge& edge = m_edges[i];
    const unsigned next = (i + 1) % 3;
    edge.px = m_x[i];
    edge.py = m_y[i];
    edge.dx = m_x[next] - m_x[i];
    edge.dy = m_y[next] - m_y[i];
    edge.norm = std::max(std::llabs(edge.dx), std::llabs(edge.dy));
    edge.sign = sign;
    edge.a = static_cast<int32_t>(round_div(Wide{512} * sign * edge.dy, edge.norm));
    edge.b = static_cast<int32_t>(round_div(Wide{-512} * sign * edge.dx, edge.norm));
    // The exact inward normal decides the ownership of pixels on the edge
    // (the arm back end's rule): a left edge (inside at greater x) or a
    // horizontal top edge (inside below it).
    const int64_t exact_a = sign * edge.dy, exact_b = -sign * edge.dx;
    edge.top_left = exact_a > 0 || (exact_a == 0 && exact_b < 0);
  }
  const int64_t x_lo = std::min({m_x[0], m_x[1], m_x[2]}), x_hi = std::max({m_x[0], m_x[1], m_x[2]});
  const int64_t y_lo = std::min({m_y[0], m_y[1], m_y[2]}), y_hi = std::max({m_y[0], m_y[1], m_y[2]});
  // Pixels whose centres (16 i + 8) lie in the box, clamped to the frame.
  m_x_min = static_cast<int>(std::max<int64_t>(0, -floor_div(-(x_lo - 8), 16)));
  m_x_max = static_cast<int>(std::min<int64_t>(frame.width() - 1, floor_div(x_hi - 8, 16)));
  m_y_min = static_cast<int>(std::max<int64_t>(0, -floor_div(-(y_lo - 8), 16)));
  m_y_max = static_cast<int>(std::min<int64_t>(frame.height() - 1, floor_div(y_hi - 8, 16)));

  // Depth: z24 * 65535 / 65536 in 16.8, so that with the half added for
  // rounding every inside pixel stays below 2^24 (README.md, "Fixed point").
  m_z.num = 65535;
  m_z.den = 65536;
  m_z.fraction = 0;
  m_z.bias = 128;
  const unsigned color_max[3] = {31, 63, 31};
  for (unsigned i = 0; i < 3; ++i) {
    const gl::ScreenVertex& v = flags.flat ? triangle.v[2] : triangle.v[i];
    m_z.v[i] = triangle.v[i].z;
    const uint8_t channel[3] = {v.r, v.g, v.b};
    for (unsigned k = 0; k < 3; ++k) {
      m_color[k].v[i] = channel[k];
      m_color[k].num = color_max[k];
      m_color[k].den = 255;
      m_color[k].fraction = 8;
      m_color[k].bias = 128;
    }
    m_tex[0][i] = static_cast<double>(triangle.v[i].tex[flags.tex_unit].s) * flags.tex_width * 256.0;
    m_tex[1][i] = static_cast<double>(triangle.v[i].tex[flags.tex_unit].t) * flags.tex_height * 256.0;
  }
  m_valid = true;
}

int64_t TriangleSetup::edge_at(const Edge& edge, int64_t x16, int64_t y16) const {
  const Wide raw = Wide{x16 - edge.px} * edge.dy - Wide{y16 - edge.py} * edge.dx;
  const int64_t value = round_div(Wide{32} * edge.sign * raw, edge.norm);
  return edge.top_left ? value : value - 1;
}

int64_t TriangleSetup::corner_x16(unsigned c) const {
  return 16 * int64_t{(c + 1) * m_frame.tile_width - 1} + 8;
}

int64_t TriangleSetup::corner_y16(unsigned r) const {
  return 16 * int64_t{m_frame.height() - (r + 1) * m_frame.tile_height} + 8;
}

TriangleSetup::EdgeInTile TriangleSetup::edge_in_tile(const Edge& edge, unsigned c, unsigned r) const {
  EdgeInTile t;
  t.e0 = edge_at(edge, corner_x16(c), corner_y16(r));
  t.du = -int64_t{edge.a};
  t.dv = edge.b;
  const int64_t last_u = m_frame.tile_width - 1, last_v = m_frame.tile_height - 1;
  const int64_t corners[] = {t.e0, t.e0 + last_u * t.du, t.e0 + last_v * t.dv, t.e0 + last_u * t.du + last_v * t.dv};
  t.low = *std::min_element(std::begin(corners), std::end(corners));
  t.high = *std::max_element(std::begin(corners), std::end(corners));
  return t;
}

bool TriangleSetup::overlaps(unsigned c, unsigned r) const {
  if (!m_valid || c >= m_frame.columns || r >= m_frame.rows) return false;
  const int x0 = static_cast<int>(c * m_frame.tile_width), x1 = x0 + static_cast<int>(m_frame.tile_width) - 1;
  const int y0 = static_cast<int>(m_frame.height() - (r + 1) * m_frame.tile_height);
  const int y1 = y0 + static_cast<int>(m_frame.tile_height) - 1;
  if (x1 < m_x_min || x0 > m_x_max || y1 < m_y_min || y0 > m_y_max) return false;
  for (const Edge& edge : m_edges)
    if (edge_in_tile(edge, c, r).high < 0) return false;
  return true;
}

std::vector<unsigned> TriangleSetup::tiles() const {
  std::vector<unsigned> result;
  if (!m_valid || m_x_max < m_x_min || m_y_max < m_y_min) return result;
  const unsigned c0 = static_cast<unsigned>(m_x_min) / m_frame.tile_width;
  const unsigned c1 = static_cast<unsigned>(m_x_max) / m_frame.tile_width;
  // GL rows to tile rows (tile row 0 at the top).
  const unsigned r0 = (m_frame.height() - 1 - static_cast<unsigned>(m_y_max)) / m_frame.tile_height;
  const unsigned r1 = (m_frame.height() - 1 - static_cast<unsigned>(m_y_min)) / m_frame.tile_height;
  for (unsigned r = r0; r <= r1; ++r)
    for (unsigned c = c0; c <= c1; ++c)
      if (overlaps(c, r)) result.push_back(r * m_frame.columns + c);
  return result;
}

namespace {

// The plane's numerators: value = v0 + (cx (x - x0) + cy (y - y0)) / area.
std::pair<Wide, Wide> plane_numerators(const Plane& plane, const int64_t* x, const int64_t* y) {
  const Wide dv1 = plane.v[1] - plane.v[0], dv2 = plane.v[2] - plane.v[0];
  return {dv1 * (y[2] - y[0]) - dv2 * (y[1] - y[0]), dv2 * (x[1] - x[0]) - dv1 * (x[2] - x[0])};
}

}  // namespace

int64_t TriangleSetup::plane_at(const Plane& plane, int64_t x16, int64_t y16) const {
  const auto [cx, cy] = plane_numerators(plane, m_x, m_y);
  const Wide numerator =
      (Wide{plane.v[0]} * m_area + cx * (x16 - m_x[0]) + cy * (y16 - m_y[0])) * plane.num * (Wide{1} << plane.fraction);
  return round_div(numerator, Wide{plane.den} * m_area) + plane.bias;
}

int64_t TriangleSetup::plane_step(const Plane& plane, int64_t dx16, int64_t dy16) const {
  const auto [cx, cy] = plane_numerators(plane, m_x, m_y);
  return round_div((cx * dx16 + cy * dy16) * plane.num * (Wide{1} << plane.fraction), Wide{plane.den} * m_area);
}

double TriangleSetup::texture_at(unsigned k, double x16, double y16) const {
  const double* v = m_tex[k];
  const double area = static_cast<double>(m_area);
  const double cx =
      (v[1] - v[0]) * static_cast<double>(m_y[2] - m_y[0]) - (v[2] - v[0]) * static_cast<double>(m_y[1] - m_y[0]);
  const double cy =
      (v[2] - v[0]) * static_cast<double>(m_x[1] - m_x[0]) - (v[1] - v[0]) * static_cast<double>(m_x[2] - m_x[0]);
  return v[0] + (cx * (x16 - static_cast<double>(m_x[0])) + cy * (y16 - static_cast<double>(m_y[0]))) / area;
}

namespace {

// A real value as a 16-bit two's complement 8.8 code, modulo 2^16.
uint16_t wrap16(double value) {
  const double wrapped = std::fmod(std::round(value), 65536.0);
  return static_cast<uint16_t>(static_cast<int64_t>(wrapped < 0 ? wrapped + 65536.0 : wrapped));
}

}  // namespace

TileRecord TriangleSetup::record(unsigned c, unsigned r) const {
  TileRecord record;
  if (!overlaps(c, r)) return record;
  record.live = true;
  const int64_t x16 = corner_x16(c), y16 = corner_y16(r);
  for (unsigned e = 0; e < 3; ++e) {
    const EdgeInTile t = edge_in_tile(m_edges[e], c, r);
    if (t.low >= 0) continue;  // the whole tile is inside this edge: E = 0 everywhere
    // The edge crosses the tile, so every value in it lies within the
    // tile's span of the function: |E| <= 7 * 512 + 35 * 512 < 2^15.
    record.e0[e] = static_cast<int16_t>(t.e0);
    record.edu[e] = static_cast<int16_t>(t.du);
    record.edv[e] = static_cast<int16_t>(t.dv);
  }
  record.z0 = static_cast<uint32_t>(plane_at(m_z, x16, y16)) & 0xffffffu;
  record.zdu = static_cast<uint32_t>(plane_step(m_z, -16, 0)) & 0xffffffu;
  record.zdv = static_cast<uint32_t>(plane_step(m_z, 0, 16)) & 0xffffffu;
  for (unsigned k = 0; k < 3; ++k) {
    record.c0[k] = static_cast<uint16_t>(plane_at(m_color[k], x16, y16));
    record.cdu[k] = static_cast<uint16_t>(plane_step(m_color[k], -16, 0));
    record.cdv[k] = static_cast<uint16_t>(plane_step(m_color[k], 0, 16));
  }
  if (m_flags.tex != 0) {
    const auto x = static_cast<double>(x16), y = static_cast<double>(y16);
    for (unsigned k = 0; k < 2; ++k) {
      const double start = texture_at(k, x, y);
      record.st0[k] = wrap16(start);
      record.stdu[k] = wrap16(texture_at(k, x - 16, y) - start);
      record.stdv[k] = wrap16(texture_at(k, x, y + 16) - start);
    }
  }
  record.tex = m_flags.tex;
  record.zoff = !m_flags.depth_test;
  record.zlequal = m_flags.depth_lequal;
  record.zwrite = m_flags.depth_test && m_flags.depth_write;
  return record;
}

}  // namespace tessera::ap_tile
