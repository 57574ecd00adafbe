// The texture sampler (tlm/raster/core/texture_sampler.h) on its own: a
// 4 x 4 RGBA8 texture in a plain memory, s/w, t/w and 1/w planes written
// by hand (1/w = 1, so s and t are the planes' values), the environment
// REPLACE (the fragment's colour is the filtered texel). Expected fetch
// addresses and filtered texels follow datapath/texel_address.h's header
// (GL 1.2 "Texturing"): u = s * 4; NEAREST takes floor(u); LINEAR
// floor(u - 1/2) and the next with the weight frac(u - 1/2) in 1/256;
// REPEAT reduces indices modulo 4, CLAMP_TO_EDGE clamps s to [1/8, 7/8]
// first; texel (i, j) at base + (4 j + i) * 4, row t = 0 first; the four
// texels of LINEAR in the order (i0,j0), (i1,j0), (i0,j1), (i1,j1).
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "raster/core/texture_sampler.h"
#include "raster_core_test_support.h"

using namespace tessera::raster;
using tessera::TexEnv;
using tessera::TexFilter;
using tessera::TexWrap;
using tessera::raster::test::StageRun;

namespace {

constexpr uint32_t TEX = 0x1000;
constexpr int64_t ONE = int64_t{1} << 24;  // 1.0 in the texture planes' q15.24 words

uint32_t texel_address(unsigned i, unsigned j) {
  return TEX + (4 * j + i) * 4;
}
// Texel (i, j): R = 20 i + 60 j, G = i, B = j, A = 255 but texel (2, 1)'s 0.
uint32_t texel(unsigned i, unsigned j) {
  const uint32_t a = i == 2 && j == 1 ? 0 : 255;
  return (20 * i + 60 * j) | i << 8 | j << 16 | a << 24;
}

struct SamplerBench : StageRun {
  explicit SamplerBench(TexWrap wrap, TexFilter min = TexFilter::nearest, TexFilter mag = TexFilter::nearest)
      : StageRun(0x2000, RunConfig{}), scratch(new TextureScratch) {
    for (unsigned j = 0; j < 4; ++j)
      for (unsigned i = 0; i < 4; ++i) port.set_word(texel_address(i, j), texel(i, j));
    state.flags |= StateFlag::texture;
    state.texture.base = TEX;
    state.texture.log2_width = state.texture.log2_height = 2;
    state.texture.wrap_s = state.texture.wrap_t = wrap;
    state.min_filter = min;
    state.mag_filter = mag;
    state.env = TexEnv::replace;
    setup.q = attribute_plane_from_raw(AttributeKind::texcoord, ONE, 0, 0);
  }
  // s = s0 + ds dx along x, t = t0 everywhere (in units of 1/16).
  void coordinates(int s0_16ths, int ds_16ths, int t0_16ths) {
    setup.s = attribute_plane_from_raw(AttributeKind::texcoord, s0_16ths * ONE / 16, ds_16ths * ONE / 16, 0);
    setup.t = attribute_plane_from_raw(AttributeKind::texcoord, t0_16ths * ONE / 16, 0, 0);
  }
  // Samples fragments dx = first .. first + count - 1 of row 0.
  unsigned sample(int first, unsigned count) {
    dx.resize(count);
    dy.assign(count, 0);
    rgba.assign(count, 0x12345678);  // the fragments' colours, replaced
    for (unsigned i = 0; i < count; ++i) dx[i] = first + int(i);
    TextureSampler sampler(run, state, *scratch);
    return sampler.sample(setup, dx.data(), dy.data(), count, rgba.data());
  }

