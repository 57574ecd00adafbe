// Triangle setup (tlm/raster/core/triangle_setup.h) on its own: a right
// triangle with legs of 8 pixels along the axes, whose area, edges,
// reciprocals and plane equations are worked out by hand below from the
// formulas of tlm/raster/core/README.md ("Triangle setup", "Texture
// coordinates"). The quantities are powers of two, so the refined
// reciprocal (good to about 2^-28) gives them exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "raster/core/triangle_setup.h"

using namespace tessera::raster;

namespace {

// A vertex at pixel coordinates (x, y) (9.4 codes 16 x, 16 y).
TriangleVertex at(double x, double y, uint32_t rgba, uint32_t z = 0) {
  TriangleVertex v;
  v.x = uint32_t(std::lround(x * 16));
  v.y = uint32_t(std::lround(y * 16));
  v.z = z;
  v.color = Rgba8::unpack(rgba);
  v.inv_w = 1.0f;
  return v;
}

// v0 = (0, 0), v1 = (8, 0), v2 = (0, 8), counter-clockwise in GL's y-up
// window coordinates. R is 0, 128, 0 (16 codes a pixel in x), G 0, 0, 64 (8
// a pixel in y), B 200 and A 255 everywhere; depth 0, 2^23, 2^22 (2^20 a
// pixel in x, 2^19 in y).
TriangleVertices right_triangle() {
  return {at(0, 0, 0xffc80000, 0), at(8, 0, 0xffc80080, 0x800000), at(0, 8, 0xffc84000, 0x400000)};
}

TEST(TriangleSetup, RightTriangleAreaEdgesAndReciprocals) {
  TriangleSetup ts;
  ASSERT_TRUE(set_up_triangle(right_triangle(), DrawState{}, RecipMethod::method3, ts));
  // area2 = (x1 - x0)(y2 - y0) - (x2 - x0)(y1 - y0) = 128 * 128 = 16384 > 0:
  // counter-clockwise, so the edges are taken v0 -> v2 -> v1 (clockwise).
  const auto expect_edge = [&](unsigned k, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
    EXPECT_EQ(ts.edges[k].x0.raw, x0) << k;
    EXPECT_EQ(ts.edges[k].y0.raw, y0) << k;
    EXPECT_EQ(ts.edges[k].x1.raw, x1) << k;
    EXPECT_EQ(ts.edges[k].y1.raw, y1) << k;
  };
  expect_edge(0, 0, 0, 0, 128);
  expect_edge(1, 0, 128, 128, 0);
  expect_edge(2, 128, 0, 0, 0);
  // EASA reciprocals 1 / (|dx| + |dy|) in 5.16: legs 8 -> 1/8 = 8192, the
  // hypotenuse 8 + 8 = 16 -> 1/16 = 4096.
  EXPECT_EQ(ts.edge_recip[0].raw, 8192u);
  EXPECT_EQ(ts.edge_recip[1].raw, 4096u);
  EXPECT_EQ(ts.edge_recip[2].raw, 8192u);
  // E = (cx - x0) dy - (cy - y0) dx at pixel centres (16 p + 8): positive
  // inside. Pixel (0, 0), centre (8, 8): 8 * 128 = 1024 on both legs, and
  // 8 * -128 - (8 - 128) * 128 = 14336 on the hypotenuse; pixel (7, 7),
  // centre (120, 120), is outside the hypotenuse: -15360 + 1024 = -14336.
  EXPECT_EQ(edge_value_at(ts.edges[0], 0, 0).raw, 1024);
  EXPECT_EQ(edge_value_at(ts.edges[1], 0, 0).raw, 14336);
  EXPECT_EQ(edge_value_at(ts.edges[2], 0, 0).raw, 1024);
  EXPECT_EQ(edge_value_at(ts.edges[1], 7, 7).raw, -14336);
}

TEST(TriangleSetup, ClockwiseInputGivesTheSameEdges) {
  TriangleVertices v = right_triangle();
  std::swap(v[1], v[2]);  // area2 = -16384: taken in the order given
  TriangleSetup ts;
  ASSERT_TRUE(set_up_triangle(v, DrawState{}, RecipMethod::method3, ts));
  EXPECT_EQ(ts.edges[0].y1.raw, 128u);  // v0 -> (0, 8)
  EXPECT_EQ(ts.edges[1].x1.raw, 128u);  // (0, 8) -> (8, 0)
  EXPECT_EQ(ts.edges[2].x0.raw, 128u);  // (8, 0) -> v0
}

TEST(TriangleSetup, PlaneEquationsOfDepthAndGouraudColour) {
  TriangleSetup ts;
  ASSERT_TRUE(set_up_triangle(right_triangle(), DrawState{}, RecipMethod::method3, ts));
  EXPECT_FALSE(ts.flat);
  // All 1/w equal: colours are linear in screen space, no division per pixel.
  EXPECT_FALSE(ts.perspective_color);
  // The reference pixel holds v0: (0, 0), centre (0.5, 0.5).
  EXPECT_EQ(ts.ref_x, 0);
  EXPECT_EQ(ts.ref_y, 0);
  // Depth words are codes << 8: grad_x = 2^20 << 8, grad_y = 2^19 << 8, and
  // at the centre 0.5 * 2^20 + 0.5 * 2^19 = 0xc0000, << 8.
  EXPECT_EQ(ts.depth.grad_x, int64_t{0x10000000});
  EXPECT_EQ(ts.depth.grad_y, int64_t{0x8000000});
  EXPECT_EQ(ts.depth.start, int64_t{0xc000000});
  // Colour words are codes << 16. R: 16 a pixel in x, 8 at the centre.
  EXPECT_EQ(ts.color[0].grad_x, int64_t{16} << 16);
  EXPECT_EQ(ts.color[0].grad_y, 0);
  EXPECT_EQ(ts.color[0].start, int64_t{8} << 16);
  // G: 8 a pixel in y, 4 at the centre.
  EXPECT_EQ(ts.color[1].grad_x, 0);
  EXPECT_EQ(ts.color[1].grad_y, int64_t{8} << 16);
  EXPECT_EQ(ts.color[1].start, int64_t{4} << 16);
  // B and A constant.
  EXPECT_EQ(ts.color[2].start, int64_t{200} << 16);
  EXPECT_EQ(ts.color[2].grad_x, 0);
  EXPECT_EQ(ts.color[3].start, int64_t{255} << 16);
  EXPECT_EQ(ts.color[3].grad_y, 0);
  // 1/w = 1 everywhere, normalised to [1/2, 1): q = 0.5 in q15.24 = 2^23.
  EXPECT_EQ(ts.q.start, int64_t{1} << 23);
  EXPECT_EQ(ts.q.grad_x, 0);
  EXPECT_EQ(ts.q.grad_y, 0);
}

TEST(TriangleSetup, PlanesStartAtTheCentreOfThePixelHoldingVertexZero) {
  // The triangle moved so that v0 = (2.75, 3.25): the reference pixel is
  // (2, 3), whose centre (2.5, 3.5) is (-0.25, +0.25) from v0; the planes
  // are extrapolated there: R 16 * -0.25 = -4, G 8 * 0.25 = 2, depth
  // 2^20 * -0.25 + 2^19 * 0.25 = -2^17.
  TriangleVertices v = right_triangle();
  for (TriangleVertex& vertex : v) {
    vertex.x += 44;  // 2.75 in 9.4
    vertex.y += 52;  // 3.25
  }
  TriangleSetup ts;
  ASSERT_TRUE(set_up_triangle(v, DrawState{}, RecipMethod::method3, ts));
  EXPECT_EQ(ts.ref_x, 2);
  EXPECT_EQ(ts.ref_y, 3);
  EXPECT_EQ(ts.color[0].start, -(int64_t{4} << 16));
  EXPECT_EQ(ts.color[1].start, int64_t{2} << 16);
  EXPECT_EQ(ts.depth.start, -(int64_t{1} << 17 << 8));
  EXPECT_EQ(ts.color[0].grad_x, int64_t{16} << 16);  // gradients unchanged by the move
}

TEST(TriangleSetup, FlatShadingTakesTheProvokingVertex) {
  DrawState state;
  state.flags |= StateFlag::flat_shading;
  TriangleSetup ts;
  ASSERT_TRUE(set_up_triangle(right_triangle(), state, RecipMethod::method3, ts));
  EXPECT_TRUE(ts.flat);
  EXPECT_EQ(ts.flat_color.pack(), 0xffc84000u);  // v[2]'s colour
}

TEST(TriangleSetup, TextureCoordinatePlanes) {
  // s/w 0, 1, 0 and t/w 0, 0, 1 with 1/w = 1: after the normalisation by
  // 2^-1 the words are 0, 2^23, 0 (q15.24), so s/w rises 2^23 / 8 = 2^20 a
  // pixel in x and is 2^19 at the reference centre; s = (s/w) / q there is
  // 2^19 / 2^23 = 1/16 = 0.5 / 8, the texture's s at x = 0.5.
  TriangleVertices v = right_triangle();
  v[1].s_over_w = 1.0f;
  v[2].t_over_w = 1.0f;
  DrawState state;
  state.flags |= StateFlag::texture;
  TriangleSetup ts;
  ASSERT_TRUE(set_up_triangle(v, state, RecipMethod::method3, ts));
  EXPECT_EQ(ts.s.grad_x, int64_t{1} << 20);
  EXPECT_EQ(ts.s.grad_y, 0);
  EXPECT_EQ(ts.s.start, int64_t{1} << 19);
  EXPECT_EQ(ts.t.grad_x, 0);
  EXPECT_EQ(ts.t.grad_y, int64_t{1} << 20);
  EXPECT_EQ(ts.t.start, int64_t{1} << 19);
}

TEST(TriangleSetup, RefusesZeroAreaAndUnusableTextureCoordinates) {
  TriangleSetup ts;
  // Three vertices on a line: area2 = 0, the reciprocal unit's operand 0.
  const TriangleVertices line = {at(0, 0, 0), at(4, 4, 0), at(8, 8, 0)};
  EXPECT_FALSE(set_up_triangle(line, DrawState{}, RecipMethod::method3, ts));
  DrawState textured;
  textured.flags |= StateFlag::texture;
  TriangleVertices v = right_triangle();
  v[0].inv_w = 0;  // 1/w must be finite and positive
  EXPECT_FALSE(set_up_triangle(v, textured, RecipMethod::method3, ts));
  EXPECT_TRUE(set_up_triangle(v, DrawState{}, RecipMethod::method3, ts));  // untextured: screen-linear colours
  EXPECT_FALSE(ts.perspective_color);
  v = right_triangle();
  v[1].s_over_w = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(set_up_triangle(v, textured, RecipMethod::method3, ts));
  v = right_triangle();
  v[1].s_over_w = 70000.0f;  // normalised: 35000, beyond q15.24's +-32767
  EXPECT_FALSE(set_up_triangle(v, textured, RecipMethod::method3, ts));
}

TEST(RefinedReciprocal, TwoNewtonStepsBoundTheSeedsErrorToItsFourthPower) {
  // 1/v = y 2^-(30 + n) after the unit's seed and two Newton-Raphson steps
  // (README.md, "Reciprocal of the area"). Each step squares the relative
  // error e = 1 - f y. Every method's seed is a truncated 1/X with 6 or 7
  // significant bits (a 1.6 mantissa; Method 1's 5.10 entry of 1/X for X
  // in [8, 16), whose 8-bit operand is itself truncated): e0 < 1.5 * 2^-6,
  // so e2 < 5.1 * 2^-24 < 2^-21, plus the Q30 truncations (about 2^-29).
  // README.md's "about 2^-28" is the typical case, not a bound: over
  // every v below 2^22 the worst is near 2^-24 for each method.
  for (RecipMethod method : {RecipMethod::method1, RecipMethod::method2, RecipMethod::method3})
    for (uint64_t v : {uint64_t{3}, uint64_t{7}, uint64_t{1000}, uint64_t{12345}, (uint64_t{1} << 27) - 1}) {
      Reciprocal r;
      ASSERT_TRUE(refined_reciprocal(v, method, r));
      const double relative = std::ldexp(double(r.y), -(30 + r.n)) * double(v) - 1;
      EXPECT_LT(std::fabs(relative), std::ldexp(1.0, -21)) << int(method) << " " << v;
    }
  Reciprocal zero;
  EXPECT_FALSE(refined_reciprocal(0, RecipMethod::method3, zero));  // the unit flags operand 0
}

TEST(RefinedReciprocal, QuotientsRoundToNearestTiesUp) {
  // 1/4 is exact: f = 1/2, the seed 2 is a fixed point of the refinement.
  Reciprocal quarter;
  ASSERT_TRUE(refined_reciprocal(4, RecipMethod::method3, quarter));
  EXPECT_EQ(divide(10, quarter, false), 3);     // 2.5 up
  EXPECT_EQ(divide(-10, quarter, false), -2);   // -2.5 up, towards +infinity
  EXPECT_EQ(divide(10, quarter, true), -2);     // 10 / -4
  EXPECT_EQ(divide(9, quarter, false), 2);      // 2.25
  EXPECT_EQ(divide(10, quarter, false, 2), 1);  // 2.5 / 4 = 0.625 -> 1
  // A numerator beyond the 64-bit path: 2^70 / 4 = 2^68 exactly.
  EXPECT_TRUE(divide(int128{1} << 70, quarter, false) == int128{1} << 68);
}

}  // namespace
