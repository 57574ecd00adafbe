// Traversal (tlm/raster/core/traversal.h) on its own: traversal_box's
// bounding box of pixel centres cut to the tile and the scissor, and
// traverse's fill rule, with flat-shaded triangles set up by hand (edges
// and colour, no triangle_setup) and drawn with additive blending into a
// tile cache, so that every pixel shows how many times and by which
// triangle it was drawn. Expected pixels follow the fill rule of
// tlm/raster/core/README.md ("Traversal and coverage"): a centre (16 p + 8
// in 9.4) on an edge belongs to the triangle when the edge, taken
// clockwise, has dy > 0, or dy == 0 and dx < 0 (left and bottom edges in
// GL's y-up coordinates), so a centre on a shared edge is drawn once.
#include <gtest/gtest.h>

#include <memory>

#include "raster/core/traversal.h"
#include "raster_core_test_support.h"

using namespace tessera::raster;
using tessera::BlendFactor;
using tessera::PixelFormat;
using tessera::raster::test::StageRun;

namespace {

struct Point {
  uint32_t x, y;  // 9.4 codes
};

TriangleVertices vertices(const std::array<Point, 3>& p) {
  TriangleVertices v;
  for (unsigned k = 0; k < 3; ++k) {
    v[k].x = p[k].x;
    v[k].y = p[k].y;
  }
  return v;
}

// A flat-shaded triangle given clockwise (interior on the edges' right),
// planes starting at pixel (0, 0).
TriangleSetup flat_triangle(const std::array<Point, 3>& clockwise, uint32_t rgba) {
  TriangleSetup ts;
  for (unsigned k = 0; k < 3; ++k) {
    const Point a = clockwise[k], b = clockwise[(k + 1) % 3];
    ts.edges[k] = {q9_4::from_raw(a.x), q9_4::from_raw(a.y), q9_4::from_raw(b.x), q9_4::from_raw(b.y)};
  }
  ts.flat = true;
  ts.flat_color = Rgba8::unpack(rgba);
  ts.depth = attribute_plane_from_raw(AttributeKind::depth, 0, 0, 0);
  return ts;
}

// A 64 x 64 RGBA8888 frame in one tile, the tile cache starting at 0, the
// state blending ONE, ONE: each fragment adds its colour.
struct TraversalBench : StageRun {
  TraversalBench() : StageRun(0x100, frame()), cache(config), shader_work(new ShadingWorkspace) {
    cache.select(0, 0);
    state.operations.blend = true;
    state.operations.blend_src = BlendFactor::one;
    state.operations.blend_dst = BlendFactor::one;
  }
  static RunConfig frame() {
    RunConfig c;
    c.width = c.height = c.tile_width = c.tile_height = 64;
    c.color_format = PixelFormat::rgba8888;
    return c;
  }
  void draw(const TriangleSetup& ts, const Rect& box) {
    FragmentShader shader(run, cache, state, *shader_work);
    traverse(run, ts, box, false, *shader_work, shader);
  }
  uint32_t pixel(int x, int y) { return cache.color(cache.index(x, y)); }

