#include "renderers/ap_tile/tile_setup.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>

#include "renderers/common/texel_fixed.h"

namespace tessera::ap_tile {

namespace {

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

// The ranges below follow from the vertices' bound: |x|, |y| <= 2^14
// (COORDINATE_LIMIT), and pixel centres of a frame of at most 512 pixels,
// in [8, 8184]. Every point involved lies in a square of side 2^15, so any
// difference of coordinates is at most 2^15 in magnitude and twice the
// area of a triangle of such points (the doubled area itself, an edge
// function's raw value, a barycentric numerator) at most 2^30: a triangle
// inside a square covers at most half of it.

namespace {

// 255 as a Divisor, made once: the colour planes' denominator.
constexpr Divisor BY_255{255};

int32_t magnitude(int32_t v) {
  return v < 0 ? -v : v;
}

// floor(n / 16): an arithmetic shift (GCC and clang shift signed values
// arithmetically).
int32_t floor16(int32_t n) {
  return n >> 4;
}

}  // namespace

TriangleSetup::TriangleSetup(const gl::Triangle& triangle, const DrawFlags& flags, const FrameGeometry& frame)
    : m_frame(frame), m_flags(flags) {
  if (frame.width() > MAX_FRAME || frame.height() > MAX_FRAME) return;
  for (unsigned i = 0; i < 3; ++i) {
    m_x[i] = triangle.v[i].x;
    m_y[i] = triangle.v[i].y;
    if (magnitude(m_x[i]) > COORDINATE_LIMIT || magnitude(m_y[i]) > COORDINATE_LIMIT) return;
  }
  const int32_t dx1 = m_x[1] - m_x[0], dy1 = m_y[1] - m_y[0];
  const int32_t dx2 = m_x[2] - m_x[0], dy2 = m_y[2] - m_y[0];
  m_area = int64_t{dx1} * dy2 - int64_t{dy1} * dx2;  // |area| <= 2^30
  if (m_area == 0) return;
  m_area_divisor = Divisor(static_cast<uint32_t>(m_area < 0 ? -m_area : m_area));
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
    edge.norm = std::max(magnitude(edge.dx), magnitude(edge.dy));  // <= 2^15
    edge.sign = sign;
    m_norms[i] = Divisor(static_cast<uint32_t>(edge.norm));
    // |512 dy| <= 2^24; the quotients are at most 512.
    edge.a = static_cast<int32_t>(m_norms[i].round_divide(int64_t{512} * sign * edge.dy));
    edge.b = static_cast<int32_t>(m_norms[i].round_divide(int64_t{-512} * sign * edge.dx));
    // The exact inward normal decides the ownership of pixels on the edge
    // (the arm back end's rule): a left edge (inside at greater x) or a
    // horizontal top edge (inside below it).
    const int32_t exact_a = sign * edge.dy, exact_b = -sign * edge.dx;
    edge.top_left = exact_a > 0 || (exact_a == 0 && exact_b < 0);
  }
  const int32_t x_lo = std::min({m_x[0], m_x[1], m_x[2]}), x_hi = std::max({m_x[0], m_x[1], m_x[2]});
  const int32_t y_lo = std::min({m_y[0], m_y[1], m_y[2]}), y_hi = std::max({m_y[0], m_y[1], m_y[2]});
  // Pixels whose centres (16 i + 8) lie in the box, clamped to the frame.
  m_x_min = static_cast<int>(std::max<int32_t>(0, -floor16(-(x_lo - 8))));
  m_x_max = static_cast<int>(std::min<int32_t>(static_cast<int32_t>(frame.width()) - 1, floor16(x_hi - 8)));
  m_y_min = static_cast<int>(std::max<int32_t>(0, -floor16(-(y_lo - 8))));
  m_y_max = static_cast<int>(std::min<int32_t>(static_cast<int32_t>(frame.height()) - 1, floor16(y_hi - 8)));

