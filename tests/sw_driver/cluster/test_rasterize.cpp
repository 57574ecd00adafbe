// The stripe rasteriser against values computed by hand: the colour and
// depth at pixel centres of small triangles, the depth test, the scissor,
// and the buffers' checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cluster_test_support.h"

namespace tessera::cluster {
namespace {

using testing::Frame;

ScreenVertex vertex(int32_t x, int32_t y, uint32_t z, uint8_t r, uint8_t g, uint8_t b) {
  ScreenVertex v;
  v.x = x;
  v.y = y;
  v.z = z;
  v.r = r;
  v.g = g;
  v.b = b;
  return v;
}

// A right triangle with legs of 16 pixels at the origin (9.4: 256): red
// 0 -> 255 along x, green 0 -> 128 along y, blue 200; z 1000, + 4096 per
// pixel in x, + 65536 per pixel in y. At the centre of pixel (i, r):
// red = 255 (i + 1/2) / 16, green = 8 r + 4, z = 1000 + 4096 (i + 1/2) +
// 65536 (r + 1/2). Its pixels are those with i + r <= 14 (a centre with
// i + r = 15 lies on the hypotenuse, a right edge): 120 of them.
ScreenTriangle hand_triangle(int32_t z_offset = 0) {
  return {{vertex(0, 0, static_cast<uint32_t>(1000 + z_offset), 0, 0, 200),
           vertex(256, 0, static_cast<uint32_t>(1000 + 16 * 4096 + z_offset), 255, 0, 200),
           vertex(0, 256, static_cast<uint32_t>(1000 + 16 * 65536 + z_offset), 0, 128, 200)}};
}

uint32_t rgba(uint32_t r, uint32_t g, uint32_t b) {
  return r | g << 8 | b << 16 | 0xffu << 24;
}

TEST(ClusterRasterize, GouraudAndDepthAtPixelCentres) {
  Frame frame(20, 20, 1);
  frame.draw({hand_triangle()});
  EXPECT_EQ(frame.stripes[0].counters().depth_passes, 120u);
  EXPECT_EQ(frame.stripes[0].counters().pixels, 120u);
  // Rows 0 .. 15 (centres 0.5 .. 15.5 < 16); row 15's span is empty (its
  // one candidate, pixel 0, has its centre on the hypotenuse).
  EXPECT_EQ(frame.stripes[0].counters().rows, 16u);
  EXPECT_EQ(frame.stripes[0].counters().spans, 15u);
  // red 255 * 0.5 / 16 = 7.97 -> 8; green 4.
  EXPECT_EQ(frame.color(0, 0), rgba(8, 4, 200));
  EXPECT_EQ(frame.depth(0, 0), 1000u + 2048 + 32768);
  // (3, 5): red 255 * 3.5 / 16 = 55.78 -> 56; green 44.
  EXPECT_EQ(frame.color(3, 5), rgba(56, 44, 200));
  EXPECT_EQ(frame.depth(3, 5), 1000u + 4096 * 3 + 2048 + 65536 * 5 + 32768);
  // (10, 4): red 255 * 10.5 / 16 = 167.34 -> 167; green 36.
  EXPECT_EQ(frame.color(10, 4), rgba(167, 36, 200));
  // (14, 0): red 255 * 14.5 / 16 = 231.09 -> 231.
  EXPECT_EQ(frame.color(14, 0), rgba(231, 4, 200));
  EXPECT_EQ(frame.color(0, 14), rgba(8, 116, 200));
  // Outside: i + r = 15 on the hypotenuse, and beyond.
  EXPECT_EQ(frame.color(15, 0), 0xff000000u);
  EXPECT_EQ(frame.color(7, 8), 0xff000000u);
  EXPECT_EQ(frame.depth(7, 8), MAX_DEPTH);
  EXPECT_EQ(frame.color(0, 15), 0xff000000u);
}

TEST(ClusterRasterize, Rgb565RoundsEachChannelToNearest) {
  Frame frame(20, 20, 1, PixelFormat::rgb565);
  frame.draw({hand_triangle()});
  // (10, 3): 167, 28, 200 -> round(167 * 31 / 255) = 20, round(28 * 63 /
  // 255) = 7, round(200 * 31 / 255) = 24.
  EXPECT_EQ(frame.color(10, 3), (20u << 11) | (7u << 5) | 24u);
}

TEST(ClusterRasterize, TheDepthTestIsLessThan) {
  Frame frame(20, 20, 1);
  frame.draw({hand_triangle()});
  ScreenTriangle nearer = hand_triangle(-10);
  for (ScreenVertex& v : nearer.v) v.r = v.g = v.b = 0;
  ScreenTriangle same = hand_triangle(0), farther = hand_triangle(10);
  for (ScreenVertex& v : same.v) v.g = 255;
  for (ScreenVertex& v : farther.v) v.g = 255;
  frame.draw({same, farther});
  EXPECT_EQ(frame.stripes[0].counters().depth_passes, 120u);  // neither equal nor farther z passes
  EXPECT_EQ(frame.color(3, 5), rgba(56, 44, 200));
  frame.draw({nearer});
  EXPECT_EQ(frame.stripes[0].counters().depth_passes, 240u);
  EXPECT_EQ(frame.color(3, 5), rgba(0, 0, 0));
  EXPECT_EQ(frame.depth(3, 5), 1000u - 10 + 4096 * 3 + 2048 + 65536 * 5 + 32768);
}

TEST(ClusterRasterize, SpansAreScissoredToTheScreen) {
  // An 8 x 10 screen: rows 0 .. 9 (the split drops the rest), on row r the
  // pixels 0 .. min(14 - r, 7): 8 on rows 0 .. 7, 7 on row 8, 6 on row 9.
  Frame frame(8, 10, 2);
  frame.draw({hand_triangle()});
  const uint64_t passes = frame.stripes[0].counters().depth_passes + frame.stripes[1].counters().depth_passes;
  EXPECT_EQ(passes, 77u);
  EXPECT_EQ(frame.color(7, 7), rgba(120, 60, 200));  // red 255 * 7.5 / 16 = 119.53
  // Moved 5 pixels off the left side: pixel i shows the triangle's i + 5,
  // on row r the pixels 0 .. 9 - r: 55 in all.
  ScreenTriangle left = hand_triangle();
  for (ScreenVertex& v : left.v) v.x -= 80;
  Frame moved(20, 20, 3);
  moved.draw({left});
  uint64_t moved_passes = 0;
  for (const Stripe& stripe : moved.stripes) moved_passes += stripe.counters().depth_passes;
  EXPECT_EQ(moved_passes, 55u);
  EXPECT_EQ(moved.color(0, 0), rgba(88, 4, 200));    // 255 * 5.5 / 16 = 87.66
  EXPECT_EQ(moved.color(2, 3), rgba(120, 28, 200));  // the triangle's (7, 3): 255 * 7.5 / 16 = 119.53
}

// Gouraud on general triangles: every drawn pixel within one code of the
// exact barycentric interpolation at its centre (rounded to nearest), and
// depth within two.
TEST(ClusterRasterize, GeneralTrianglesInterpolateWithinRounding) {
  uint64_t state = 5;
  auto next = [&](int n) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<int32_t>((state >> 33) % static_cast<uint64_t>(n));
  };
  for (int n = 0; n < 300; ++n) {
    ScreenTriangle t;
    for (ScreenVertex& v : t.v)
      v = vertex(next(64 * 16), next(64 * 16), static_cast<uint32_t>(next(1 << 24)), static_cast<uint8_t>(next(256)),
                 static_cast<uint8_t>(next(256)), static_cast<uint8_t>(next(256)));
    Frame frame(64, 64, 5);
    frame.draw({t});
    const double x0 = t.v[0].x, y0 = t.v[0].y, x1 = t.v[1].x, y1 = t.v[1].y, x2 = t.v[2].x, y2 = t.v[2].y;
    const double area = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
    for (unsigned r = 0; r < 64; ++r) {
      for (unsigned i = 0; i < 64; ++i) {
        const bool covered = testing::reference_covers(t, static_cast<int>(i), static_cast<int>(r));
        ASSERT_EQ(frame.depth(i, r) != MAX_DEPTH || frame.color(i, r) != 0xff000000u, covered) << n;
        if (!covered) continue;
        const double px = 16.0 * i + 8, py = 16.0 * r + 8;
        const double w1 = ((px - x0) * (y2 - y0) - (py - y0) * (x2 - x0)) / area;
        const double w2 = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)) / area;
        auto exact = [&](double a0, double a1, double a2) { return a0 + w1 * (a1 - a0) + w2 * (a2 - a0); };
        const uint32_t c = frame.color(i, r);
        const double expected[3] = {exact(t.v[0].r, t.v[1].r, t.v[2].r), exact(t.v[0].g, t.v[1].g, t.v[2].g),
                                    exact(t.v[0].b, t.v[1].b, t.v[2].b)};
        for (int k = 0; k < 3; ++k)
          ASSERT_LE(std::fabs(static_cast<double>((c >> (8 * k)) & 255) - expected[k]), 1.0) << n << " " << k;
        ASSERT_LE(std::fabs(frame.depth(i, r) - exact(t.v[0].z, t.v[1].z, t.v[2].z)), 2.0) << n;
      }
    }
  }
}