  TileCache cache;
  DrawState state;
  std::unique_ptr<ShadingWorkspace> shader_work;  // about 250 KB
};

TEST(Traversal, BoxOfPixelCentresCutToTileAndScissor) {
  // x from 1.25 to 6.25, y from 1.5 to 12.5: centres p + 1/2 in [1.25, 6.25]
  // are p = 1..5, in [1.5, 12.5] p = 1..12.
  const TriangleVertices v = vertices({{{20, 24}, {100, 24}, {60, 200}}});
  const Rect tile{0, 0, 32, 16};
  DrawState state;
  const Rect box = traversal_box(v, false, tile, state);
  EXPECT_EQ(box.x0, 1);
  EXPECT_EQ(box.y0, 1);
  EXPECT_EQ(box.x1, 6);
  EXPECT_EQ(box.y1, 13);
  // polygon_smooth grows it by one pixel on each side.
  const Rect smooth = traversal_box(v, true, tile, state);
  EXPECT_EQ(smooth.x0, 0);
  EXPECT_EQ(smooth.y0, 0);
  EXPECT_EQ(smooth.x1, 7);
  EXPECT_EQ(smooth.y1, 14);
  // Another tile: x 4.., y 8..
  const Rect cut = traversal_box(v, false, Rect{4, 8, 36, 24}, state);
  EXPECT_EQ(cut.x0, 4);
  EXPECT_EQ(cut.y0, 8);
  EXPECT_EQ(cut.x1, 6);
  EXPECT_EQ(cut.y1, 13);
  // The scissor cuts it further (and only with its flag).
  state.scissor_box = {0, 10, 100, 11};
  EXPECT_EQ(traversal_box(v, false, Rect{4, 8, 36, 24}, state).y0, 8);
  state.scissor = true;
  const Rect scissored = traversal_box(v, false, Rect{4, 8, 36, 24}, state);
  EXPECT_EQ(scissored.x0, 4);
  EXPECT_EQ(scissored.y0, 10);
  EXPECT_EQ(scissored.x1, 6);
  EXPECT_EQ(scissored.y1, 11);
}

TEST(Traversal, BoxIsEmptyWithoutACentreInside) {
  // x from 0 to 7/16: the first centre, 1/2, is beyond it.
  const TriangleVertices v = vertices({{{0, 0}, {7, 0}, {0, 100}}});
  EXPECT_TRUE(traversal_box(v, false, Rect{0, 0, 32, 32}, DrawState{}).empty());
  // A maximum exactly on a centre (6.5) takes that pixel.
  const TriangleVertices on = vertices({{{0, 0}, {104, 0}, {0, 100}}});
  EXPECT_EQ(traversal_box(on, false, Rect{0, 0, 32, 32}, DrawState{}).x1, 7);
}

TEST(Traversal, ASharedEdgeThroughPixelCentresIsDrawnOnce) {
  TraversalBench b;
  // The square (0.5, 0.5) - (4.5, 4.5) split along its diagonal, which runs
  // through the centres of pixels (p, p). Clockwise:
  //   lower right: (0.5, 0.5) -> (4.5, 4.5) -> (4.5, 0.5): the diagonal goes
  //     up (dy > 0): its centres are this triangle's; the bottom edge goes
  //     -x (dy == 0, dx < 0): row 0 is in; the right edge goes down: out.
  //   upper left: (0.5, 0.5) -> (0.5, 4.5) -> (4.5, 4.5): the left edge goes
  //     up: column 0 is in; the top edge goes +x: out; the diagonal down: out.
  const std::array<Point, 3> lower{{{8, 8}, {72, 72}, {72, 8}}};
  const std::array<Point, 3> upper{{{8, 8}, {8, 72}, {72, 72}}};
  const Rect box = traversal_box(vertices(lower), false, b.cache.tile(), b.state);
  EXPECT_EQ(box.x1, 5);  // centres 0.5 .. 4.5: pixels 0..4, 25 in the box
  b.draw(flat_triangle(lower, 0x00000001), box);
  EXPECT_EQ(b.run.result().fragments, 10u);  // y <= x, x and y in 0..3
  b.draw(flat_triangle(upper, 0x00000100), traversal_box(vertices(upper), false, b.cache.tile(), b.state));
  EXPECT_EQ(b.run.result().fragments, 16u);  // and 6 above the diagonal
  // Every pixel of the 4 x 4 square drawn once, by the triangle the rule
  // gives it; nothing on the right column or the top row (4).
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      const uint32_t expected = x > 3 || y > 3 ? 0u : y <= x ? 0x00000001u : 0x00000100u;
      EXPECT_EQ(b.pixel(x, y), expected) << x << "," << y;
    }
  // One fragment cycle per pixel of each box, covered or not.
  EXPECT_EQ(b.run.result().fragment_cycles, 2u * 25);
  // The spans, one per row with a pixel inside: the lower triangle's rows
  // 0..3 hold 4, 3, 2, 1 pixels, the upper's rows 1..3 hold 1, 2, 3.
  const tessera::Log2Histogram& spans = b.run.result().span_pixels;
  EXPECT_EQ(spans.count(), 7u);
  EXPECT_EQ(spans.sum(), 16u);  // every fragment
  EXPECT_EQ(spans.min(), 1u);
  EXPECT_EQ(spans.max(), 4u);
  EXPECT_EQ(spans.bucket(tessera::Log2Histogram::bucket_of(1)), 2u);  // 1 and 1
  EXPECT_EQ(spans.bucket(tessera::Log2Histogram::bucket_of(2)), 4u);  // 2-3: 3, 2, 2, 3
  EXPECT_EQ(spans.bucket(tessera::Log2Histogram::bucket_of(4)), 1u);  // 4-7: 4
}

