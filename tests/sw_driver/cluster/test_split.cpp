// The split and the rasteriser together against an independent reference
// of the fill rule: every pixel a triangle covers is drawn exactly once,
// whatever the number of stripes, and the image does not depend on it.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "cluster/geometry.h"
#include "cluster/scene.h"
#include "cluster_test_support.h"

namespace tessera::cluster {
namespace {

using testing::CollectingSink;
using testing::Frame;
using testing::Piece;
using testing::reference_covers;

// Counts the colour stores per pixel of a width x height screen laid out as
// Frame lays it out (RGBA8888); every depth load reads "far", so every
// pixel walked is stored, and a pixel walked twice is counted twice.
class CoverageMemory : public StripeMemory {
 public:
  CoverageMemory(unsigned width, unsigned height)
      : counts(std::size_t{width} * height), m_far(4 * MAX_SCREEN, 0xff), m_scratch(4 * MAX_SCREEN) {}
  const uint8_t* load(uint32_t, unsigned, unsigned) override { return m_far.data(); }
  uint8_t* store(uint32_t address, unsigned size, unsigned count) override {
    const uint32_t color_bytes = static_cast<uint32_t>(counts.size()) * 4;
    if (address < color_bytes)
      for (unsigned k = 0; k < count; ++k) ++counts.at(address / 4 + k);
    (void)size;
    return m_scratch.data();
  }
  std::vector<unsigned> counts;