  // Depth in z24 (< 2^24), colour channels in 0.8, texture coordinates in
  // 1/4096 texel: each plane's value at vertex 0 and its differences.
  const auto plane = [](int32_t v0, int32_t v1, int32_t v2) { return Plane{v0, v1 - v0, v2 - v0}; };
  const gl::ScreenVertex* colour_of[3] = {&triangle.v[0], &triangle.v[1], &triangle.v[2]};
  if (flags.flat) colour_of[0] = colour_of[1] = colour_of[2] = &triangle.v[2];
  m_z = plane(static_cast<int32_t>(triangle.v[0].z), static_cast<int32_t>(triangle.v[1].z),
              static_cast<int32_t>(triangle.v[2].z));
  m_color[0] = plane(colour_of[0]->r, colour_of[1]->r, colour_of[2]->r);
  m_color[1] = plane(colour_of[0]->g, colour_of[1]->g, colour_of[2]->g);
  m_color[2] = plane(colour_of[0]->b, colour_of[1]->b, colour_of[2]->b);
  if (flags.tex != 0) {
    // s x width and t x height in 1/4096 texel; the 8.8 code wraps
    // every 256 texels (2^20 units): renderers/common/texel_fixed.h.
    const float scale[2] = {static_cast<float>(flags.tex_width) * 4096.0f,
                            static_cast<float>(flags.tex_height) * 4096.0f};
    for (unsigned k = 0; k < 2; ++k) {
      float st[3];
      for (unsigned i = 0; i < 3; ++i) {
        const gl::TexCoord& tc = triangle.v[i].tex[flags.tex_unit];
        st[i] = k == 0 ? tc.s : tc.t;
      }
      int32_t v[3];
      renderers::texel_fixed(st, scale[k], 20, v);
      m_tex[k] = plane(v[0], v[1], v[2]);
    }
  }

