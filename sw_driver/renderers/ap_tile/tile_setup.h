// The host's side of the ap-tile algorithm, plain C++: the CMEM layout the
// array program declares, a triangle's set-up in the study's fixed point
// (32-bit integer arithmetic, as the ARM922T runs it)
// (three normalised edge functions, attribute planes), the tiles it
// overlaps, and the record each overlapped CU receives. The formats are in
// README.md ("Fixed point"); the array program is ap_tile.s, and
// tile_reference.h runs the same arithmetic natively.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "array/program.h"
#include "gl/renderer.h"
#include "renderers/common/divisor.h"

namespace tessera::ap_tile {

// Where everything lives in a CU's CMEM, read from the program's variables
// (ap_tile.s is the one place the layout is written). Pixel (x, l) of a
// plane (x the tile column from the left, l the row from the top) is at
// plane + tile_height * x + l.
struct CmemLayout {
  unsigned tile_width = 0, tile_height = 0;
  // Planes of tile_width * tile_height bytes.
  uint16_t chi = 0, clo = 0, zhi = 0, zlo = 0, shi = 0, slo = 0, thi = 0, tlo = 0, tid = 0, we = 0;
  // The triangle record.
  uint16_t live = 0, e0 = 0, edu = 0, edv = 0, z0 = 0, zdu = 0, zdv = 0, c0 = 0, cdu = 0, cdv = 0;
  uint16_t st0 = 0, stdu = 0, stdv = 0, tex = 0, zlequal = 0, zoff = 0, zwrite = 0;
  // Constants and clear values.
  uint16_t yc = 0, zero = 0, clear_c = 0, clear_z = 0;
  // The record's bytes are [record_first, record_first + record_bytes).
  uint16_t record_first = 0, record_bytes = 0;

  unsigned pixel(uint16_t plane, unsigned x, unsigned l) const { return plane + tile_height * x + l; }

  // Throws std::invalid_argument naming a variable the program lacks or
  // sizes differently, or a record that is not contiguous.
  static CmemLayout of(const ap::Program& program);
};

// The frame: columns x rows tiles, one per CU, tile (c, r) at pixel column
// c * tile_width and display row r * tile_height (row 0 at the top).
struct FrameGeometry {
  unsigned columns = 24, rows = 4;
  unsigned tile_width = 8, tile_height = 36;

  unsigned width() const { return columns * tile_width; }
  unsigned height() const { return rows * tile_height; }
  unsigned cus() const { return columns * rows; }
};

// What the host writes into one CU before a pass (the program's record).
struct TileRecord {
  bool live = false;
  std::array<int16_t, 3> e0{}, edu{}, edv{};      // edge functions, 1/512 pixel
  uint32_t z0 = 0, zdu = 0, zdv = 0;              // depth, 16.8, modulo 2^24
  std::array<uint16_t, 3> c0{}, cdu{}, cdv{};     // R, G, B in 5/6/5-bit units, 8.8, modulo 2^16
  std::array<uint16_t, 2> st0{}, stdu{}, stdv{};  // s, t in texels, 8.8, modulo 2^16
  uint8_t tex = 0;
  bool zlequal = false, zoff = false, zwrite = true;
};

// What the host writes into one CU before a pass of the study's program
// (ap_tile_study.s, README.md "The study's program"): three lines
// E = A x + B y + C (x the tile column from the left, y the row from the
// top, C the value at the tile's top-left pixel, inside where E >= 0),
// depth, colour and texture coordinates at the tile's bottom-right pixel
// with their steps per pixel right (dx) and per row down (dy). Every value
// 16 bits, wrapping.
struct StudyRecord {
  bool live = false;                                 // the triangle reaches the tile (else the CU draws nothing)
  std::array<int16_t, 3> a{}, b{}, c{};              // lines, 1/512 pixel
  uint16_t z = 0, z_dx = 0, z_dy = 0;                // depth, 16-bit unsigned
  std::array<uint16_t, 3> colour{}, c_dx{}, c_dy{};  // R, G, B in 8.8, 0..255
  std::array<uint16_t, 2> st{}, st_dx{}, st_dy{};    // s, t in texels, 8.8
  uint8_t tex = 0;
  bool depth_test = false;  // the draw tests depth (the host decides whether the pass runs the depth stage)
};

// Writes `record` as the program lays it out: layout.record_bytes bytes,
// the first at CMEM address layout.record_first.
void encode_record(const TileRecord& record, const CmemLayout& layout, uint8_t* bytes);

// Per-draw state the record carries.
struct DrawFlags {
  bool depth_test = false;
  bool depth_lequal = false;  // GL_LEQUAL rather than GL_LESS
  bool depth_write = true;
  bool flat = false;
  uint8_t tex = 0;  // texture number of the frame (0: untextured)
  unsigned tex_width = 0, tex_height = 0;
  uint8_t tex_unit = 0;  // the texture unit whose coordinates are drawn
};

// One normalised edge function E = A x + B y + C in 1/512 pixel, inside >= 0.
struct Edge {
  int32_t px = 0, py = 0, dx = 0, dy = 0;  // the edge's start and direction, 1/16 pixel
  int32_t norm = 1;                        // max(|dx|, |dy|)
  int sign = 1;                            // +1 or -1: makes the inside positive
  int32_t a = 0, b = 0;                    // per pixel right and per pixel up, rounded
  bool top_left = false;                   // owns the pixels exactly on it
};

// The set-up is 32-bit integer arithmetic written for the ARM922T (no FPU,
// no divide instruction): 32x32->64 multiplies, 64-bit additions, and
// divisions by a Divisor made once per triangle (renderers/common/
// divisor.h). The ranges, from the vertices' bound (COORDINATE_LIMIT) and
// the formats, are written in tile_setup.cpp beside each computation.
class TriangleSetup {
 public:
  // Vertices are 1/16 pixel; the GL front end gives 9.4 codes in
  // [0, 2^13). The set-up accepts |x|, |y| <= 2^14 (so that tests may put
  // vertices a screen's width off it) and refuses the triangle beyond, as
  // it does a frame wider or taller than MAX_FRAME pixels.
  static constexpr int32_t COORDINATE_LIMIT = int32_t{1} << 14;
  static constexpr unsigned MAX_FRAME = 512;