TEST(ClusterRasterize, APieceForAnotherStripeDrawsNothing) {
  std::vector<uint8_t> bytes(4096);
  ArrayMemory memory(bytes.data(), bytes.size());
  StripeBuffers buffers;
  buffers.width = 16;
  buffers.first_row = 20;
  buffers.rows = 10;
  buffers.depth_address = 2048;
  ASSERT_EQ(Stripe::error(buffers, &memory), nullptr);
  Stripe stripe(memory, buffers);
  testing::CollectingSink sink;
  split_triangle(hand_triangle(), 512, 1, sink);
  ASSERT_EQ(sink.pieces.size(), 1u);
  rasterize_trapezoid(sink.pieces[0].trapezoid, stripe);
  EXPECT_EQ(stripe.counters().trapezoids_in, 1u);
  EXPECT_EQ(stripe.counters().rows, 0u);
  EXPECT_EQ(stripe.counters().pixels, 0u);
}

TEST(ClusterRasterize, BadBuffersAreNamed) {
  std::vector<uint8_t> bytes(1024);
  ArrayMemory memory(bytes.data(), bytes.size(), 0x1000);
  StripeBuffers buffers;
  buffers.width = 8;
  buffers.first_row = 0;
  buffers.rows = 8;
  buffers.color_address = 0x1000;        // 8 * 8 * 2 = 128 bytes
  buffers.depth_address = 0x1000 + 128;  // 8 * 8 * 4 = 256 bytes
  EXPECT_EQ(Stripe::error(buffers, &memory), nullptr);
  buffers.depth_address = 0x1000 + 1024 - 255;
  EXPECT_EQ(std::string(Stripe::error(buffers, &memory)), "depth_address: the depth buffer does not fit the memory");
  buffers.color_address = 0xfff;
  EXPECT_EQ(std::string(Stripe::error(buffers, &memory)), "color_address: the colour buffer does not fit the memory");
  buffers.width = 513;
  EXPECT_EQ(std::string(Stripe::error(buffers)), "width: must be in 1 .. 512");
  buffers.width = 8;
  buffers.rows = 0;
  EXPECT_NE(Stripe::error(buffers), nullptr);
  EXPECT_THROW(memory.load(0x1000 + 1020, 4, 2), std::out_of_range);
}

}  // namespace
}  // namespace tessera::cluster
