// The sort-middle renderer's geometry stage (README.md, step 2): a lit
// triangle in world space to a snapped triangle on the screen, or culled.
// Single-precision float per vertex only; the result is fixed point
// (records.h). No 3-D clipping: a triangle with a vertex at w <= 0, outside
// the depth range [-1, 1] or beyond the guard band (+-1023 pixels) is
// rejected whole; one partly off the screen is kept (the split drops the
// rows off the screen, the rasteriser the columns).
#pragma once

#include <cstdint>

#include "cluster/records.h"

namespace tessera::cluster {

// Column-major, as GL: element (row, column) is m[column * 4 + row].
struct Matrix4 {
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};

Matrix4 multiply(const Matrix4& a, const Matrix4& b);  // a * b
Matrix4 translation(float x, float y, float z);
Matrix4 scaling(float x, float y, float z);
// A rotation by the angle whose cosine and sine are given, about axis 0
// (x), 1 (y) or 2 (z) (no trigonometry on the ARM: the caller has them).
Matrix4 rotation(int axis, float cosine, float sine);
// As glOrtho and glFrustum.
Matrix4 orthographic(float left, float right, float bottom, float top, float near, float far);
Matrix4 frustum(float left, float right, float bottom, float top, float near, float far);

struct WorldVertex {
  float x = 0, y = 0, z = 0;
  float r = 0, g = 0, b = 0;  // lit colour, 0 .. 1
};

struct WorldTriangle {
  WorldVertex v[3];  // counter-clockwise seen from the front (GL's default)
};

// World (or object) space to clip space, and the screen.
struct View {
  Matrix4 matrix;
  unsigned width = 0, height = 0;  // 1 .. MAX_SCREEN
};

enum class GeometryResult { accepted, culled, rejected };

// Counts the triangle in `counters` (triangles_in and one of accepted,
// culled, rejected); fills `out` when accepted.
GeometryResult transform_triangle(const WorldTriangle& triangle, const View& view, ScreenTriangle* out,
                                  WorkCounters& counters);

}  // namespace tessera::cluster
