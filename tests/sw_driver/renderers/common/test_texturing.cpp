// Unit tests of the texture sampling the back ends share
// (renderers/common/texturing.h): the level of detail of OpenGL ES 1.1
// section 3.8.8, the level and filter choice of sections 3.8.8-3.8.9 with
// the switch point c, the blend of two levels, and the components a base
// format lacks (table 3.15). Expected values are worked out by hand from
// the specification's formulas; lambda is 16.16 fixed point, as the back
// ends compute it on the ARM922T.
#include <gtest/gtest.h>

#include <cmath>

#include "renderers/common/texturing.h"

using namespace tessera;
using renderers::LOD_MAGNIFIED;
using renderers::LOD_ONE;
using renderers::LodChoice;

namespace {

// lambda in 16.16, as the back ends compute it.
int32_t q16(double lambda) {
  return int32_t(std::lround(lambda * 65536));
}
LodChoice choose_levels(const gl::Texture& tex, double lambda) {
  return renderers::choose_levels_q16(tex, q16(lambda));
}

// An 8 x 8 texture with its four levels (8, 4, 2, 1) and the given filters.
gl::Texture mipmapped(gl::TexFilter within, gl::MipmapFilter mipmap, gl::TexFilter mag) {
  gl::Texture t;
  t.width = t.height = 8;
  t.min_filter = within;
  t.min_mipmap = mipmap;
  t.mag_filter = mag;
  t.levels = 4;
  for (unsigned k = 0; k < 4; ++k) t.level[k] = {0x1000u * (k + 1), 8u >> k, 8u >> k};
  t.address = t.level[0].address;
  return t;
}

}  // namespace

TEST(TextureLod, IsLog2OfTheLargerScaleFactor) {
  using renderers::texture_lod_q16;
  // rho = max(fx, fy), fx = max(|ux|, |vx|): equation 3.17's lower bound.
  EXPECT_EQ(texture_lod_q16(2, 0, 0, 2, 0), 1 * LOD_ONE);
  EXPECT_EQ(texture_lod_q16(1, 0, 0, 4, 0), 2 * LOD_ONE);      // the larger of the two directions
  EXPECT_EQ(texture_lod_q16(8, 0, 0, 1, 0), 3 * LOD_ONE);      // of the magnitudes
  EXPECT_EQ(texture_lod_q16(1, 0, 0, 1, -LOD_ONE), -LOD_ONE);  // magnified two times: 0.5 in units of 2^-1
  EXPECT_EQ(texture_lod_q16(0, 0, 0, 0, 0), LOD_MAGNIFIED);    // a texture that does not move
  // Within the bounds the specification allows for fx:
  // max(|ux|, |vx|) <= fx <= |ux| + |vx|, and at most the exact sqrt form.
  const double ux = 3, vx = 4;
  const double fx = std::exp2(texture_lod_q16(3, 4, 0, 0, 0) / 65536.0);
  EXPECT_GE(fx, std::max(ux, vx));
  EXPECT_LE(fx, ux + vx);
  EXPECT_LE(fx, std::sqrt(ux * ux + vx * vx));
  // log2 of a magnitude that is not a power of two, within 1.2 units of 2^-16.
  EXPECT_NEAR(texture_lod_q16(3, 0, 0, 0, 0), std::log2(3.0) * 65536, 1.2);
}

TEST(TextureLod, LinearMipmapLinearBlendsTheTwoNearestLevels) {
  const gl::Texture t = mipmapped(gl::TexFilter::linear, gl::MipmapFilter::linear, gl::TexFilter::linear);
  LodChoice c = choose_levels(t, 1.25);
  EXPECT_EQ(c.count, 2u);
  EXPECT_EQ(c.level[0], 1u);
  EXPECT_EQ(c.level[1], 2u);
  EXPECT_EQ(c.blend, 64u);  // 0.25 * 256
  EXPECT_TRUE(c.linear);
  c = choose_levels(t, 3.5);  // beyond the last level q = 3: level q alone
  EXPECT_EQ(c.count, 1u);
  EXPECT_EQ(c.level[0], 3u);
  c = choose_levels(t, 2.0);  // frac 0: level 2 alone
  EXPECT_EQ(c.count, 1u);
  EXPECT_EQ(c.level[0], 2u);
  c = choose_levels(t, -0.5);  // magnified: level 0 with the magnification filter
  EXPECT_EQ(c.count, 1u);
  EXPECT_EQ(c.level[0], 0u);
}

TEST(TextureLod, NearestMipmapTakesCeilOfLambdaPlusHalfMinusOne) {
  const gl::Texture t = mipmapped(gl::TexFilter::nearest, gl::MipmapFilter::nearest, gl::TexFilter::nearest);
  EXPECT_EQ(choose_levels(t, 0.25).level[0], 0u);
  EXPECT_EQ(choose_levels(t, 0.5).level[0], 0u);
  EXPECT_EQ(choose_levels(t, 0.51).level[0], 1u);
  EXPECT_EQ(choose_levels(t, 1.5).level[0], 1u);  // ceil(2) - 1
  EXPECT_EQ(choose_levels(t, 1.51).level[0], 2u);
  EXPECT_EQ(choose_levels(t, 9.0).level[0], 3u);  // at most q
  EXPECT_FALSE(choose_levels(t, 1.0).linear);
}

