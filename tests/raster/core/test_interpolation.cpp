// Interpolation (tlm/raster/core/interpolation.h) on its own: planes
// written by hand, evaluated at offsets (dx, dy) from the reference pixel
// as plane.start + dx grad_x + dy grad_y, then the interpolator's output
// rule (README.md, "Triangle setup"; datapath/attribute_interpolator.h):
// round to nearest, ties towards +infinity, and clamp (colour words have
// 16 fraction bits, 0.8 out; depth words 8, 0.24 out). Perspective colours
// divide c/w by q (1/w, 24 fraction bits) per pixel (README.md, "Colour").
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "raster/core/interpolation.h"

using namespace tessera::raster;

namespace {

constexpr int64_t COLOR_ONE = int64_t{1} << 16;  // one colour code in colour words

AttributePlane color_plane(int64_t start, int64_t grad_x, int64_t grad_y) {
  return attribute_plane_from_raw(AttributeKind::color, start, grad_x, grad_y);
}

// The fragments at offsets dx[i], dy[i].
struct Fragments {
  std::vector<int32_t> dx, dy;
  unsigned count() const { return unsigned(dx.size()); }
};

std::vector<uint32_t> colors(const TriangleSetup& ts, const Fragments& f, RecipMethod method = RecipMethod::method3) {
  auto scratch = std::make_unique<InterpolationScratch>();
  std::vector<uint32_t> rgba(f.count());
  interpolated_colors(ts, f.dx.data(), f.dy.data(), f.count(), method, *scratch, rgba.data());
  return rgba;
}

TEST(Interpolation, FlatColourIsTheSameEverywhere) {
  TriangleSetup ts;
  ts.flat = true;
  ts.flat_color = Rgba8::unpack(0x80402010);
  ts.color[0] = color_plane(COLOR_ONE * 7, COLOR_ONE, COLOR_ONE);  // ignored when flat
  const Fragments f{{0, 5, -3}, {0, 2, 9}};
  EXPECT_EQ(colors(ts, f), (std::vector<uint32_t>{0x80402010, 0x80402010, 0x80402010}));
}

TEST(Interpolation, GouraudRoundsTiesUpAndClamps) {
  TriangleSetup ts;
  // R = 10.5 + 2 dx - 3 dy; G = 0; B = 100 - dx / 4; A = 255.
  ts.color[0] = color_plane(10 * COLOR_ONE + COLOR_ONE / 2, 2 * COLOR_ONE, -3 * COLOR_ONE);
  ts.color[1] = color_plane(0, 0, 0);
  ts.color[2] = color_plane(100 * COLOR_ONE, -COLOR_ONE / 4, 0);
  ts.color[3] = color_plane(255 * COLOR_ONE, 0, 0);
  const Fragments f{{0, 1, 0, -6, 150, 2}, {0, 0, 1, 0, 0, 0}};
  const std::vector<uint32_t> rgba = colors(ts, f);
  const auto r = [&](unsigned i) { return rgba[i] & 0xff; };
  const auto b = [&](unsigned i) { return (rgba[i] >> 16) & 0xff; };
  EXPECT_EQ(r(0), 11u);   // 10.5: the tie goes up
  EXPECT_EQ(r(1), 13u);   // 12.5
  EXPECT_EQ(r(2), 8u);    // 7.5
  EXPECT_EQ(r(3), 0u);    // -1.5 clamps to 0
  EXPECT_EQ(r(4), 255u);  // 310.5 clamps to 255
  EXPECT_EQ(b(0), 100u);
  EXPECT_EQ(b(5), 100u);  // 99.5: the tie goes up
  EXPECT_EQ(b(4), 63u);   // 100 - 37.5 = 62.5: up
  for (uint32_t c : rgba) {
    EXPECT_EQ((c >> 8) & 0xff, 0u);
    EXPECT_EQ(c >> 24, 255u);
  }
}

TEST(Interpolation, PerspectiveColourIsColourOverWOverOneOverW) {
  // Along x, q = 1/w goes 0.5, 1, 1.5, 2 (q15.24) and c/w 50, 60, 70, 80
  // (colour words): c = (c/w) / q = 100, 60, 46.67 -> 47, 40 -- not the
  // screen-linear 100, 60, 20, -20.
  TriangleSetup ts;
  ts.perspective_color = true;
  ts.q = attribute_plane_from_raw(AttributeKind::texcoord, int64_t{1} << 23, int64_t{1} << 23, 0);
  ts.color[0] = color_plane(50 * COLOR_ONE, 10 * COLOR_ONE, 0);
  // G: c/w = 255 q everywhere, so c = 255.
  ts.color[1] = color_plane(255 * COLOR_ONE / 2, 255 * COLOR_ONE / 2, 0);
  ts.color[2] = color_plane(0, 0, 0);
  ts.color[3] = color_plane(0, 0, 0);
  const Fragments f{{0, 1, 2, 3}, {0, 0, 0, 0}};
  // The batch kernel (Method 3's seed) and the scalar path (Method 1's).
  for (RecipMethod method : {RecipMethod::method3, RecipMethod::method1}) {
    const std::vector<uint32_t> rgba = colors(ts, f, method);
    EXPECT_EQ(rgba, (std::vector<uint32_t>{100 | 255u << 8, 60 | 255u << 8, 47 | 255u << 8, 40 | 255u << 8}));
  }
}

TEST(Interpolation, DepthRoundsAndClampsToTwentyFourBits) {
  TriangleSetup ts;
  // Depth words have 8 fraction bits: 0x123456.5 + dx - 0x200000 dy.
  ts.depth = attribute_plane_from_raw(AttributeKind::depth, (int64_t{0x123456} << 8) + 0x80, 1 << 8,
                                      -(int64_t{0x200000} << 8));
  const Fragments f{{0, 3, 0, 0}, {0, 0, 1, -8}};
  auto scratch = std::make_unique<InterpolationScratch>();
  std::vector<uint32_t> depth(f.count());
  interpolated_depths(ts, f.dx.data(), f.dy.data(), f.count(), *scratch, depth.data());
  EXPECT_EQ(depth[0], 0x123457u);  // .5 up
  EXPECT_EQ(depth[1], 0x12345au);  // 0x123459.5 up
  EXPECT_EQ(depth[2], 0u);         // 0x123456.5 - 0x200000 < 0: clamped
  EXPECT_EQ(depth[3], 0xffffffu);  // 0x123456.5 + 0x1000000: clamped
}

TEST(Interpolation, FogArgumentIsThePlaneWithoutPerspective) {
  TriangleSetup ts;
  // 16.16 words: 1.0 + 0.5 dx - 2 dy.
  ts.fog = attribute_plane_from_raw(AttributeKind::texcoord, 0x10000, 0x8000, -0x20000);
  const Fragments f{{0, 2, 0}, {0, 0, 1}};
  auto scratch = std::make_unique<InterpolationScratch>();
  std::vector<int32_t> fog(f.count());
  interpolated_fogs(ts, f.dx.data(), f.dy.data(), f.count(), RecipMethod::method3, *scratch, fog.data());
  EXPECT_EQ(fog, (std::vector<int32_t>{0x10000, 0x20000, -0x10000}));
}

}  // namespace
