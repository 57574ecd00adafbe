// The host's side of the ap-object algorithm, plain C++: the CMEM layout the
// array program declares, a triangle's set-up into two halves (exact edge
// stepping with the top-left rule, depth and colour planes), the pieces a
// half is cut into when it does not fit a CU's slots, and the record a CU
// receives for a piece. The formats are in README.md ("Fixed point"); the
// array program is ap_object.s, assembled per span class and unit.
//
// The set-up is 32-bit integer arithmetic with 32x32->64 multiplies and
// divisions by per-triangle Divisors (renderers/common/divisor.h), written
// for the ARM922T: no floating point, no 64-bit division.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "array/program.h"
#include "gl/renderer.h"
#include "renderers/common/divisor.h"

namespace tessera::ap_object {

// ap.object.unit: what a CU walks per batch, one half of a triangle (the
// paper's strategy 3) or a whole triangle, its two halves one after the
// other (strategy 1).
enum class Unit : unsigned { half, triangle };
inline constexpr const char* UNIT_NAMES[] = {"half", "triangle"};
// The unit named `name`; throws std::invalid_argument naming `key` and the
// names allowed otherwise.
Unit unit_named(const std::string& name, const std::string& key = "ap.object.unit");

// The span classes: the program walks W pixels a row; the host picks the
// narrowest class that holds the batch's widest span, cutting wider spans
// into column pieces of the widest class.
inline constexpr unsigned SPAN_CLASSES = 3;
inline constexpr unsigned SPAN_WIDTHS[SPAN_CLASSES] = {8, 16, 32};

// ap.object.zpath: where the pixels go, to CMEM slots the host reads and
// z-tests (host) or through zsend to the z-buffer unit (unit).
enum class ZPath : unsigned { host, unit };
inline constexpr const char* ZPATH_NAMES[] = {"host", "unit"};
ZPath zpath_named(const std::string& name, const std::string& key = "ap.object.zpath");

const ap::Program& program_of(Unit unit, unsigned span_class, ZPath zpath = ZPath::host);

// Where everything lives in a CU's CMEM, read from the program's variables
// and constants (the program's source is the one place it is written).
struct ObjectLayout {
  unsigned span = 0;   // W: pixels walked per row
  unsigned rows = 0;   // RM: rows a region holds
  unsigned units = 1;  // records per CU: 1 (half) or 2 (triangle)
  unsigned rec = 0, rec_bytes = 0, cacc = 0, tacc = 0, out = 0, region = 0;
  // Offsets within a record.
  unsigned xl = 0, ul = 0, ql = 0, rl = 0, nl = 0, xr = 0, ur = 0, qr = 0, rr = 0, nr = 0;
  unsigned z = 0, zgx = 0, zrow = 0, c = 0, cgx = 0, crow = 0, s = 0, sgx = 0, srow = 0, t = 0, tgx = 0, trow = 0;
  unsigned slot_bytes = 13, row_bytes = 4;
  unsigned entry = 0;
  std::array<unsigned, 2> loop_word{};  // the row loop of each record, by word
  unsigned cmem_bytes = 0;              // the end of the last variable
  // The z path through the unit (ZSEND programs): no slots; the record goes
  // on with the walk's offset, the row's y in memory rows and the rows
  // left; the span's accumulators, the pixel sent and the host's constants.
  bool zsend = false;
  unsigned ofs = 0, yw = 0, nrows = 0;
  unsigned zacc = 0, pos = 0, pix = 0, konst = 0;

  unsigned record(unsigned h) const { return rec + rec_bytes * h; }
  // The row planes: byte b of row slot l (b 0, 1: XL; 2, 3: XR).
  unsigned row_plane(unsigned h, unsigned b, unsigned l) const { return out + region * h + rows * b + l; }
  // The slot planes: byte b of pixel p's slot in row slot l (b 0..2: z's
  // top byte, z16 high, z16 low; 3..6: R, G, B, A; 7..9: s, 10..12: t).
  unsigned slot(unsigned h, unsigned p, unsigned b, unsigned l) const {
    return out + region * h + rows * (row_bytes + slot_bytes * p + b) + l;
  }