TEST(TextureLod, SwitchPointIsHalfForLinearMagnificationWithNearestMipmaps) {
  // c = 0.5: lambda 0.3 is still magnified, with the LINEAR magnification filter.
  gl::Texture t = mipmapped(gl::TexFilter::nearest, gl::MipmapFilter::nearest, gl::TexFilter::linear);
  EXPECT_EQ(renderers::lod_switch_point(t), LOD_ONE / 2);
  EXPECT_TRUE(choose_levels(t, 0.3).linear);
  EXPECT_FALSE(choose_levels(t, 0.6).linear);
  // c = 0 otherwise: lambda 0.3 is minified, NEAREST within level 0.
  t.mag_filter = gl::TexFilter::nearest;
  EXPECT_EQ(renderers::lod_switch_point(t), 0);
  t.mag_filter = gl::TexFilter::linear;
  t.min_filter = gl::TexFilter::linear;  // LINEAR_MIPMAP_NEAREST: c = 0
  EXPECT_EQ(renderers::lod_switch_point(t), 0);
  gl::Texture plain;  // GL_NEAREST minification, GL_LINEAR magnification, no mipmaps
  plain.min_filter = gl::TexFilter::nearest;
  EXPECT_TRUE(choose_levels(plain, 0.0).linear);      // lambda <= 0: magnified
  EXPECT_FALSE(choose_levels(plain, 0.01).linear);    // minified
  EXPECT_EQ(choose_levels(plain, 5.0).level[0], 0u);  // no mipmaps: level 0
}

TEST(TextureLod, LodIsSkippedWhereItChangesNothing) {
  gl::Texture t;
  t.min_filter = t.mag_filter = gl::TexFilter::linear;
  EXPECT_FALSE(renderers::texture_needs_lod(t));
  t.min_filter = gl::TexFilter::nearest;
  EXPECT_TRUE(renderers::texture_needs_lod(t));
  t.min_filter = gl::TexFilter::linear;
  t.min_mipmap = gl::MipmapFilter::nearest;
  EXPECT_TRUE(renderers::texture_needs_lod(t));
}

TEST(TextureLod, SamplesEachLevelAtItsScaleAndBlendsWithEightBitWeights) {
  const gl::Texture t = mipmapped(gl::TexFilter::nearest, gl::MipmapFilter::linear, gl::TexFilter::nearest);
  int seen_u[2] = {}, seen_v[2] = {};
  unsigned calls = 0;
  // Level 1 is black, level 2 white.
  auto filter = [&](unsigned level, int u8, int v8, bool, uint8_t out[4]) {
    seen_u[calls] = u8;
    seen_v[calls] = v8;
    ++calls;
    for (int ch = 0; ch < 4; ++ch) out[ch] = level == 1 ? 0 : 255;
  };
  uint8_t out[4];
  const LodChoice c = renderers::sample_texture_lod_q16(t, 0x300, 0x140, q16(1.25), filter, out);
  EXPECT_EQ(c.count, 2u);
  EXPECT_EQ(seen_u[0], 0x180);  // 3.0 texels of level 0 are 1.5 of level 1
  EXPECT_EQ(seen_v[0], 0xa0);
  EXPECT_EQ(seen_u[1], 0xc0);  // and 0.75 of level 2
  EXPECT_EQ(out[0], 64);       // (0 * 192 + 255 * 64 + 128) >> 8 = 64
  EXPECT_EQ(renderers::texture_level(t, 0).address, t.address);
  EXPECT_EQ(renderers::texture_level(t, 2).width, 2u);
}

TEST(TextureEnv, MissingComponentsComeFromTheFragmentUnderReplaceAndModulate) {
  const uint32_t fragment = 10u | 20u << 8 | 30u << 16 | 40u << 24;
  gl::Texture alpha;
  alpha.has_color = false;  // GL_ALPHA: expanded to (0, 0, 0, a)
  uint8_t texel[4] = {0, 0, 0, 77};
  renderers::fill_missing_components(alpha, gl::TexEnv::replace, fragment, texel);
  EXPECT_EQ(renderers::apply_tex_env(gl::TexEnv::replace, fragment, texel), 10u | 20u << 8 | 30u << 16 | 77u << 24);
  uint8_t texel2[4] = {0, 0, 0, 255};
  renderers::fill_missing_components(alpha, gl::TexEnv::modulate, fragment, texel2);
  EXPECT_EQ(renderers::apply_tex_env(gl::TexEnv::modulate, fragment, texel2), fragment);  // Cv = Cf, Av = Af At
  gl::Texture rgb;
  rgb.has_alpha = false;  // GL_RGB and GL_LUMINANCE: alpha expanded to 255
  uint8_t texel3[4] = {100, 110, 120, 255};
  renderers::fill_missing_components(rgb, gl::TexEnv::replace, fragment, texel3);
  EXPECT_EQ(renderers::apply_tex_env(gl::TexEnv::replace, fragment, texel3),
            100u | 110u << 8 | 120u << 16 | 40u << 24);  // Av = Af
  EXPECT_FALSE(renderers::env_needs_base_format(rgb, gl::TexEnv::modulate));
  EXPECT_FALSE(renderers::env_needs_base_format(gl::Texture{}, gl::TexEnv::replace));
}
