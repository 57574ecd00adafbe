// The host's side of the ap-tile algorithm, plain C++: the CMEM layout the
// array program declares, a triangle's set-up in the study's fixed point
// (three normalised edge functions, attribute planes), the tiles it
// overlaps, and the record each overlapped CU receives. The formats are in
// README.md ("Fixed point"); the array program is ap_tile.s, and
// tile_reference.h runs the same arithmetic natively.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "array/asm/program.h"
#include "gl/renderer.h"

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
  int64_t px = 0, py = 0, dx = 0, dy = 0;  // the edge's start and direction, 1/16 pixel
  int64_t norm = 1;                        // max(|dx|, |dy|)
  int sign = 1;                            // +1 or -1: makes the inside positive
  int32_t a = 0, b = 0;                    // per pixel right and per pixel up, rounded
  bool top_left = false;                   // owns the pixels exactly on it
};

// An attribute's plane: value(x, y) = (v1 * area + cx (x - x1) + cy (y - y1)) / area
// times num / den, in 2^-fraction units, plus bias.
struct Plane {
  std::array<int64_t, 3> v{};
  int64_t num = 1, den = 1;
  int fraction = 8;
  int64_t bias = 0;
};

class TriangleSetup {
 public:
  TriangleSetup(const gl::Triangle& triangle, const DrawFlags& flags, const FrameGeometry& frame);

  // False for a triangle that draws nothing (zero area, or a vertex beyond
  // +-2^18 pixels, as the arm back end).
  bool valid() const { return m_valid; }
  // The tiles the triangle reaches: its bounding box overlaps the tile's
  // pixel centres and no edge has all four corner pixels of the tile
  // outside. Tile index r * columns + c.
  std::vector<unsigned> tiles() const;
  bool overlaps(unsigned c, unsigned r) const;
  // The record for CU (c, r).
  TileRecord record(unsigned c, unsigned r) const;

  const std::array<Edge, 3>& edges() const { return m_edges; }

 private:
  // An edge over tile (c, r) as the CU steps it: the value at the
  // bottom-right pixel, the steps left and up, and the least and greatest
  // value at the tile's four corner pixels.
  struct EdgeInTile {
    int64_t e0 = 0, du = 0, dv = 0, low = 0, high = 0;
  };

  // The edge function at a pixel centre (sixteenths), rounded, with the
  // tie bias.
  int64_t edge_at(const Edge& edge, int64_t x16, int64_t y16) const;
  EdgeInTile edge_in_tile(const Edge& edge, unsigned c, unsigned r) const;
  // The centre of tile column c's / row r's bottom-right pixel, 1/16 pixel.
  int64_t corner_x16(unsigned c) const;
  int64_t corner_y16(unsigned r) const;
  int64_t plane_at(const Plane& plane, int64_t x16, int64_t y16) const;
  int64_t plane_step(const Plane& plane, int64_t dx16, int64_t dy16) const;
  double texture_at(unsigned k, double x16, double y16) const;

  FrameGeometry m_frame;
  DrawFlags m_flags;
  bool m_valid = false;
  int64_t m_x[3]{}, m_y[3]{};  // vertices, 1/16 pixel, GL y
  int64_t m_area = 0;          // twice the signed area, 1/256 pixel^2
  std::array<Edge, 3> m_edges{};
  Plane m_z, m_color[3];
  double m_tex[2][3]{};                                      // s * width * 256, t * height * 256 per vertex
  int m_x_min = 0, m_x_max = -1, m_y_min = 0, m_y_max = -1;  // pixel bounding box, GL rows
};

}  // namespace tessera::ap_tile
