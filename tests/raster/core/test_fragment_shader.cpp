// The fragment shader (tlm/raster/core/fragment_shader.h) on its own: a
// batch of four fragments on row 0 of an 8 x 8 tile, planes written by
// hand, the tile cache's depth, stencil and colour set beforehand, and
// what shade() leaves in the tile checked against GL's per-fragment order
// (README.md, "Per-fragment operations" and "Batches"): the tests against
// the tile's stored values, then blending and the colour into the tile,
// with depth and stencil written back where the tests say.
#include <gtest/gtest.h>

#include <memory>

#include "raster/core/fragment_shader.h"
#include "raster_core_test_support.h"

using namespace tessera::raster;
using tessera::CompareFunc;
using tessera::PixelFormat;
using tessera::StencilOp;
using tessera::raster::test::StageRun;

namespace {

constexpr int64_t COLOR_ONE = int64_t{1} << 16;

struct ShaderBench : StageRun {
  explicit ShaderBench(PixelFormat format = PixelFormat::rgba8888)
      : StageRun(0x100, tile_config(format)), cache(config), work(new ShadingWorkspace) {
    cache.select(0, 0);
    setup.flat = true;
    setup.flat_color = Rgba8::unpack(0xff00ff00);
    depth_everywhere(0x400000);
  }
  static RunConfig tile_config(PixelFormat format) {
    RunConfig c;
    c.width = c.height = c.tile_width = c.tile_height = 8;
    c.color_format = format;
    return c;
  }
  void depth_everywhere(uint32_t z) {
    setup.depth = attribute_plane_from_raw(AttributeKind::depth, int64_t{z} << 8, 0, 0);
  }
  // Shades pixels (0, 0) .. (3, 0), the planes starting at (0, 0).
  unsigned shade() {
    work->batch.reset(0, 0);
    work->batch.add_run(0, 0, 4, nullptr);
    FragmentShader shader(run, cache, state, *work);
    return shader.shade(setup, work->batch);
  }
  unsigned at(int x) const { return cache.index(x, 0); }

  TileCache cache;
  DrawState state;
  TriangleSetup setup;
  std::unique_ptr<ShadingWorkspace> work;
};

TEST(FragmentShader, DepthTestAgainstTheTileWritesThePassingFragmentsOnly) {
  ShaderBench b;
  b.state.operations.depth_test = true;  // LESS, depth writes on
  const uint32_t stored[4] = {0x300000, 0x500000, 0x400000, 0xffffff};
  for (int x = 0; x < 4; ++x) {
    b.cache.depth(b.at(x)) = stored[x];
    b.cache.color(b.at(x)) = 0x11111111;
  }
  ASSERT_EQ(b.shade(), 4u);
  // 0x400000 < stored: fragments 1 and 3 (equal is not less).
  for (int x = 0; x < 4; ++x) {
    const bool pass = x == 1 || x == 3;
    EXPECT_EQ(b.cache.color(b.at(x)), pass ? 0xff00ff00u : 0x11111111u) << x;
    EXPECT_EQ(b.cache.depth(b.at(x)), pass ? 0x400000u : stored[x]) << x;
  }
  EXPECT_EQ(b.run.result().fragments_written, 2u);
}

TEST(FragmentShader, StencilIsWrittenBackForEveryFragmentThatReachedTheTest) {
  ShaderBench b;
  b.state.operations.stencil_test = true;
  b.state.operations.stencil_func = CompareFunc::equal;
  b.state.operations.stencil_ref = 0;
  b.state.operations.stencil_fail = StencilOp::replace;  // the reference, 0
  b.state.operations.depth_pass = StencilOp::incr;
  const uint8_t stored[4] = {0, 7, 0, 9};
  for (int x = 0; x < 4; ++x) b.cache.stencil(b.at(x)) = stored[x];
  b.shade();
  // Equal to 0 passes and increments; the others fail and are replaced by 0.
  EXPECT_EQ(b.cache.stencil(b.at(0)), 1);
  EXPECT_EQ(b.cache.stencil(b.at(1)), 0);
  EXPECT_EQ(b.cache.stencil(b.at(2)), 1);
  EXPECT_EQ(b.cache.stencil(b.at(3)), 0);
  EXPECT_EQ(b.run.result().fragments_written, 2u);
  // Without the depth test the tile's depth is left alone (README.md,
  // "Per-fragment operations"; datapath/fragment_tests.h).
  EXPECT_EQ(b.cache.depth(b.at(0)), 0u);
}

TEST(FragmentShader, AlphaTestReadsTheInterpolatedColour) {
  ShaderBench b;
  // Gouraud: alpha 90 + 10 dx: 90, 100, 110, 120 on the four fragments.
  b.setup.flat = false;
  b.setup.color[0] = attribute_plane_from_raw(AttributeKind::color, 7 * COLOR_ONE, 0, 0);
  b.setup.color[1] = attribute_plane_from_raw(AttributeKind::color, 0, 0, 0);
  b.setup.color[2] = attribute_plane_from_raw(AttributeKind::color, 0, 0, 0);
  b.setup.color[3] = attribute_plane_from_raw(AttributeKind::color, 90 * COLOR_ONE, 10 * COLOR_ONE, 0);
  b.state.operations.alpha_test = true;
  b.state.operations.alpha_func = CompareFunc::greater;
  b.state.operations.alpha_ref = 100;
  b.shade();
  EXPECT_EQ(b.cache.color(b.at(0)), 0u);
  EXPECT_EQ(b.cache.color(b.at(1)), 0u);  // 100 is not greater than 100
  EXPECT_EQ(b.cache.color(b.at(2)), 7u | 110u << 24);
  EXPECT_EQ(b.cache.color(b.at(3)), 7u | 120u << 24);
}

TEST(FragmentShader, Rgb565TileKeepsWhatA565BufferWould) {
  ShaderBench b(PixelFormat::rgb565);
  // R 255 -> 31 -> 255; G 128 -> round(128 * 63 / 255) = 32 -> (32 << 2) |
  // (32 >> 4) = 130; B 0; alpha reads 255.
  b.setup.flat_color = Rgba8::unpack(0x000080ff);
  b.shade();
  EXPECT_EQ(b.cache.color(b.at(0)), 0xff0082ffu);
}

}  // namespace
