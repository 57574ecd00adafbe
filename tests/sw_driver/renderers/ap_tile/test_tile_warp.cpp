// ap.tile.texture_warp's plain C++ part (tile_warp.h): the plane of a
// textured triangle against a projective map the test makes, the plan's
// refusals, and warps on the host resampler whose results follow from the
// map alone: under the identity the box of width 1 copies the texels, under
// a uniform 2:1 minification it averages pairs, a magnifying plane is
// upscaled first.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "renderers/ap_tile/tile_warp.h"

namespace tessera::ap_tile {
namespace {

constexpr int FRAME_W = 96, FRAME_H = 64;

// A 3 x 3 map (x w, y w, w) = m (u, v, 1) and a texture of `size` texels.
struct Map {
  std::array<float, 9> m;
  gl::ScreenVertex vertex(float u, float v, float size) const {
    gl::ScreenVertex out{};
    const float w = m[6] * u + m[7] * v + m[8];
    out.x_window = (m[0] * u + m[1] * v + m[2]) / w;
    out.y_window = (m[3] * u + m[4] * v + m[5]) / w;
    out.x = static_cast<int32_t>(std::lround(out.x_window * 16.0f));
    out.y = static_cast<int32_t>(std::lround(out.y_window * 16.0f));
    out.inv_w = 1.0f / w;
    out.tex[0].s = u / size;
    out.tex[0].t = v / size;
    return out;
  }
  gl::Triangle triangle(std::array<std::array<float, 2>, 3> uv, float size) const {
    gl::Triangle t{};
    for (int k = 0; k < 3; ++k) t.v[k] = vertex(uv[k][0], uv[k][1], size);
    return t;
  }
};

gl::Texture texture(unsigned size) {
  gl::Texture tex;
  tex.width = tex.height = size;
  tex.wrap_s = tex.wrap_t = gl::TexWrap::repeat;
  return tex;
}

// Texel (i, j) of a test texture: distinct values in each channel.
void texel_of(int i, int j, uint8_t out[4]) {
  out[0] = static_cast<uint8_t>((i * 37 + j * 11) & 0xff);
  out[1] = static_cast<uint8_t>((i * 5 + j * 71 + 40) & 0xff);
  out[2] = static_cast<uint8_t>(((i ^ j) * 13) & 0xff);
  out[3] = 255;
}

TEST(TexturePlane, RecoversTheMapItsVerticesCameFrom) {
  const Map map{{40.0f, 6.0f, 120.0f, -3.0f, 25.0f, 90.0f, 0.01f, 0.02f, 1.5f}};
  const gl::Triangle t = map.triangle({{{0, 0}, {30, 2}, {5, 28}}}, 32.0f);
  const std::optional<TexturePlane> plane = texture_plane(t, texture(32));
  ASSERT_TRUE(plane.has_value());
  for (float u : {-4.0f, 3.5f, 17.0f, 40.0f})
    for (float v : {-2.0f, 9.0f, 31.0f}) {
      const float w = map.m[6] * u + map.m[7] * v + map.m[8];
      float x = 0, y = 0;
      ASSERT_TRUE(plane->map(u, v, x, y));
      EXPECT_NEAR(x, (map.m[0] * u + map.m[1] * v + map.m[2]) / w, 0.25f) << u << ", " << v;
      EXPECT_NEAR(y, (map.m[3] * u + map.m[4] * v + map.m[5]) / w, 0.25f) << u << ", " << v;
    }
  // The quad's other half lies on it; a triangle of another map does not.
  EXPECT_TRUE(on_plane(*plane, map.triangle({{{0, 0}, {5, 28}, {30, 30}}}, 32.0f), texture(32)));
  Map other = map;
  other.m[2] += 3.0f;
  EXPECT_FALSE(on_plane(*plane, other.triangle({{{0, 0}, {5, 28}, {30, 30}}}, 32.0f), texture(32)));
}

TEST(TexturePlane, CollinearTextureCoordinatesHaveNone) {
  const Map map{{1, 0, 0, 0, 1, 0, 0, 0, 1}};
  gl::Triangle t = map.triangle({{{0, 0}, {4, 4}, {9, 2}}}, 16.0f);
  for (int k = 0; k < 3; ++k) t.v[k].tex[0] = {static_cast<float>(k) / 16.0f, static_cast<float>(k) / 16.0f};
  EXPECT_FALSE(texture_plane(t, texture(16)).has_value());
}

TEST(WarpPlan, TwoPlanesUnderOneTextureAreRefused) {
  const Map a{{1, 0, 10, 0, 1, 10, 0, 0, 1}}, b{{1, 0, 50, 0, 1, 10, 0, 0, 1}};
  WarpPlan plan;
  plan.add(1, a.triangle({{{0, 0}, {16, 0}, {16, 16}}}, 16.0f), texture(16));
  plan.add(1, a.triangle({{{0, 0}, {16, 16}, {0, 16}}}, 16.0f), texture(16));
  EXPECT_TRUE(plan.warped(1));
  plan.add(2, a.triangle({{{0, 0}, {16, 0}, {16, 16}}}, 16.0f), texture(16));
  plan.add(2, b.triangle({{{0, 0}, {16, 16}, {0, 16}}}, 16.0f), texture(16));
  EXPECT_FALSE(plan.warped(2));
  EXPECT_EQ(plan.reason(2), "its triangles do not share one texture plane");
  EXPECT_FALSE(plan.warped(3));
}

// Warps the texture `plan` recorded for texture 1 on the host.
std::string warp(WarpPlan& plan, const gl::Texture& tex, WarpedTexture& out, WarpJob& job) {
  std::string error = plan.job(1, tex, FRAME_W, FRAME_H, 512, job);
  if (!error.empty()) return error;
  uint64_t texels = 0;
  const WarpJob::TexelSource source = [&](int level, int i, int j, uint8_t texel[4]) {
    if (level > 0) return false;
    texel_of(wrap_texel(i, static_cast<int>(tex.width), tex.wrap_s),
             wrap_texel(j, static_cast<int>(tex.height), tex.wrap_t), texel);
    return true;
  };
  return job.run(source, nullptr, out, texels);
}

TEST(WarpJob, TheIdentityCopiesTheTexelsWithTheBoxOfWidthOne) {
  const Map map{{1, 0, 20, 0, 1, 8, 0, 0, 1}};  // x = u + 20, y = v + 8
  WarpPlan plan;
  plan.add(1, map.triangle({{{0, 0}, {32, 0}, {32, 32}}}, 32.0f), texture(32));
  plan.add(1, map.triangle({{{0, 0}, {32, 32}, {0, 32}}}, 32.0f), texture(32));
  WarpJob job(warp_filter(1));
  WarpedTexture out;
  ASSERT_EQ(warp(plan, texture(32), out, job), "");
  EXPECT_EQ(out.region.upscale, 1);
  for (int v = 0; v < 32; ++v)
    for (int u = 0; u < 32; ++u) {
      uint8_t expected[4], got[4];
      texel_of(u, v, expected);
      out.texel(u + 20, v + 8, got);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(got[c], expected[c]) << "texel " << u << ", " << v << " channel " << c;
    }
}

TEST(WarpJob, HalvingAveragesPairsWithTheBoxOfWidthOne) {
  const Map map{{0.5f, 0, 10, 0, 0.5f, 4, 0, 0, 1}};  // x = u / 2 + 10, y = v / 2 + 4
  WarpPlan plan;
  plan.add(1, map.triangle({{{0, 0}, {64, 0}, {64, 64}}}, 64.0f), texture(64));
  WarpJob job(warp_filter(1));
  WarpedTexture out;
  ASSERT_EQ(warp(plan, texture(64), out, job), "");
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      uint8_t got[4], t[4][4];
      texel_of(2 * x, 2 * y, t[0]);
      texel_of(2 * x + 1, 2 * y, t[1]);
      texel_of(2 * x, 2 * y + 1, t[2]);
      texel_of(2 * x + 1, 2 * y + 1, t[3]);
      out.texel(x + 10, y + 4, got);
      for (int c = 0; c < 3; ++c) {
        const double mean = (t[0][c] + t[1][c] + t[2][c] + t[3][c]) / 4.0;
        // Two passes, each rounding to q8_8, and the final unorm8 rounding.
        ASSERT_NEAR(got[c], mean, 1.0) << "pixel " << x << ", " << y << " channel " << c;
      }
    }
}

TEST(WarpJob, AMagnifyingPlaneIsUpscaledUntilNoTexelCoversMoreThanAPixel) {
  const Map map{{2.5f, 0, 4, 0, 1.2f, 4, 0, 0, 1}};
  WarpPlan plan;
  plan.add(1, map.triangle({{{0, 0}, {16, 0}, {16, 16}}}, 16.0f), texture(16));
  WarpJob job(warp_filter(2));
  WarpedTexture out;
  ASSERT_EQ(warp(plan, texture(16), out, job), "");
  EXPECT_EQ(out.region.upscale, 4);
  // Inside the texel (3, 5): its colour, the box of two pixels within it.
  uint8_t expected[4], got[4];
  texel_of(3, 5, expected);
  out.texel(static_cast<int>(4 + 2.5f * 3.5f), static_cast<int>(4 + 1.2f * 5.5f), got);
  EXPECT_NEAR(got[0], expected[0], 1);
}

// 640 texels along u (644 with the margins) do not fit the program's 512 at
// the base level: the region is cut into bands at level 3, whose texels
// (the means of 8 x 8 base texels) cover a pixel each; the pixel is that
// mean.
TEST(WarpJob, ALongRegionIsWarpedInBandsAtTheLevelOfItsScale) {
  const Map map{{0.125f, 0, 4, 0, 0.125f, 4, 0, 0, 1}};
  WarpPlan plan;
  plan.add(1, map.triangle({{{0, 0}, {640, 0}, {640, 64}}}, 64.0f), texture(64));
  WarpJob job(warp_filter(1));
  WarpedTexture out;
  ASSERT_EQ(warp(plan, texture(64), out, job), "");
  ASSERT_GE(job.bands().size(), 1u);
  EXPECT_EQ(out.region.bands, static_cast<int>(job.bands().size()));
  for (const WarpBand& band : job.bands()) EXPECT_EQ(band.level, 3);
  for (int y = 1; y < 7; ++y)
    for (int x = 1; x < 79; ++x) {
      unsigned sum[3] = {};
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
          uint8_t t[4];
          texel_of((8 * x + i) % 64, (8 * y + j) % 64, t);
          for (int c = 0; c < 3; ++c) sum[c] += t[c];
        }
      uint8_t got[4];
      out.texel(x + 4, y + 4, got);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], sum[c] / 64.0, 1.5) << "pixel " << x << ", " << y;
    }
}

