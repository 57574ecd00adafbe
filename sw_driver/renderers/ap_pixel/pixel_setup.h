// The host's side of the ap-pixel algorithm, plain C++: the CMEM layout the
// array program declares, a triangle's exact coverage and depth (the host's
// scan conversion and depth test), its 21 attribute values at an origin
// pixel in the program's fixed point, and the reference of what a CU
// computes from them. The formats are in README.md ("Fixed point"); the
// array programs are ap_pixel.s (`tuned`) and ap_pixel_study.s (`study`).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "array/program.h"
#include "gl/renderer.h"
#include "renderers/common/divisor.h"

namespace tessera::ap_pixel {

// The attributes every CU evaluates, in the program's order.
enum class Attribute : unsigned { red, green, blue, alpha, s, t, z };
constexpr unsigned ATTRIBUTES = 7;

// The array programs (ap.pixel.program): `tuned` (ap_pixel.s: 16.8 values,
// kept in registers between statements) and `study` (ap_pixel_study.s: the
// study's 8.8 values, every statement loading from and storing to CMEM).
enum class ProgramVariant : unsigned { tuned, study };
inline constexpr const char* PROGRAM_VARIANT_NAMES[] = {"tuned", "study"};

// The variant named `name`; throws std::invalid_argument naming `key` and
// the names allowed otherwise.
ProgramVariant program_variant(const std::string& name, const std::string& key = "ap.pixel.program");
const char* program_variant_name(ProgramVariant variant);
// The variant's array program, as assembled at build time.
const ap::Program& program_of(ProgramVariant variant);

// Where everything lives in a CU's CMEM, read from the program's variables
// (the program's source is the one place its layout is written).
struct PixelLayout {
  ProgramVariant variant = ProgramVariant::tuned;
  unsigned max_block = 0;  // MAX_BLOCK: the largest k
  // Bytes of a value (C0 and a result): 3 (16.8) or 2 (8.8). A gradient is
  // two bytes (8.8) at gx + value_bytes a + gradient_offset: tuned keeps a
  // sign byte before it (the program makes it), study does not.
  unsigned value_bytes = 3, gradient_offset = 1;
  uint16_t c0 = 0, gx = 0, gy = 0, dx = 0, dy = 0, out = 0;
  uint16_t scratch = 0;             // the program's temporary, value_bytes long
  std::array<unsigned, 6> entry{};  // entry[k]: block k's entry word, k = 1..5
  // study only: shade_entry[n] evaluates the first n attributes of one
  // pixel (n = 1..7; 0 where the program has no such entry).
  std::array<unsigned, ATTRIBUTES + 1> shade_entry{};
  unsigned cmem_bytes = 0;  // CMEM a CU uses: the end of the last variable

  // The first (high) byte of attribute `a` of the block's pixel (u, v).
  unsigned result(unsigned u, unsigned v, Attribute a) const {
    return out + value_bytes * ATTRIBUTES * (max_block * v + u) + value_bytes * static_cast<unsigned>(a);
  }