 private:
  std::vector<uint8_t> m_far, m_scratch;
};

struct Coverage {
  std::vector<unsigned> counts;
  unsigned pieces = 0;
};

Coverage cover(const std::vector<ScreenTriangle>& triangles, unsigned width, unsigned height, unsigned p) {
  CoverageMemory memory(width, height);
  std::vector<Stripe> stripes;
  stripes.reserve(p);
  for (unsigned s = 0; s < p; ++s) {
    const RowRange rows = stripe_rows(s, height, p);
    StripeBuffers buffers;
    buffers.width = width;
    buffers.first_row = rows.begin;
    buffers.rows = rows.end - rows.begin;
    buffers.color_format = PixelFormat::rgba8888;
    buffers.color_address = rows.begin * width * 4;
    buffers.depth_address = width * height * 4 + rows.begin * width * 4;
    stripes.emplace_back(memory, buffers);
  }
  Coverage out;
  for (const ScreenTriangle& t : triangles) {
    CollectingSink sink;
    out.pieces += split_triangle(t, height, p, sink);
    for (const Piece& piece : sink.pieces) {
      EXPECT_GE(piece.trapezoid.first_row, static_cast<int>(stripe_rows(piece.stripe, height, p).begin));
      EXPECT_LT(piece.trapezoid.last_row, static_cast<int>(stripe_rows(piece.stripe, height, p).end));
      rasterize_trapezoid(piece.trapezoid, stripes[piece.stripe]);
    }
  }
  out.counts = std::move(memory.counts);
  return out;
}

std::vector<unsigned> reference(const std::vector<ScreenTriangle>& triangles, unsigned width, unsigned height) {
  std::vector<unsigned> counts(std::size_t{width} * height);
  for (const ScreenTriangle& t : triangles)
    for (unsigned r = 0; r < height; ++r)
      for (unsigned i = 0; i < width; ++i)
        if (reference_covers(t, static_cast<int>(i), static_cast<int>(r))) ++counts[std::size_t{r} * width + i];
  return counts;
}

// A small generator of the tests' own (not the scene's).
struct TestRandom {
  uint64_t state;
  uint32_t next() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<uint32_t>(state >> 33);
  }
  int32_t in(int32_t low, int32_t high) { return low + static_cast<int32_t>(next() % uint32_t(high - low + 1)); }
};

ScreenVertex vertex(int32_t x, int32_t y) {
  ScreenVertex v;
  v.x = x;
  v.y = y;
  v.z = 100;
  return v;
}

// Triangles of every kind: anywhere (partly off the screen too), small,
// slivers, horizontal edges, vertices on pixel centres and on stripe
// boundaries (multiples of 16 in 9.4: the rows' edges; 16 r + 8: centres).
std::vector<ScreenTriangle> awkward_triangles(uint64_t seed, unsigned width, unsigned height, int count) {
  TestRandom random{seed};
  const int32_t w = static_cast<int32_t>(width) * 16, h = static_cast<int32_t>(height) * 16;
  std::vector<ScreenTriangle> out;
  for (int n = 0; n < count; ++n) {
    ScreenTriangle t;
    const int kind = n % 6;
    for (int k = 0; k < 3; ++k) {
      int32_t x = random.in(-64, w + 64), y = random.in(-64, h + 64);
      if (kind == 1 && k > 0) {  // small
        x = t.v[0].x + random.in(-60, 60);
        y = t.v[0].y + random.in(-60, 60);
      }
      if (kind == 3) {  // on centres or row edges
        x = random.in(-2, static_cast<int32_t>(width) + 2) * 16 + (random.next() % 2) * 8;
        y = random.in(-2, static_cast<int32_t>(height) + 2) * 16 + (random.next() % 2) * 8;
      }
      t.v[k] = vertex(x, y);
    }
    if (kind == 2) t.v[2].y = t.v[1].y;  // a horizontal edge
    if (kind == 4) {                     // a sliver along the first edge
      t.v[2] = vertex(t.v[0].x + (t.v[1].x - t.v[0].x) / 2 + random.in(-3, 3),
                      t.v[0].y + (t.v[1].y - t.v[0].y) / 2 + random.in(-3, 3));
    }
    if (kind == 5) t.v[1].x = t.v[0].x;  // a vertical edge
    out.push_back(t);
  }
  return out;
}

TEST(ClusterSplit, EachTriangleCoversWhatTheReferenceCovers) {
  const unsigned sizes[][2] = {{128, 128}, {100, 131}};
  for (const auto& size : sizes) {
    const unsigned width = size[0], height = size[1];
    for (uint64_t seed = 1; seed <= 40; ++seed) {
      const std::vector<ScreenTriangle> triangles = awkward_triangles(seed, width, height, 12);
      for (const ScreenTriangle& t : triangles) {
        const std::vector<ScreenTriangle> one{t};
        const std::vector<unsigned> expected = reference(one, width, height);
        for (unsigned p : {1u, 2u, 3u, 7u, 64u, 128u}) {
          if (p > height) continue;
          const Coverage got = cover(one, width, height, p);
          ASSERT_EQ(got.counts, expected)
              << "seed " << seed << ", p " << p << ", triangle (" << t.v[0].x << "," << t.v[0].y << ") (" << t.v[1].x
              << "," << t.v[1].y << ") (" << t.v[2].x << "," << t.v[2].y << ")";
        }
      }
    }
  }
}

// A mesh of jittered grid points, each cell cut along a random diagonal,
// its border on the screen's: every pixel is covered exactly once.
TEST(ClusterSplit, AMeshCoversEveryPixelOnce) {
  const unsigned width = 96, height = 90;
  const int cells_x = 7, cells_y = 9;
  TestRandom random{77};
  std::vector<int32_t> gx((cells_x + 1) * (cells_y + 1)), gy(gx.size());
  for (int j = 0; j <= cells_y; ++j) {
    for (int i = 0; i <= cells_x; ++i) {
      int32_t x = i * static_cast<int32_t>(width) * 16 / cells_x, y = j * static_cast<int32_t>(height) * 16 / cells_y;
      if (i > 0 && i < cells_x) x += random.in(-40, 40);
      if (j > 0 && j < cells_y) y += random.in(-40, 40);
      if (j == 4) y = 16 * 40;  // a row of vertices on a row boundary: horizontal shared edges
      gx[j * (cells_x + 1) + i] = x;
      gy[j * (cells_x + 1) + i] = y;
    }
  }
  auto at = [&](int i, int j) { return vertex(gx[j * (cells_x + 1) + i], gy[j * (cells_x + 1) + i]); };
  std::vector<ScreenTriangle> mesh;
  for (int j = 0; j < cells_y; ++j) {
    for (int i = 0; i < cells_x; ++i) {
      const ScreenVertex a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (random.next() % 2 != 0) {
        mesh.push_back({{a, b, c}});
        mesh.push_back({{a, c, d}});
      } else {
        mesh.push_back({{a, b, d}});
        mesh.push_back({{b, c, d}});
      }
    }
  }
  const std::vector<unsigned> once(std::size_t{width} * height, 1);
  EXPECT_EQ(reference(mesh, width, height), once);
  for (unsigned p : {1u, 2u, 3u, 7u, 64u, 90u}) EXPECT_EQ(cover(mesh, width, height, p).counts, once) << "p " << p;
}

TEST(ClusterSplit, PiecesOfOneTriangleGoToEveryStripeItCrossesInOrder) {
  // Rows 0 .. 99 of a 100-row screen: the triangle's rows are those with
  // centres in [y_top, y_bottom) = [0.5, 99.5): rows 0 .. 98.
  ScreenTriangle t{{vertex(8, 8), vertex(1000, 8 + 16 * 50), vertex(8, 8 + 16 * 99)}};
  CollectingSink sink;
  WorkCounters counters;
  EXPECT_EQ(split_triangle(t, 100, 7, sink, &counters), 8u);  // 7 stripes, and the middle vertex's row in stripe 3
  ASSERT_EQ(sink.pieces.size(), 8u);
  // Stripes of 100 rows in 7: floor(s 100 / 7) = 0, 14, 28, 42, 57, 71, 85, 100.
  const int expected[8][3] = {{0, 0, 13},  {1, 14, 27}, {2, 28, 41}, {3, 42, 49},
                              {3, 50, 56}, {4, 57, 70}, {5, 71, 84}, {6, 85, 98}};
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(sink.pieces[k].stripe, static_cast<unsigned>(expected[k][0])) << k;
    EXPECT_EQ(sink.pieces[k].trapezoid.first_row, expected[k][1]) << k;
    EXPECT_EQ(sink.pieces[k].trapezoid.last_row, expected[k][2]) << k;
  }
  EXPECT_EQ(counters.triangles_split, 1u);
  EXPECT_EQ(counters.trapezoids_nonempty, 2u);
  EXPECT_EQ(counters.trapezoids_out, 8u);
  EXPECT_EQ(counters.trapezoid_rows_out, 99u);
}