TEST(Traversal, OnlyThePixelsOfTheBoxAreVisited) {
  TraversalBench b;
  const std::array<Point, 3> lower{{{8, 8}, {72, 72}, {72, 8}}};
  b.draw(flat_triangle(lower, 0x00000001), Rect{1, 0, 3, 2});
  // (1, 0), (2, 0), (1, 1), (2, 1): all with y <= x.
  EXPECT_EQ(b.run.result().fragments, 4u);
  EXPECT_EQ(b.run.result().fragment_cycles, 4u);
  EXPECT_EQ(b.pixel(0, 0), 0u);
  EXPECT_EQ(b.pixel(1, 1), 1u);
  EXPECT_EQ(b.pixel(3, 0), 0u);
}

TEST(Traversal, ATriangleOfManyBatchesLosesNoFragment) {
  TraversalBench b;
  // The lower-right half of (0.5, 0.5) - (64.5, 64.5): pixels with y <= x,
  // 64 * 65 / 2 = 2080 of them in the tile (x = 64 is beyond it), in
  // batches of 512.
  const std::array<Point, 3> lower{{{8, 8}, {1032, 1032}, {1032, 8}}};
  const Rect box = traversal_box(vertices(lower), false, b.cache.tile(), b.state);
  EXPECT_EQ(box.x1, 64);
  b.draw(flat_triangle(lower, 0x00000001), box);
  EXPECT_EQ(b.run.result().fragments, 2080u);
  EXPECT_EQ(b.run.result().fragment_cycles, 64u * 64);
  unsigned wrong = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) wrong += b.pixel(x, y) != (y <= x ? 1u : 0u);
  EXPECT_EQ(wrong, 0u);
}

TEST(Traversal, PolygonSmoothGivesEachPixelItsEasaCoverage) {
  TraversalBench b;
  b.state.flags |= StateFlag::polygon_smooth;
  b.state.operations.blend = false;
  // Clockwise: (0.75, 0.5) -> (0.75, 16.5) -> (16.75, 0.5). The left edge is
  // 1/4 pixel right of column 0's centres, the bottom edge runs through row
  // 0's centres. Coverage = min over the edges of clamp(1/2 + E / (|dx| +
  // |dy|), 0, 1) in 0.8 (README.md, "Traversal and coverage";
  // datapath/edge_function.h: (255 t + 128) >> 8 with t = 256 (1/2 + d)):
  // 1/2 - 1/4 -> t 64 -> 64; 1/2 -> 128; 1/2 + 3/4 or more -> 255.
  const std::array<Point, 3> clockwise{{{12, 8}, {12, 264}, {268, 8}}};
  TriangleSetup ts = flat_triangle(clockwise, 0xff0000ff);
  // 1 / (|dx| + |dy|) in 5.16: the legs 16 pixels (1/16), the hypotenuse 32.
  ts.edge_recip = {q5_16::from_raw(4096), q5_16::from_raw(2048), q5_16::from_raw(4096)};
  const Rect box = traversal_box(vertices(clockwise), true, b.cache.tile(), b.state);
  EXPECT_EQ(box.x0, 0);  // grown by one pixel, cut to the tile
  FragmentShader shader(b.run, b.cache, b.state, *b.shader_work);
  traverse(b.run, ts, box, true, *b.shader_work, shader);
  // The coverage multiplies alpha (255): round(255 c / 255) = c.
  EXPECT_EQ(b.pixel(0, 0) >> 24, 64u);   // left edge 64, bottom 128
  EXPECT_EQ(b.pixel(1, 0) >> 24, 128u);  // left 255, bottom 128
  EXPECT_EQ(b.pixel(0, 1) >> 24, 64u);   // left 64, bottom 1/2 + 1 -> 255
  EXPECT_EQ(b.pixel(2, 2) >> 24, 255u);  // inside by more than 1/2 from every edge
  EXPECT_EQ(b.pixel(2, 2) & 0xffffff, 0x0000ffu);
  // The column left of the edge by 3/4 (pixel -1) is outside the tile; the
  // pixels right of the hypotenuse by more than 1/2 get no fragment.
  EXPECT_EQ(b.pixel(20, 0), 0u);
}

}  // namespace