  // Throws std::invalid_argument naming a variable, constant or entry the
  // program lacks or sizes differently.
  static PixelLayout of(const ap::Program& program, ProgramVariant variant = ProgramVariant::tuned);
  static PixelLayout of(ProgramVariant variant) { return of(program_of(variant), variant); }
};

// A triangle's 21 values at its origin pixel: per attribute the value at the
// origin's centre (16.8, modulo 2^24) and its steps per pixel right and up
// (8.8, signed).
struct TriangleValues {
  std::array<uint32_t, ATTRIBUTES> c0{};
  std::array<int16_t, ATTRIBUTES> gx{}, gy{};
  // Per attribute: a gradient steeper than 8.8 can hold (above 128 units
  // per pixel, on slivers) was clamped, so the array's values are wrong.
  std::array<bool, ATTRIBUTES> clamped{};
};

// What CU arithmetic gives pixel (u, v) of a block whose first pixel is
// (dx, dy) from the origin: the program's sum, modulo 2^24.
inline uint32_t shade_reference(const TriangleValues& values, Attribute a, int dx, int dy, unsigned u, unsigned v) {
  const auto i = static_cast<unsigned>(a);
  const int64_t value = int64_t{values.c0[i]} + int64_t{dx + static_cast<int>(u)} * values.gx[i] +
                        int64_t{dy + static_cast<int>(v)} * values.gy[i];
  return static_cast<uint32_t>(value) & 0xffffffu;
}

// The bytes the host writes for the first `attributes` attributes of
// `values` (the program's c0, gx, gy without tuned's sign bytes, which the
// program makes; study's C0 is the 16.8 value modulo 2^16, the same
// fraction): `write(address, byte)` once per byte, 7 (tuned) or 6 (study)
// per attribute.
template <typename Write>
void for_each_value_byte(const TriangleValues& values, const PixelLayout& layout, Write&& write,
                         unsigned attributes = ATTRIBUTES) {
  for (unsigned i = 0; i < attributes; ++i) {
    const unsigned a = layout.value_bytes * i, g = a + layout.gradient_offset;
    if (layout.value_bytes == 3) write(layout.c0 + a, static_cast<uint8_t>(values.c0[i] >> 16));
    write(layout.c0 + a + layout.value_bytes - 2, static_cast<uint8_t>(values.c0[i] >> 8));
    write(layout.c0 + a + layout.value_bytes - 1, static_cast<uint8_t>(values.c0[i]));
    const auto gx = static_cast<uint16_t>(values.gx[i]), gy = static_cast<uint16_t>(values.gy[i]);
    write(layout.gx + g, static_cast<uint8_t>(gx >> 8));
    write(layout.gx + g + 1, static_cast<uint8_t>(gx));
    write(layout.gy + g, static_cast<uint8_t>(gy >> 8));
    write(layout.gy + g + 1, static_cast<uint8_t>(gy));
  }
}

// The pixels the host may draw: the frame, narrowed by a scissor box.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive, GL rows (0 at the bottom)
};

// The set-up is 32-bit integer arithmetic written for the ARM922T: 32x32->64
// multiplies, 64-bit additions and divisions by per-triangle Divisors
// (renderers/common/divisor.h); the ranges are in pixel_setup.cpp.
class PixelTriangle {
 public:
  static constexpr int32_t COORDINATE_LIMIT = int32_t{1} << 14;

  // flat: every vertex takes v[2]'s colour; tex_width, tex_height: the
  // texture's size in texels (S and T are in texels), 0 when untextured.
  // `unit`: the texture unit whose coordinates are interpolated.
  PixelTriangle(const gl::Triangle& triangle, bool flat, unsigned tex_width, unsigned tex_height, const PixelBox& box,
                unsigned unit = 0);

  // False for a triangle that draws nothing (zero area, a vertex beyond
  // +-2^14 sixteenths (COORDINATE_LIMIT: twice the 9.4 screen), or wholly
  // outside the box, which must lie within a 512-pixel frame).
  bool valid() const { return m_valid; }
  // The rows with pixel centres in the triangle's bounding box, in the box.
  int y_first() const { return m_y_min; }
  int y_last() const { return m_y_max; }
  // The pixels of row j whose centres are inside (the top-left rule of the
  // arm back end, exactly), in the box: [first, last]; false if none.
  bool span(int j, int& first, int& last) const;
  // The 16-bit depth at pixel (i, j)'s centre: the exact 0.24 depth,
  // truncated to its top 16 bits.
  uint16_t depth16(int i, int j) const;
  // The 21 values with the origin at pixel (ox, oy) (README.md, "Fixed
  // point": colour rounded by a half in C0, gradients clamped to 8.8).
  TriangleValues values(int ox, int oy) const;

 private:
  struct Edge {
    int32_t a = 0, b = 0, c = 0;  // E = a x16 + b y16 + c, inside > 0 (or = 0 on a top-left edge)
    bool top_left = false;
    Divisor over_16a{1};  // 16 |a| (1 when a = 0)
  };
  // An attribute: its value at vertex 0 and its differences to vertices 1
  // and 2, in 2^-fraction units of its 16.8 code.
  struct Plane {
    int32_t v0 = 0, d1 = 0, d2 = 0;
    unsigned fraction = 8;
  };

  PixelBox m_box;
  bool m_valid = false;
  uint32_t m_area = 0;  // |twice the area|, 1/256 pixel^2: the sum of the three edge functions
  Divisor m_area_divisor{1};
  int m_area_sign = 1;
  std::array<Edge, 3> m_edges{};
  std::array<Plane, ATTRIBUTES> m_planes{};
  // The gradients, the same for every origin.
  TriangleValues m_gradients;
  std::array<int32_t, 3> m_x{}, m_y{};  // vertices, 1/16 pixel
  std::array<uint32_t, 3> m_z{};        // 0.24 depth
  int m_y_min = 0, m_y_max = -1;
};

}  // namespace tessera::ap_pixel