TEST(ClusterSplit, StripesFollowTheFloorRule) {
  EXPECT_EQ(stripe_parameters_error(512, 0), std::string("nodes: p must be in 1 .. 128"));
  EXPECT_NE(stripe_parameters_error(100, 101), nullptr);
  EXPECT_NE(stripe_parameters_error(513, 1), nullptr);
  EXPECT_EQ(stripe_parameters_error(512, 128), nullptr);
  for (unsigned height : {1u, 7u, 100u, 128u, 131u, 512u}) {
    for (unsigned p = 1; p <= 128 && p <= height; ++p) {
      unsigned previous_end = 0;
      for (unsigned s = 0; s < p; ++s) {
        const RowRange rows = stripe_rows(s, height, p);
        EXPECT_EQ(rows.begin, previous_end);
        EXPECT_GE(rows.end - rows.begin, height / p);
        EXPECT_LE(rows.end - rows.begin, height / p + 1);
        for (unsigned y = rows.begin; y < rows.end; ++y) ASSERT_EQ(stripe_of_row(y, height, p), s);
        previous_end = rows.end;
      }
      EXPECT_EQ(previous_end, height);
    }
  }
}

TEST(ClusterSplit, BadParametersAndDegenerateTrianglesGiveNoPieces) {
  CollectingSink sink;
  const ScreenTriangle t{{vertex(0, 0), vertex(160, 0), vertex(0, 160)}};
  EXPECT_EQ(split_triangle(t, 100, 0, sink), 0u);
  EXPECT_EQ(split_triangle(t, 100, 129, sink), 0u);
  EXPECT_EQ(split_triangle(t, 5, 6, sink), 0u);
  const ScreenTriangle line{{vertex(0, 0), vertex(160, 160), vertex(320, 320)}};
  EXPECT_EQ(split_triangle(line, 100, 3, sink), 0u);
  const ScreenTriangle far_away{{vertex(0, 0), vertex(MAX_COORDINATE + 1, 0), vertex(0, 160)}};
  EXPECT_EQ(split_triangle(far_away, 100, 3, sink), 0u);
  EXPECT_TRUE(sink.pieces.empty());
}

// The random scene's image, drawn in the same triangle order, is the same
// bytes whatever the number of stripes.
TEST(ClusterSplit, TheImageDoesNotDependOnTheStripes) {
  for (PixelFormat format : {PixelFormat::rgb565, PixelFormat::rgba8888}) {
    RandomScene scene;
    scene.seed = 11;
    scene.count = 6000;
    scene.size = 14;
    scene.width = 512;
    scene.height = 512;
    const View view = random_scene_view(scene);
    std::vector<ScreenTriangle> triangles;
    WorkCounters counters;
    for (uint32_t i = 0; i < scene.count; ++i) {
      ScreenTriangle t;
      if (transform_triangle(random_triangle(scene, i), view, &t, counters) == GeometryResult::accepted)
        triangles.push_back(t);
    }
    Frame one(512, 512, 1, format);
    one.draw(triangles);
    EXPECT_GT(one.stripes[0].counters().depth_passes, 100000u);
    for (unsigned p : {2u, 3u, 7u, 64u, 128u}) {
      Frame many(512, 512, p, format);
      many.draw(triangles);
      EXPECT_TRUE(many.bytes() == one.bytes()) << "p " << p;
    }
  }
}

}  // namespace
}  // namespace tessera::cluster