  // The steps per pixel left (x - 1) and per row up (y + 1).
  m_zdu = static_cast<uint32_t>(depth_value(step_numerator(m_z, -16, 0))) & 0xffffffu;
  m_zdv = static_cast<uint32_t>(depth_value(step_numerator(m_z, 0, 16))) & 0xffffffu;
  const unsigned color_max[3] = {31, 63, 31};
  for (unsigned k = 0; k < 3; ++k) {
    m_cdu[k] = static_cast<uint16_t>(colour_value(step_numerator(m_color[k], -16, 0), color_max[k]));
    m_cdv[k] = static_cast<uint16_t>(colour_value(step_numerator(m_color[k], 0, 16), color_max[k]));
  }
  if (flags.tex != 0)
    for (unsigned k = 0; k < 2; ++k) {
      m_stdu[k] = static_cast<uint16_t>(texel_value(step_numerator(m_tex[k], -16, 0)));
      m_stdv[k] = static_cast<uint16_t>(texel_value(step_numerator(m_tex[k], 0, 16)));
    }
  m_valid = true;
}

int32_t TriangleSetup::edge_at(unsigned e, int32_t x16, int32_t y16) const {
  const Edge& edge = m_edges[e];
  // Twice the area of (pixel, start, start + direction): |raw| <= 2^30,
  // and |value| <= 32 (|x - px| + |y - py|) < 2^21.
  const int64_t raw = int64_t{x16 - edge.px} * edge.dy - int64_t{y16 - edge.py} * edge.dx;
  const auto value = static_cast<int32_t>(m_norms[e].round_divide(32 * edge.sign * raw));
  return edge.top_left ? value : value - 1;
}

int32_t TriangleSetup::corner_x16(unsigned c) const {
  return 16 * static_cast<int32_t>((c + 1) * m_frame.tile_width - 1) + 8;
}

int32_t TriangleSetup::corner_y16(unsigned r) const {
  return 16 * static_cast<int32_t>(m_frame.height() - (r + 1) * m_frame.tile_height) + 8;
}

TriangleSetup::EdgeInTile TriangleSetup::edge_in_tile(unsigned e, unsigned c, unsigned r) const {
  EdgeInTile t;
  t.e0 = edge_at(e, corner_x16(c), corner_y16(r));
  t.du = -m_edges[e].a;
  t.dv = m_edges[e].b;
  const auto last_u = static_cast<int32_t>(m_frame.tile_width - 1),
             last_v = static_cast<int32_t>(m_frame.tile_height - 1);
  const int32_t corners[] = {t.e0, t.e0 + last_u * t.du, t.e0 + last_v * t.dv, t.e0 + last_u * t.du + last_v * t.dv};
  t.low = *std::min_element(std::begin(corners), std::end(corners));
  t.high = *std::max_element(std::begin(corners), std::end(corners));
  return t;
}

bool TriangleSetup::in_box(unsigned c, unsigned r) const {
  if (!m_valid || c >= m_frame.columns || r >= m_frame.rows) return false;
  if (m_x_max < m_x_min || m_y_max < m_y_min) return false;  // no pixel centre in the box
  const int x0 = static_cast<int>(c * m_frame.tile_width), x1 = x0 + static_cast<int>(m_frame.tile_width) - 1;
  const int y0 = static_cast<int>(m_frame.height() - (r + 1) * m_frame.tile_height);
  const int y1 = y0 + static_cast<int>(m_frame.tile_height) - 1;
  return !(x1 < m_x_min || x0 > m_x_max || y1 < m_y_min || y0 > m_y_max);
}

bool TriangleSetup::overlaps(unsigned c, unsigned r) const {
  if (!in_box(c, r)) return false;
  for (unsigned e = 0; e < 3; ++e)
    if (edge_in_tile(e, c, r).high < 0) return false;
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

// plane(x, y) * area = v0 area + d1 w1 + d2 w2, with w1 and w2 the
// barycentric numerators (|w| <= 2^30). Depth: |v0|, |d| < 2^24, so the
// sum stays below 3 x 2^54; colour below 3 x 2^38; texture coordinates
// (|v0| <= 2^20, |d| < 2^30) below 2^62.
int64_t TriangleSetup::plane_numerator(const Plane& plane, int32_t w1, int32_t w2) const {
  const int64_t n = int64_t{plane.v0} * static_cast<int32_t>(m_area) + int64_t{plane.d1} * w1 + int64_t{plane.d2} * w2;
  return m_area < 0 ? -n : n;
}

// The plane's change over (dx16, dy16) times the area: (cx dx16 + cy dy16)
// with cx = d1 dy2 - d2 dy1, cy = d2 dx1 - d1 dx2 (|cx|, |cy| < 2^40 for
// depth, 2^46 for texture coordinates; a step is 16 sixteenths).
int64_t TriangleSetup::step_numerator(const Plane& plane, int dx16, int dy16) const {
  const int32_t dx1 = m_x[1] - m_x[0], dy1 = m_y[1] - m_y[0];
  const int32_t dx2 = m_x[2] - m_x[0], dy2 = m_y[2] - m_y[0];
  const int64_t cx = int64_t{plane.d1} * dy2 - int64_t{plane.d2} * dy1;
  const int64_t cy = int64_t{plane.d2} * dx1 - int64_t{plane.d1} * dx2;
  const int64_t n = cx * dx16 + cy * dy16;
  return m_area < 0 ? -n : n;
}

TriangleSetup::Scaled TriangleSetup::scale(int64_t numerator, uint32_t m) const {
  // numerator = q |area| + r; r m = q2 |area| + rest (r m < 2^30 x 2^16).
  const Divisor::Floor f = m_area_divisor.floor_divide(numerator);
  const Divisor::Unsigned g = m_area_divisor.divide(uint64_t{f.remainder} * m);
  // q m + q2 wraps modulo 2^64 for depth's large q (2^56 x 65535), whose
  // code is taken modulo 2^24 from bits the wrap keeps.
  return {static_cast<int64_t>(static_cast<uint64_t>(f.quotient) * m + g.quotient), g.remainder};
}

namespace {

// k + (fraction g / d) rounded, halves away from zero: up at g / d >= 1/2
// when the whole value is positive, above 1/2 when it is negative.
int64_t round_fraction(int64_t k, uint64_t g, uint64_t d, bool negative) {
  return k + ((negative ? 2 * g > d : 2 * g >= d) ? 1 : 0);
}

}  // namespace

// numerator / area x 65535 / 65536 = k + (l area + rest) / (65536 area)
// with whole = 65536 k + l: round(numerator x 65535 / (65536 area)),
// halves away from zero, modulo 2^24 (l area < 2^46).
int64_t TriangleSetup::depth_value(int64_t numerator) const {
  const Scaled s = scale(numerator, 65535);
  const uint64_t area = m_area_divisor.value();
  const uint64_t l = static_cast<uint64_t>(s.whole) & 0xffffu;
  return round_fraction(s.whole >> 16, l * area + s.rest, area << 16, numerator < 0);
}

// round(numerator x max x 256 / (255 area)): whole = 255 k + l (whole <
// 2^55), the fraction (l area + rest) / (255 area).
int64_t TriangleSetup::colour_value(int64_t numerator, unsigned max) const {
  const Scaled s = scale(numerator, max * 256);
  const uint64_t area = m_area_divisor.value();
  const Divisor::Floor k = BY_255.floor_divide(s.whole);
  return round_fraction(k.quotient, uint64_t{k.remainder} * area + s.rest, 255 * area, numerator < 0);
}

// numerator / area in 1/4096 texel to 8.8 texels, rounded (halves up).
int64_t TriangleSetup::texel_value(int64_t numerator) const {
  return (m_area_divisor.floor_divide(numerator).quotient + 8) >> 4;
}

TileRecord TriangleSetup::record(unsigned c, unsigned r) const {
  TileRecord record;
  if (!in_box(c, r)) return record;
  EdgeInTile edges[3];
  for (unsigned e = 0; e < 3; ++e) {
    edges[e] = edge_in_tile(e, c, r);
    if (edges[e].high < 0) return record;
  }
  record.live = true;
  for (unsigned e = 0; e < 3; ++e) {
    const EdgeInTile& t = edges[e];
    if (t.low >= 0) continue;  // the whole tile is inside this edge: E = 0 everywhere
    // The edge crosses the tile, so every value in it lies within the
    // tile's span of the function: |E| <= 7 * 512 + 35 * 512 < 2^15.
    record.e0[e] = static_cast<int16_t>(t.e0);
    record.edu[e] = static_cast<int16_t>(t.du);
    record.edv[e] = static_cast<int16_t>(t.dv);
  }
  // The barycentric numerators of the tile's corner pixel: twice the areas
  // of (corner, vertex 0, vertex 2) and (corner, vertex 0, vertex 1),
  // |w| <= 2^30.
  const int32_t dx = corner_x16(c) - m_x[0], dy = corner_y16(r) - m_y[0];
  const auto w1 = static_cast<int32_t>(int64_t{m_y[2] - m_y[0]} * dx - int64_t{m_x[2] - m_x[0]} * dy);
  const auto w2 = static_cast<int32_t>(int64_t{m_x[1] - m_x[0]} * dy - int64_t{m_y[1] - m_y[0]} * dx);
  // Depth and colour carry half a unit (128 in x.8) for the CU's truncation.
  record.z0 = static_cast<uint32_t>(depth_value(plane_numerator(m_z, w1, w2)) + 128) & 0xffffffu;
  record.zdu = m_zdu;
  record.zdv = m_zdv;
  const unsigned color_max[3] = {31, 63, 31};
  for (unsigned k = 0; k < 3; ++k) {
    record.c0[k] = static_cast<uint16_t>(colour_value(plane_numerator(m_color[k], w1, w2), color_max[k]) + 128);
    record.cdu[k] = m_cdu[k];
    record.cdv[k] = m_cdv[k];
  }
  if (m_flags.tex != 0)
    for (unsigned k = 0; k < 2; ++k) {
      record.st0[k] = static_cast<uint16_t>(texel_value(plane_numerator(m_tex[k], w1, w2)));
      record.stdu[k] = m_stdu[k];
      record.stdv[k] = m_stdv[k];
    }
  record.tex = m_flags.tex;
  record.zoff = !m_flags.depth_test;
  record.zlequal = m_flags.depth_lequal;
  record.zwrite = m_flags.depth_test && m_flags.depth_write;
  return record;
}

namespace {

// A 16.8 step (24 bits, wrapping) to the nearest whole unit, halves away
// from zero, as a signed value.
int32_t round_16_8(uint32_t step) {
  const int32_t v = static_cast<int32_t>(step << 8) >> 8;
  return v >= 0 ? (v + 128) >> 8 : -((-v + 128) >> 8);
}

}  // namespace

StudyRecord TriangleSetup::study_record(unsigned c, unsigned r) const {
  StudyRecord study;
  const TileRecord tuned = record(c, r);
  if (!tuned.live) return study;
  study.live = true;
  const auto last_x = static_cast<int32_t>(m_frame.tile_width - 1),
             last_y = static_cast<int32_t>(m_frame.tile_height - 1);
  for (unsigned e = 0; e < 3; ++e) {
    // The tuned record steps left (du) and up (dv) from the bottom-right
    // pixel; the study's line steps right and down from the top-left one.
    // A line that crosses the tile has every value in it below 2^15 in
    // magnitude (record()), the top-left one too; a tile wholly inside
    // gets 0, 0, 0.
    study.a[e] = static_cast<int16_t>(-tuned.edu[e]);
    study.b[e] = static_cast<int16_t>(-tuned.edv[e]);
    study.c[e] = static_cast<int16_t>(tuned.e0[e] + last_x * tuned.edu[e] + last_y * tuned.edv[e]);
  }
  // Depth: the integer part of the 16.8 value (its half unit is in z0
  // already), the steps rounded to whole units.
  study.z = static_cast<uint16_t>(tuned.z0 >> 8);
  study.z_dx = static_cast<uint16_t>(-round_16_8(tuned.zdu));
  study.z_dy = static_cast<uint16_t>(-round_16_8(tuned.zdv));
  // Colour in 8.8 of 0..255, plus half a unit for the CU's truncation.
  const int32_t dx = corner_x16(c) - m_x[0], dy = corner_y16(r) - m_y[0];
  const auto w1 = static_cast<int32_t>(int64_t{m_y[2] - m_y[0]} * dx - int64_t{m_x[2] - m_x[0]} * dy);
  const auto w2 = static_cast<int32_t>(int64_t{m_x[1] - m_x[0]} * dy - int64_t{m_y[1] - m_y[0]} * dx);
  for (unsigned k = 0; k < 3; ++k) {
    study.colour[k] = static_cast<uint16_t>(colour_value(plane_numerator(m_color[k], w1, w2), 255) + 128);
    study.c_dx[k] = static_cast<uint16_t>(colour_value(step_numerator(m_color[k], 16, 0), 255));
    study.c_dy[k] = static_cast<uint16_t>(colour_value(step_numerator(m_color[k], 0, -16), 255));
  }
  for (unsigned k = 0; k < 2; ++k) {
    study.st[k] = tuned.st0[k];
    study.st_dx[k] = static_cast<uint16_t>(-tuned.stdu[k]);
    study.st_dy[k] = static_cast<uint16_t>(-tuned.stdv[k]);
  }
  study.tex = tuned.tex;
  study.depth_test = !tuned.zoff;
  return study;
}

}  // namespace tessera::ap_tile
