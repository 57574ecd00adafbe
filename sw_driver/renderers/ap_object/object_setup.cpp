#include "renderers/ap_object/object_setup.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "array/isa/ap_isa.h"
#include "renderers/common/named_choice.h"
#include "renderers/common/texel_fixed.h"

#include "ap_programs/ap_object_tri_w16.h"
#include "ap_programs/ap_object_tri_w32.h"
#include "ap_programs/ap_object_tri_w8.h"
#include "ap_programs/ap_object_w16.h"
#include "ap_programs/ap_object_w32.h"
#include "ap_programs/ap_object_w8.h"
#include "ap_programs/ap_object_zs_tri_w16.h"
#include "ap_programs/ap_object_zs_tri_w32.h"
#include "ap_programs/ap_object_zs_tri_w8.h"
#include "ap_programs/ap_object_zs_w16.h"
#include "ap_programs/ap_object_zs_w32.h"
#include "ap_programs/ap_object_zs_w8.h"

namespace tessera::ap_object {

// The ranges below follow from the vertices' bound, |x|, |y| <= 2^14
// sixteenths (COORDINATE_LIMIT), as in ap-pixel's set-up: differences are
// at most 2^15, an edge's a and b at most 2^15, its value at a pixel centre
// and the doubled area at most 2^31 (held in 64 bits), 16 |a| at most 2^19.
// A plane's numerators cx, cy are at most 2^41 (depth: differences below
// 2^24 times 2^16), so a plane evaluated 2^16 sixteenths away, or stepped
// by a row and 2^15 pixels, stays below 2^61: 64-bit multiplies and
// additions, and divisions by the triangle's Divisor only.

namespace {

constexpr uint32_t TWO_24 = uint32_t{1} << 24;

int32_t magnitude(int32_t v) {
  return v < 0 ? -v : v;
}

// floor(n / 16) and ceil(n / 16): arithmetic shifts.
int32_t floor16(int32_t n) {
  return n >> 4;
}
int32_t ceil16(int32_t n) {
  return -((-n) >> 4);
}

void put(uint8_t* bytes, unsigned at, uint32_t value, unsigned width) {
  for (unsigned i = 0; i < width; ++i) bytes[at + i] = static_cast<uint8_t>(value >> (8 * (width - 1 - i)));
}

}  // namespace

Unit unit_named(const std::string& name, const std::string& key) {
  return renderers::named_choice<Unit>(name, UNIT_NAMES, key, "unit");
}

ZPath zpath_named(const std::string& name, const std::string& key) {
  return renderers::named_choice<ZPath>(name, ZPATH_NAMES, key, "z path");
}

const ap::Program& program_of(Unit unit, unsigned span_class, ZPath zpath) {
  if (zpath == ZPath::unit && unit == Unit::triangle) {
    switch (span_class) {
      case 0: return ap::programs::ap_object_zs_tri_w8();
      case 1: return ap::programs::ap_object_zs_tri_w16();
      default: return ap::programs::ap_object_zs_tri_w32();
    }
  }
  if (zpath == ZPath::unit) {
    switch (span_class) {
      case 0: return ap::programs::ap_object_zs_w8();
      case 1: return ap::programs::ap_object_zs_w16();
      default: return ap::programs::ap_object_zs_w32();
    }
  }
  if (unit == Unit::triangle) {
    switch (span_class) {
      case 0: return ap::programs::ap_object_tri_w8();
      case 1: return ap::programs::ap_object_tri_w16();
      default: return ap::programs::ap_object_tri_w32();
    }
  }
  switch (span_class) {
    case 0: return ap::programs::ap_object_w8();
    case 1: return ap::programs::ap_object_w16();
    default: return ap::programs::ap_object_w32();
  }
}

ObjectLayout ObjectLayout::of(const ap::Program& program) {
  ObjectLayout m;
  m.span = static_cast<unsigned>(ap::constant_value(program, "W"));
  m.rows = static_cast<unsigned>(ap::constant_value(program, "RM"));
  m.units = static_cast<unsigned>(ap::constant_value(program, "UNITS"));
  m.rec_bytes = static_cast<unsigned>(ap::constant_value(program, "REC"));
  m.zsend = ap::constant_value(program, "ZSEND") != 0;
  m.slot_bytes = static_cast<unsigned>(ap::constant_value(program, "SLOT_BYTES"));
  m.row_bytes = static_cast<unsigned>(ap::constant_value(program, "ROW_BYTES"));
  if (m.units < 1 || m.units > 2 || m.slot_bytes != 13 || m.row_bytes != 4)
    throw std::invalid_argument(program.source_name + ": the host expects 1 or 2 units, 13-byte slots, 4-byte rows");
  m.rec = ap::variable_address(program, "rec", 2 * m.rec_bytes);
  m.cacc = ap::variable_address(program, "cacc", 8);
  if (m.zsend) {
    m.ofs = static_cast<unsigned>(ap::constant_value(program, "OFS"));
    m.yw = static_cast<unsigned>(ap::constant_value(program, "YW"));
    m.nrows = static_cast<unsigned>(ap::constant_value(program, "NROWS"));
    if (m.rows > 255 || m.nrows + 1 > m.rec_bytes)
      throw std::invalid_argument(program.source_name + ": RM beyond a byte, or NROWS beyond the record");
    m.zacc = ap::variable_address(program, "zacc", 4);
    m.pos = ap::variable_address(program, "pos", 4);
    m.pix = ap::variable_address(program, "pix", 4);
    m.konst = ap::variable_address(program, "konst", static_cast<unsigned>(std::size(ZSEND_KONST)));
  } else {
    m.region = static_cast<unsigned>(ap::constant_value(program, "REGION"));
    if (m.rows * (m.row_bytes + m.slot_bytes * m.span) > m.region)
      throw std::invalid_argument(program.source_name + ": RM rows of W pixels do not fit a region");
    m.tacc = ap::variable_address(program, "tacc", 3);
    m.out = ap::variable_address(program, "out", static_cast<unsigned>(ap::constant_value(program, "OUT_BYTES")));
    if (m.region * m.units > static_cast<unsigned>(ap::constant_value(program, "OUT_BYTES")))
      throw std::invalid_argument(program.source_name + ": the regions do not fit `out`");
  }
  unsigned* fields[] = {&m.xl,  &m.ul,   &m.ql, &m.rl,  &m.nl,   &m.xr, &m.ur,  &m.qr,   &m.rr, &m.nr,  &m.z,
                        &m.zgx, &m.zrow, &m.c,  &m.cgx, &m.crow, &m.s,  &m.sgx, &m.srow, &m.t,  &m.tgx, &m.trow};
  const char* names[] = {"XL",  "UL",   "QL", "RL",  "NL",   "XR", "UR",  "QR",   "RR", "NR",  "Z",
                         "ZGX", "ZROW", "C",  "CGX", "CROW", "S",  "SGX", "SROW", "T",  "TGX", "TROW"};
  for (unsigned i = 0; i < std::size(fields); ++i)
    *fields[i] = static_cast<unsigned>(ap::constant_value(program, names[i]));
  m.entry = ap::entry_word(program, "walk");
  // The row loops, in order: one per record (the outermost loops; a ZSEND
  // program's pixel loop is inside its row loop).
  unsigned found = 0, depth = 0;
  for (unsigned w = m.entry; w < program.words.size() && found < m.units; ++w) {
    const ap::Decoded decoded = ap::decode(program.words[w]);
    if (!decoded.error.empty()) continue;
    if (decoded.instruction.opcode == ap::Opcode::op_loop && depth++ == 0) m.loop_word[found++] = w;
    if (decoded.instruction.opcode == ap::Opcode::op_endloop) --depth;
  }
  if (found != m.units) throw std::invalid_argument(program.source_name + ": a row loop per record expected");
  for (const auto& [name, variable] : program.variables)
    m.cmem_bytes = std::max(m.cmem_bytes, unsigned{variable.address} + variable.size);
  return m;
}

void encode_record(const UnitRecord& r, const ObjectLayout& m, uint8_t* bytes) {
  std::fill(bytes, bytes + m.rec_bytes, uint8_t{0});
  put(bytes, m.xl, static_cast<uint16_t>(r.xl), 2);
  put(bytes, m.ul, r.ul, 3);
  put(bytes, m.ql, static_cast<uint16_t>(r.ql), 2);
  put(bytes, m.rl, r.rl, 3);
  put(bytes, m.nl, r.nl, 3);
  put(bytes, m.xr, static_cast<uint16_t>(r.xr), 2);
  put(bytes, m.ur, r.ur, 3);
  put(bytes, m.qr, static_cast<uint16_t>(r.qr), 2);
  put(bytes, m.rr, r.rr, 3);
  put(bytes, m.nr, r.nr, 3);
  put(bytes, m.z, r.z, 4);
  put(bytes, m.zgx, r.zgx, 4);
  put(bytes, m.zrow, r.zrow, 4);
  for (unsigned k = 0; k < 4; ++k) {
    put(bytes, m.c + 2 * k, r.c[k], 2);
    put(bytes, m.cgx + 2 * k, r.cgx[k], 2);
    put(bytes, m.crow + 2 * k, r.crow[k], 2);
  }
  for (unsigned v = 0; v < 2; ++v) {
    const unsigned at = v == 0 ? m.s : m.t, gx = v == 0 ? m.sgx : m.tgx, row = v == 0 ? m.srow : m.trow;
    put(bytes, at, r.st[v], 3);
    put(bytes, gx, r.stgx[v], 3);
    put(bytes, row, r.strow[v], 3);
  }
  if (m.zsend) {
    put(bytes, m.ofs, static_cast<uint16_t>(r.offset), 2);
    put(bytes, m.yw, static_cast<uint16_t>(r.y_memory), 2);
    bytes[m.nrows] = r.rows;
  }
}

int32_t EdgeWalk::bound(int j, uint32_t& remainder) const {
  const int64_t k = int64_t{b} * (16 * j + 8) + c;
  const int64_t n = t - k - 8 * int64_t{a};
  // Left: the first i with 16 a i >= n, ceil(n / d) = floor((n + d - 1) /
  // d). Right: the last i with 16 a i >= n (a < 0), floor(-n / d).
  const Divisor::Floor f = divisor.floor_divide(left ? n + d - 1 : -n);
  remainder = f.remainder;
  return static_cast<int32_t>(f.quotient);
}

ObjectTriangle::ObjectTriangle(const gl::Triangle& triangle, bool flat, const PixelBox& box, unsigned tex_width,
                               unsigned tex_height, unsigned unit) {
  int32_t x[3], y[3];
  for (unsigned i = 0; i < 3; ++i) {
    x[i] = triangle.v[i].x;
    y[i] = triangle.v[i].y;
    if (magnitude(x[i]) > COORDINATE_LIMIT || magnitude(y[i]) > COORDINATE_LIMIT) return;
  }
  const int32_t x1 = x[1] - x[0], y1 = y[1] - y[0], x2 = x[2] - x[0], y2 = y[2] - y[0];
  const int64_t area = int64_t{x1} * y2 - int64_t{y1} * x2;
  if (area == 0 || box.x0 > box.x1) return;
  m_x0 = x[0];
  m_y0 = y[0];
  m_area_sign = area < 0 ? -1 : 1;
  m_area = Divisor(static_cast<uint32_t>(area < 0 ? -area : area));

  // The edges as the arm back end has them (ap-pixel's PixelTriangle):
  // edge i from vertex i to i + 1, a X + b Y + c >= t inside, with t = 0 on
  // a top or left edge.
  struct Edge {
    int32_t a, b;
    int64_t c;
    int32_t t;
  } edges[3];
  const int32_t sign = area > 0 ? -1 : 1;
  for (unsigned i = 0; i < 3; ++i) {
    const unsigned next = (i + 1) % 3;
    const int32_t dx = x[next] - x[i], dy = y[next] - y[i];
    Edge& e = edges[i];
    e.a = sign * dy;
    e.b = -sign * dx;
    e.c = sign * (int64_t{y[i]} * dx - int64_t{x[i]} * dy);
    e.t = (e.a > 0 || (e.a == 0 && e.b < 0)) ? 0 : 1;
  }
  // The vertices by height, and the edge joining two of them.
  unsigned s[3] = {0, 1, 2};
  std::sort(std::begin(s), std::end(s), [&](unsigned p, unsigned q) { return y[p] < y[q] || (y[p] == y[q] && p < q); });
  const auto joining = [](unsigned p, unsigned q) { return (p + 1) % 3 == q ? p : q; };
  const unsigned long_edge = joining(s[0], s[2]);
  const unsigned short_edge[2] = {joining(s[0], s[1]), joining(s[1], s[2])};
  m_first = {ceil16(y[s[0]] - 8), ceil16(y[s[1]] - 8)};
  m_last = {ceil16(y[s[1]] - 8) - 1, floor16(y[s[2]] - 8)};
  for (unsigned h = 0; h < 2; ++h) {
    m_first[h] = std::max(m_first[h], box.y0);
    m_last[h] = std::min(m_last[h], box.y1);
    // A horizontal edge decides its own row alone (the rows it lies on
    // are the half's first or last): kept on a top edge, dropped on a
    // bottom one.
    const auto row_passes = [&](int j) {
      for (const Edge& e : edges)
        if (e.a == 0 && int64_t{e.b} * (16 * j + 8) + e.c < e.t) return false;
      return true;
    };
    while (m_first[h] <= m_last[h] && !row_passes(m_first[h])) ++m_first[h];
    while (m_first[h] <= m_last[h] && !row_passes(m_last[h])) --m_last[h];
    // The half's two edges: the long one and its own short one, or the
    // other short one where its own is horizontal (it then has at most
    // the one row where both meet).
    unsigned pair[2] = {long_edge, edges[short_edge[h]].a != 0 ? short_edge[h] : short_edge[1 - h]};
    if (edges[pair[0]].a < 0) std::swap(pair[0], pair[1]);
    if (edges[pair[0]].a <= 0 || edges[pair[1]].a >= 0) {
      m_first[h] = 0;
      m_last[h] = -1;
      continue;
    }
    for (unsigned side = 0; side < 2; ++side) {
      const Edge& e = edges[pair[side]];
      EdgeWalk& w = side == 0 ? m_left[h] : m_right[h];
      w.left = side == 0;
      w.a = e.a;
      w.b = e.b;
      w.c = e.c;
      w.t = e.t;
      w.d = static_cast<uint32_t>(16 * magnitude(e.a));
      w.divisor = Divisor(w.d);
      const Divisor::Floor f = w.divisor.floor_divide(w.left ? -16 * int64_t{e.b} : 16 * int64_t{e.b});
      w.q = static_cast<int32_t>(f.quotient);
      w.r = f.remainder;
    }
  }
  if (m_first[0] > m_last[0] && m_first[1] > m_last[1]) return;

  // The planes: depth in z24 units, colour in 1/256 of a unit.
  const auto plane = [&](int64_t v0, int64_t v1, int64_t v2) {
    const int64_t d1 = v1 - v0, d2 = v2 - v0;
    return Plane{v0, d1 * y2 - d2 * y1, d2 * x1 - d1 * x2};
  };
  m_z = plane(triangle.v[0].z, triangle.v[1].z, triangle.v[2].z);
  const gl::ScreenVertex* colour[3] = {&triangle.v[0], &triangle.v[1], &triangle.v[2]};
  if (flat) colour[0] = colour[1] = colour[2] = &triangle.v[2];
  for (unsigned k = 0; k < 4; ++k) {
    int64_t v[3];
    for (unsigned i = 0; i < 3; ++i) {
      const uint8_t channels[4] = {colour[i]->r, colour[i]->g, colour[i]->b, colour[i]->a};
      v[i] = int64_t{channels[k]} << 8;
    }
    m_colour[k] = plane(v[0], v[1], v[2]);
  }
  // s and t in 1/4096 texel, as ap-pixel's set-up has them
  // (renderers/common/texel_fixed.h; coordinates that are not finite give 0).
  const unsigned sizes[2] = {tex_width, tex_height};
  for (unsigned k = 0; k < 2; ++k) {
    float st[3];
    bool finite = true;
    for (unsigned i = 0; i < 3; ++i) {
      st[i] = k == 0 ? triangle.v[i].tex[unit].s : triangle.v[i].tex[unit].t;
      finite = finite && std::isfinite(st[i]);
    }
    int32_t v[3] = {0, 0, 0};
    if (finite && sizes[k] > 0) renderers::texel_fixed(st, static_cast<float>(sizes[k]) * 4096.0f, 28, v);
    m_st[k] = plane(v[0], v[1], v[2]);
  }
  m_valid = true;
}

int64_t ObjectTriangle::code_at(const Plane& plane, int64_t px, int64_t py) const {
  return plane.v0 + step(plane, px - m_x0, py - m_y0);
}

int64_t ObjectTriangle::step(const Plane& plane, int64_t dx, int64_t dy) const {
  return m_area.round_divide(m_area_sign * (dx * plane.cx + dy * plane.cy));
}

int ObjectTriangle::left(unsigned h, int j) const {
  uint32_t remainder;
  return m_left[h].bound(j, remainder);
}

int ObjectTriangle::right(unsigned h, int j) const {
  uint32_t remainder;
  return m_right[h].bound(j, remainder);
}

UnitRecord ObjectTriangle::record(unsigned h, int j, int offset) const {
  UnitRecord r;
  const EdgeWalk& left_edge = m_left[h];
  const EdgeWalk& right_edge = m_right[h];
  uint32_t rem_l = 0, rem_r = 0;
  const int32_t xl = left_edge.bound(j, rem_l), xr = right_edge.bound(j, rem_r);
  r.xl = static_cast<int16_t>(xl);
  r.xr = static_cast<int16_t>(xr);
  r.ql = static_cast<int16_t>(left_edge.q);
  r.qr = static_cast<int16_t>(right_edge.q);
  r.nl = (TWO_24 - left_edge.d) & 0xffffff;
  r.nr = (TWO_24 - right_edge.d) & 0xffffff;
  r.ul = (rem_l + r.nl) & 0xffffff;
  r.ur = (rem_r + r.nr) & 0xffffff;
  r.rl = left_edge.r;
  r.rr = right_edge.r;
  r.offset = static_cast<int16_t>(offset);
  const int64_t px = 16 * (int64_t{xl} + offset) + 8, py = 16 * int64_t{j} + 8;
  r.z = static_cast<uint32_t>(code_at(m_z, px, py));
  r.zgx = static_cast<uint32_t>(step(m_z, 16, 0));
  r.zrow = static_cast<uint32_t>(step(m_z, 16 * int64_t{left_edge.q}, 16));
  for (unsigned k = 0; k < 4; ++k) {
    // Half a unit of bias: the high byte is the value rounded.
    r.c[k] = static_cast<uint16_t>(code_at(m_colour[k], px, py) + 128);
    r.cgx[k] = static_cast<uint16_t>(step(m_colour[k], 16, 0));
    r.crow[k] = static_cast<uint16_t>(step(m_colour[k], 16 * int64_t{left_edge.q}, 16));
  }
  // 1/4096 texel to the code's 1/256: a rounding shift.
  const auto code = [](int64_t sixteenths) { return static_cast<uint32_t>((sixteenths + 8) >> 4) & 0xffffff; };
  for (unsigned k = 0; k < 2; ++k) {
    r.st[k] = code(code_at(m_st[k], px, py));
    r.stgx[k] = code(step(m_st[k], 16, 0));
    r.strow[k] = code(step(m_st[k], 16 * int64_t{left_edge.q}, 16));
  }
  return r;
}

}  // namespace tessera::ap_object