  // Throws std::invalid_argument naming what the program lacks or sizes
  // differently.
  static ObjectLayout of(const ap::Program& program);
};

// A record: what a CU needs to walk one piece of a half (README.md,
// "The record"). 24-bit fields are held in the low bits.
struct UnitRecord {
  int16_t xl = 0, xr = 0, ql = 0, qr = 0;
  uint32_t ul = 0, rl = 0, nl = 0, ur = 0, rr = 0, nr = 0;
  uint32_t z = 0, zgx = 0, zrow = 0;
  std::array<uint16_t, 4> c{}, cgx{}, crow{};
  std::array<uint32_t, 2> st{}, stgx{}, strow{};  // s and t, 16.8 texels, 24-bit
  // ZSEND programs only: the walk's offset from the left end, the first
  // row's y in the frame's memory rows (0 at the top) and the piece's rows.
  int16_t offset = 0, y_memory = 0;
  uint8_t rows = 0;
};
// Writes the record's rec_bytes bytes, big-endian, in the program's order.
void encode_record(const UnitRecord& record, const ObjectLayout& layout, uint8_t* bytes);

// The bytes of `konst` a ZSEND program reads (ap_object.s): 1, the masks of
// red's five and green's six bits, and A / 256 of the colour's rounding.
inline constexpr uint8_t ZSEND_KONST[] = {1, 0xf8, 0xfc, 4, 2};

// The pixels the host may draw: the frame, narrowed by a scissor box.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive, GL rows (0 at the bottom)
};

// An edge stepped row by row: its bound on the row's pixels (the first
// covered pixel for a left edge, the last for a right one) as the quotient
// of an exact floor division whose remainder carries into the next row.
struct EdgeWalk {
  bool left = true;
  int32_t a = 0, b = 0;  // the edge function's coefficients (sixteenths)
  int64_t c = 0;
  int32_t t = 0;   // 0 on a top or left edge (the top-left rule), 1 otherwise
  uint32_t d = 1;  // 16 |a|
  Divisor divisor{1};
  int32_t q = 0;   // the bound's step per row
  uint32_t r = 0;  // the remainder's step per row, in [0, d)

  // The bound at row j and its remainder in [0, d).
  int32_t bound(int j, uint32_t& remainder) const;
};

// A triangle split at its middle vertex into a lower (h = 0) and an upper
// (h = 1) half, each bounded by two edges, with the planes of depth and
// colour.
class ObjectTriangle {
 public:
  static constexpr int32_t COORDINATE_LIMIT = int32_t{1} << 14;

  // flat: every vertex takes v[2]'s colour; tex_width, tex_height: the
  // texture's size in texels (s and t are in texels), 0 when untextured;
  // `unit`: the texture unit whose coordinates are interpolated.
  ObjectTriangle(const gl::Triangle& triangle, bool flat, const PixelBox& box, unsigned tex_width = 0,
                 unsigned tex_height = 0, unsigned unit = 0);
  // False for a triangle that draws nothing (zero area, a vertex beyond
  // +-2^14 sixteenths, no row in the box).
  bool valid() const { return m_valid; }
  // Half h's rows in the box, [first_row, last_row] (empty when first >
  // last).
  int first_row(unsigned h) const { return m_first[h]; }
  int last_row(unsigned h) const { return m_last[h]; }
  bool empty(unsigned h) const { return !m_valid || m_first[h] > m_last[h]; }
  // Half h's covered pixels of row j (a row of the half): [left, right],
  // empty when left > right. Not clipped to the box.
  int left(unsigned h, int j) const;
  int right(unsigned h, int j) const;
  // The record of the piece of half h starting at row j whose walk starts
  // `offset` pixels right of the row's left end.
  UnitRecord record(unsigned h, int j, int offset) const;

 private:
  struct Plane {
    int64_t v0 = 0;          // the value at vertex 0, in code units
    int64_t cx = 0, cy = 0;  // the plane's numerators (README.md)
  };
  // The plane's code at sixteenths (X, Y), rounded.
  int64_t code_at(const Plane& plane, int64_t px, int64_t py) const;
  int64_t step(const Plane& plane, int64_t dx, int64_t dy) const;

  bool m_valid = false;
  int32_t m_x0 = 0, m_y0 = 0;
  int64_t m_area_sign = 1;
  Divisor m_area{1};
  std::array<EdgeWalk, 2> m_left{}, m_right{};  // per half
  std::array<int, 2> m_first{{0, 0}}, m_last{{-1, -1}};
  Plane m_z;
  std::array<Plane, 4> m_colour;
  std::array<Plane, 2> m_st;  // in 1/4096 texel (the code's 1/256 times 16)
};

}  // namespace tessera::ap_object