  DrawState state;
  TriangleSetup setup;
  std::unique_ptr<TextureScratch> scratch;
  std::vector<int32_t> dx, dy;
  std::vector<uint32_t> rgba;
};

TEST(TextureSampler, NearestRepeatWrapsIndicesModuloTheSize) {
  SamplerBench b(TexWrap::repeat);
  // s = (2 + 4 dx) / 16 for dx = -1 .. 4: -1/8, 1/8, 3/8, 5/8, 7/8, 9/8;
  // u = -0.5, 0.5, 1.5, 2.5, 3.5, 4.5: i = -1 mod 4 = 3, 0, 1, 2, 3, 4 mod 4 = 0.
  // t = 6/16: v = 1.5, j = 1.
  b.coordinates(2, 4, 6);
  ASSERT_EQ(b.sample(-1, 6), 6u);
  const std::vector<unsigned> i = {3, 0, 1, 2, 3, 0};
  std::vector<uint32_t> addresses, texels;
  for (unsigned k : i) {
    addresses.push_back(texel_address(k, 1));
    texels.push_back(texel(k, 1));
  }
  EXPECT_EQ(b.port.reads, addresses);
  EXPECT_EQ(b.rgba, texels);  // REPLACE
  EXPECT_EQ(b.run.result().texels, 6u);
  EXPECT_EQ(b.run.result().texel_cycles, 6u * b.costs.texel);
}

TEST(TextureSampler, NearestClampToEdgeKeepsTheEdgeTexels) {
  SamplerBench b(TexWrap::clamp_to_edge);
  // As above; -1/8 clamps to 1/8 (i = 0), 9/8 to 7/8 (i = 3). t = 22/16
  // clamps to 7/8: j = 3.
  b.coordinates(2, 4, 22);
  ASSERT_EQ(b.sample(-1, 6), 6u);
  std::vector<uint32_t> addresses;
  for (unsigned k : {0u, 0u, 1u, 2u, 3u, 3u}) addresses.push_back(texel_address(k, 3));
  EXPECT_EQ(b.port.reads, addresses);
}

TEST(TextureSampler, LinearFetchesFourTexelsAndWeighsThem) {
  SamplerBench b(TexWrap::repeat, TexFilter::linear, TexFilter::linear);
  // s = 7/16: u = 1.75, u - 1/2 = 1.25: i0 = 1, i1 = 2, weight 64.
  // t = 5/16: v = 1.25, v - 1/2 = 0.75: j0 = 0, j1 = 1, weight 192.
  b.coordinates(7, 0, 5);
  ASSERT_EQ(b.sample(0, 1), 1u);
  EXPECT_EQ(b.port.reads, (std::vector<uint32_t>{texel_address(1, 0), texel_address(2, 0), texel_address(1, 1),
                                                 texel_address(2, 1)}));
  EXPECT_EQ(b.run.result().texels, 4u);
  // Weights (3/4)(1/4), (1/4)(1/4), (3/4)(3/4), (1/4)(3/4) = 3/16, 1/16,
  // 9/16, 3/16. R: 20, 40, 80, 100 -> 3.75 + 2.5 + 45 + 18.75 = 70.
  // G (i): 1, 2, 1, 2 -> 1.25 -> 1. B (j): 0, 0, 1, 1 -> 0.75 -> 1.
  // A: 255 but (2, 1)'s 0 -> 255 (1 - 3/16) = 207.19 -> 207.
  EXPECT_EQ(b.rgba[0], 70u | 1u << 8 | 1u << 16 | 207u << 24);
}

TEST(TextureSampler, LinearAtTheCornerWrapsOrClamps) {
  {
    // s = t = 0: u - 1/2 = -1/2: i0 = -1 -> 3, i1 = 0 (the same for j).
    SamplerBench b(TexWrap::repeat, TexFilter::linear, TexFilter::linear);
    b.coordinates(0, 0, 0);
    b.sample(0, 1);
    EXPECT_EQ(b.port.reads, (std::vector<uint32_t>{texel_address(3, 3), texel_address(0, 3), texel_address(3, 0),
                                                   texel_address(0, 0)}));
  }
  {
    // Clamped to s = t = 1/8: u - 1/2 = 0: i0 = 0, i1 = 1, weight 0.
    SamplerBench b(TexWrap::clamp_to_edge, TexFilter::linear, TexFilter::linear);
    b.coordinates(0, 0, 0);
    b.sample(0, 1);
    EXPECT_EQ(b.port.reads, (std::vector<uint32_t>{texel_address(0, 0), texel_address(1, 0), texel_address(0, 1),
                                                   texel_address(1, 1)}));
    EXPECT_EQ(b.rgba[0], texel(0, 0));  // weight 0: the first texel alone
  }
}

TEST(TextureSampler, MinificationFilterOnlyBeyondOneTexelAPixel) {
  // MIN LINEAR, MAG NEAREST: rho > 1 minifies (README.md, "Per-fragment
  // operations"). s rising 4/16 a pixel is one texel a pixel (rho = 1): the
  // magnification filter, one fetch; 8/16 a pixel is two (rho = 2): four.
  {
    SamplerBench b(TexWrap::repeat, TexFilter::linear, TexFilter::nearest);
    b.coordinates(2, 4, 6);
    b.sample(0, 2);
    EXPECT_EQ(b.run.result().texels, 2u);
  }
  {
    SamplerBench b(TexWrap::repeat, TexFilter::linear, TexFilter::nearest);
    b.coordinates(2, 8, 6);
    b.sample(0, 2);
    EXPECT_EQ(b.run.result().texels, 8u);
  }
}

TEST(TextureSampler, FallingCoordinatesMinifyAsRisingOnesDo) {
  // rho is the footprint's length: s falling 4/16 a pixel keeps the
  // magnification filter, 8/16 a pixel minifies (a texture mapped mirrored;
  // the fuzzer's case: the difference of two coordinates is negative).
  {
    SamplerBench b(TexWrap::repeat, TexFilter::linear, TexFilter::nearest);
    b.coordinates(30, -4, 6);
    b.sample(0, 2);
    EXPECT_EQ(b.run.result().texels, 2u);
  }
  {
    SamplerBench b(TexWrap::repeat, TexFilter::linear, TexFilter::nearest);
    b.coordinates(30, -8, 6);
    b.sample(0, 2);
    EXPECT_EQ(b.run.result().texels, 8u);
  }
}

TEST(TextureSampler, ARefusedTexelStopsAtItsFragmentWithBadTexture) {
  SamplerBench b(TexWrap::repeat);
  b.coordinates(2, 4, 6);  // fragments 0..3 fetch texels (0..3, 1)
  b.port.fail_begin = texel_address(2, 1);
  b.port.fail_end = b.port.fail_begin + 4;
  EXPECT_EQ(b.sample(0, 4), 2u);
  EXPECT_EQ(b.run.result().error, RasterError::bad_texture);
  EXPECT_EQ(b.run.result().error_address, texel_address(2, 1));
  EXPECT_EQ(b.run.result().texels, 2u);
  EXPECT_EQ(b.rgba[0], texel(0, 1));  // the fragments before it are done
  EXPECT_EQ(b.rgba[1], texel(1, 1));
}

}  // namespace