  TriangleSetup(const gl::Triangle& triangle, const DrawFlags& flags, const FrameGeometry& frame);

  // False for a triangle that draws nothing (zero area, a vertex beyond
  // COORDINATE_LIMIT, a frame beyond MAX_FRAME).
  bool valid() const { return m_valid; }
  // The tiles the triangle reaches: its bounding box overlaps the tile's
  // pixel centres and no edge has all four corner pixels of the tile
  // outside. Tile index r * columns + c.
  std::vector<unsigned> tiles() const;
  bool overlaps(unsigned c, unsigned r) const;
  // The record for CU (c, r).
  TileRecord record(unsigned c, unsigned r) const;
  // The study program's record for CU (c, r): the same edges and texture
  // coordinates as record(c, r), depth rounded to 16 bits, colour in 8.8
  // of 0..255. A CU the triangle does not reach gets live = false.
  StudyRecord study_record(unsigned c, unsigned r) const;

  const std::array<Edge, 3>& edges() const { return m_edges; }

 private:
  // An edge over tile (c, r) as the CU steps it: the value at the
  // bottom-right pixel, the steps left and up, and the least and greatest
  // value at the tile's four corner pixels.
  struct EdgeInTile {
    int32_t e0 = 0, du = 0, dv = 0, low = 0, high = 0;
  };
  // An attribute: its value at vertex 0 and its differences to vertices 1
  // and 2, in the attribute's own units.
  struct Plane {
    int32_t v0 = 0, d1 = 0, d2 = 0;
  };
  // Exact quotients by the doubled area: value * area = whole * area + rest.
  struct Scaled {
    int64_t whole = 0;
    uint32_t rest = 0;
  };

  bool in_box(unsigned c, unsigned r) const;
  // The edge function at a pixel centre (sixteenths), rounded, with the
  // tie bias.
  int32_t edge_at(unsigned e, int32_t x16, int32_t y16) const;
  EdgeInTile edge_in_tile(unsigned e, unsigned c, unsigned r) const;
  // The centre of tile column c's / row r's bottom-right pixel, 1/16 pixel.
  int32_t corner_x16(unsigned c) const;
  int32_t corner_y16(unsigned r) const;
  // plane * area at a point whose barycentric numerators are w1, w2 (the
  // area-weighted distances from the edges opposite vertices 1 and 2), or
  // a step's numerator; with the area's sign taken out.
  int64_t plane_numerator(const Plane& plane, int32_t w1, int32_t w2) const;
  int64_t step_numerator(const Plane& plane, int dx16, int dy16) const;
  // numerator * m / |area|, exact.
  Scaled scale(int64_t numerator, uint32_t m) const;
  // Of value = numerator / area, rounded: the 16.8 depth (value * 65535 /
  // 65536, exact modulo 2^24), the 8.8 colour (value * max / 255 * 256)
  // and the 8.8 texel (value / 16, exact modulo 2^16).
  int64_t depth_value(int64_t numerator) const;
  int64_t colour_value(int64_t numerator, unsigned max) const;
  int64_t texel_value(int64_t numerator) const;

  FrameGeometry m_frame;
  DrawFlags m_flags;
  bool m_valid = false;
  int32_t m_x[3]{}, m_y[3]{};  // vertices, 1/16 pixel, GL y
  int64_t m_area = 0;          // twice the signed area, 1/256 pixel^2
  Divisor m_area_divisor{1};   // |m_area|
  std::array<Edge, 3> m_edges{};
  std::array<Divisor, 3> m_norms{Divisor{1}, Divisor{1}, Divisor{1}};
  Plane m_z, m_color[3], m_tex[2];  // z24; 0.8 channels; s, t in 1/4096 texel
  // The gradients, the same in every tile.
  uint32_t m_zdu = 0, m_zdv = 0;
  std::array<uint16_t, 3> m_cdu{}, m_cdv{};
  std::array<uint16_t, 2> m_stdu{}, m_stdv{};
  int m_x_min = 0, m_x_max = -1, m_y_min = 0, m_y_max = -1;  // pixel bounding box, GL rows
};

}  // namespace tessera::ap_tile