TEST(WarpJob, ARegionBeyondTheProgramsLinesAtEveryLevelIsRefusedNamingIt) {
  // A 4 x 4 texture has levels 0 .. 2: at most 512 x 4 base texels a line.
  const Map map{{0.01f, 0, 4, 0, 0.01f, 4, 0, 0, 1}};
  WarpPlan plan;
  plan.add(1, map.triangle({{{0, 0}, {3000, 0}, {3000, 40}}}, 4.0f), texture(4));
  WarpJob job(warp_filter(1));
  WarpedTexture out;
  const std::string error = warp(plan, texture(4), out, job);
  EXPECT_NE(error.find("3000 x 40 texels, beyond the array program's 512 texels a line at every level"),
            std::string::npos)
      << error;
  EXPECT_FALSE(plan.warped(1));
}

TEST(WarpJob, APlaneBehindTheEyeIsRefused) {
  // w = 1 - u / 8: zero at u = 8, inside the region.
  const Map map{{1, 0, 0, 0, 1, 0, -0.125f, 0, 1}};
  WarpPlan plan;
  plan.add(1, map.triangle({{{0, 0}, {6, 0}, {0, 6}}}, 16.0f), texture(16));
  WarpJob job(warp_filter(4));
  WarpedTexture out;
  EXPECT_EQ(warp(plan, texture(16), out, job), "its plane passes behind the eye within the texture region");
}

}  // namespace
}  // namespace tessera::ap_tile
