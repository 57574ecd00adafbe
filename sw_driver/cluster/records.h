// The records the sort-middle renderer's stages pass on (README.md): a
// triangle on the screen, the trapezoid a node sends to a stripe's owner,
// and the counters of the work each stage does.
//
// Formats. Screen positions are 9.4 fixed point (sw_driver/gl/geometry.h's
// SUBPIXEL_BITS; the paper used 1/64 pixel) with y DOWNWARDS: row 0 is the
// top row of the image, pixel (i, r) has its centre at (16 i + 8, 16 r + 8).
// Depth is 24 bits (0 nearest), colour 8 bits per channel.
#pragma once

#include <cstdint>
#include <type_traits>

namespace tessera::cluster {

constexpr int SUBPIXEL_BITS = 4;
constexpr int32_t SUBPIXEL_ONE = 1 << SUBPIXEL_BITS;
// The guard band: a snapped vertex lies within +-MAX_COORDINATE (9.4), so
// that edge vectors, areas and the edge set-up stay within int32
// (renderers/arm/planes.h's bounds).
constexpr int32_t MAX_COORDINATE = (1 << 14) - 1;
constexpr unsigned MAX_SCREEN = 512;  // contract/common/screen_size.h's MAX_SCREEN_SIZE
constexpr unsigned MAX_NODES = 128;
constexpr uint32_t MAX_DEPTH = (1u << 24) - 1;

struct ScreenVertex {
  int32_t x = 0, y = 0;  // 9.4, y down
  uint32_t z = 0;        // 0 .. MAX_DEPTH
  uint8_t r = 0, g = 0, b = 0, unused = 0;
};

struct ScreenTriangle {
  ScreenVertex v[3];
};

// One edge of a trapezoid at its first row, as an exact DDA (the arm
// renderer's EdgeWalk): `pixel` is the first pixel whose centre is at or
// right of the edge's crossing with the row's centre line, ceil((x - 8) /
// 16) in 9.4 units, and `error` = pixel * denominator - numerator, in [0,
// denominator). A row down adds `step` to the pixel and takes `step_error`
// from the error; when the error goes negative the pixel moves one more and
// the error gains `denominator` (16 times the edge's height in 9.4 units).
struct TrapezoidEdge {
  int32_t pixel = 0, error = 0, step = 0, step_error = 0, denominator = 1;
};

// One attribute's plane: its value at the first row's first pixel (the left
// edge's `pixel`), what a row down along the left edge adds (without the
// carry), and what a pixel to the right adds (also added on the left edge's
// carry). Fixed point: DEPTH_FRACTION_BITS or COLOR_FRACTION_BITS.
struct TrapezoidPlane {
  int64_t start = 0, row_step = 0, dx = 0;
};

constexpr int DEPTH_FRACTION_BITS = 6;   // z24 * 2^6 < 2^30
constexpr int COLOR_FRACTION_BITS = 16;  // c8 * 2^16 < 2^24

// What the receiving node needs to rasterise a piece of a triangle, with no
// access to the triangle: rows first_row .. last_row (inclusive, absolute
// screen rows), on each row the pixels left.pixel <= i < right.pixel.
struct Trapezoid {
  int16_t first_row = 0, last_row = -1;
  TrapezoidEdge left, right;
  uint32_t reserved = 0;  // explicit, so that every byte sent is defined
  TrapezoidPlane z, red, green, blue;
};

// The paper's s: the bytes of one trapezoid in a message.
constexpr unsigned TRAPEZOID_BYTES = 144;
static_assert(sizeof(Trapezoid) == TRAPEZOID_BYTES, "a trapezoid is sent as 144 bytes");
static_assert(std::is_trivially_copyable_v<Trapezoid> && std::is_standard_layout_v<Trapezoid>,
              "a trapezoid is sent as its bytes");

// What a node would charge, per stage. Each function adds to the counters
// it is given.
struct WorkCounters {
  // Geometry (transform_triangle).
  uint64_t triangles_in = 0;        // transformed: three vertices each
  uint64_t triangles_rejected = 0;  // a vertex behind the eye, outside the depth range or the guard band
  uint64_t triangles_culled = 0;    // back faces and zero area after snapping
  uint64_t triangles_accepted = 0;  // handed to the split
  // Split (split_triangle).
  uint64_t triangles_split = 0;      // set up: sorted, area, gradients
  uint64_t trapezoids_nonempty = 0;  // upper and lower halves with at least one row on the screen
  uint64_t trapezoids_out = 0;       // pieces sent to stripes
  uint64_t trapezoid_rows_out = 0;   // rows of the pieces sent
  // Rasterisation (rasterize_trapezoid).
  uint64_t trapezoids_in = 0;
  uint64_t rows = 0;          // rows walked
  uint64_t spans = 0;         // rows with at least one pixel on the screen
  uint64_t pixels = 0;        // pixels walked (depth tests)
  uint64_t depth_passes = 0;  // pixels written
};

}  // namespace tessera::cluster
