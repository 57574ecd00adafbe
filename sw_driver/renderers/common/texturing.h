// Texel arithmetic the software back ends share (arm in its span loop,
// ap-tile when it textures the frame it reads back from the array): wrap
// modes, the bilinear blend of four texels with 8-bit weights, the level of
// detail and mipmap level choice, and the texture environments on RGBA8, with products of 0.8 codes rounded to
// nearest exactly (sw_driver/renderers/arm/README.md, "Rounding").
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gl/renderer.h"

namespace tessera::renderers {

// x / 255 rounded to nearest, exact for x <= 65025.
inline uint32_t div255(uint32_t x) {
  return (x + 128 + ((x + 128) >> 8)) >> 8;
}
// The product of two 0.8 codes, rounded to nearest.
inline uint32_t mul8(uint32_t a, uint32_t b) {
  return div255(a * b);
}

// Texel index i of a texture `size` texels wide (a power of two).
inline int wrap_texel(int i, unsigned size, gl::TexWrap mode) {
  if (mode == gl::TexWrap::clamp_to_edge) return std::clamp(i, 0, static_cast<int>(size) - 1);
  return i & static_cast<int>(size - 1);
}

// texel[0..3] = (i0, j0), (i1, j0), (i0, j1), (i1, j1), RGBA8 each; fu, fv
// the weights of i1 and j1 in 1/256; rounded once at the end.
inline void bilinear(const uint8_t texel[4][4], uint32_t fu, uint32_t fv, uint8_t out[4]) {
  for (int ch = 0; ch < 4; ++ch) {
    const uint32_t top = texel[0][ch] * (256 - fu) + texel[1][ch] * fu;
    const uint32_t bottom = texel[2][ch] * (256 - fu) + texel[3][ch] * fu;
    out[ch] = static_cast<uint8_t>((top * (256 - fv) + bottom * fv + 32768) >> 16);
  }
}

// The fragment colour `rgba` (r | g << 8 | b << 16 | a << 24) combined with
// `texel` by the texture environment.
inline uint32_t apply_tex_env(gl::TexEnv env, uint32_t rgba, const uint8_t texel[4]) {
  const uint32_t f[4] = {rgba & 0xff, (rgba >> 8) & 0xff, (rgba >> 16) & 0xff, rgba >> 24};
  switch (env) {
    case gl::TexEnv::modulate:
      return mul8(f[0], texel[0]) | mul8(f[1], texel[1]) << 8 | mul8(f[2], texel[2]) << 16 | mul8(f[3], texel[3]) << 24;
    case gl::TexEnv::replace:
      return uint32_t{texel[0]} | uint32_t{texel[1]} << 8 | uint32_t{texel[2]} << 16 | uint32_t{texel[3]} << 24;
    case gl::TexEnv::decal: {
      const uint32_t at = texel[3];
      return div255(f[0] * (255 - at) + texel[0] * at) | div255(f[1] * (255 - at) + texel[1] * at) << 8 |
             div255(f[2] * (255 - at) + texel[2] * at) << 16 | f[3] << 24;
    }
  }
  return rgba;
}

// Whether `env` takes a component `tex`'s base format lacks (ES 1.1 table
// 3.15): GL_REPLACE the fragment's alpha for RGB and LUMINANCE, GL_REPLACE
// and GL_MODULATE the fragment's colour for ALPHA. The other modes give the
// table's result from the expanded texel (0 colour, 255 alpha) as it is.
inline bool env_needs_base_format(const gl::Texture& tex, gl::TexEnv env) {
  return (!tex.has_alpha && env == gl::TexEnv::replace) ||
         (!tex.has_color && (env == gl::TexEnv::replace || env == gl::TexEnv::modulate));
}

// The texel `apply_tex_env` takes for `env`: the missing components made
// such that the environment's formula gives table 3.15's result (the
// fragment's own for GL_REPLACE, 255 for GL_MODULATE).
inline void fill_missing_components(const gl::Texture& tex, gl::TexEnv env, uint32_t rgba, uint8_t texel[4]) {
  if (!env_needs_base_format(tex, env)) return;
  if (!tex.has_alpha) texel[3] = static_cast<uint8_t>(rgba >> 24);
  if (!tex.has_color) {
    for (int ch = 0; ch < 3; ++ch)
      texel[ch] = env == gl::TexEnv::replace ? static_cast<uint8_t>(rgba >> (8 * ch)) : uint8_t{255};
  }
}

// The colour of `tex` at texel coordinates (u8, v8) with 8 fraction bits,
// for the back ends that texture without mipmaps (ap-tile, ap-pixel):
// nearest (the magnification filter) takes texel floor(u); bilinear blends
// texels floor(u - 0.5) and the next with 8-bit weights. fetch(i, j, out)
// reads texel (i, j), already wrapped, as RGBA8. Returns whether the blend
// was bilinear (four fetches) rather than nearest (one).
template <typename Fetch>
bool sample_texture(const gl::Texture& tex, int u8, int v8, Fetch&& fetch, uint8_t out[4]) {
  if (tex.mag_filter == gl::TexFilter::nearest) {
    fetch(wrap_texel(u8 >> 8, tex.width, tex.wrap_s), wrap_texel(v8 >> 8, tex.height, tex.wrap_t), out);
    return false;
  }
  const int um = u8 - 128, vm = v8 - 128;
  const int i0 = wrap_texel(um >> 8, tex.width, tex.wrap_s), i1 = wrap_texel((um >> 8) + 1, tex.width, tex.wrap_s);
  const int j0 = wrap_texel(vm >> 8, tex.height, tex.wrap_t), j1 = wrap_texel((vm >> 8) + 1, tex.height, tex.wrap_t);
  uint8_t four[4][4];
  fetch(i0, j0, four[0]);
  fetch(i1, j0, four[1]);
  fetch(i0, j1, four[2]);
  fetch(i1, j1, four[3]);
  bilinear(four, static_cast<uint32_t>(um) & 255, static_cast<uint32_t>(vm) & 255, out);
  return true;
}

// The level of detail of OpenGL ES 1.1 section 3.8.8: lambda = log2(rho),
// rho = max(fx, fy) with u, v in level 0's texels and x, y in pixels. The
// specification defines fx = sqrt(ux^2 + vx^2) and allows any fx between
// max(|ux|, |vx|) and |ux| + |vx| (equation 3.17); this takes the lower
// bound, fx = max(|ux|, |vx|), as Mesa's softpipe does: no squares and no
// root per pixel on the ARM, and the reference's level choice. (The exact
// form differs from it by up to log2(sqrt 2) = 0.5 where u and v both vary
// along one screen axis: on the mipmap_floor scene's outer strips it moved
// the level boundaries by several rows away from the reference.) -inf for a
// texture that does not move (rho = 0): magnified.
inline double texture_lod(double ux, double vx, double uy, double vy) {
  return std::log2(std::max({std::fabs(ux), std::fabs(vx), std::fabs(uy), std::fabs(vy)}));
}

// The switch point c between magnification (lambda <= c) and minification:
// 0.5 for a LINEAR magnification filter with a NEAREST_MIPMAP_* minification
// filter, 0 otherwise (section 3.8.9), so that a magnified texture's edge
// to level 1 is not sharper than the magnified image.
inline double lod_switch_point(const gl::Texture& tex) {
  return tex.mag_filter == gl::TexFilter::linear && tex.min_filter == gl::TexFilter::nearest &&
                 tex.min_mipmap != gl::MipmapFilter::none
             ? 0.5
             : 0.0;
}

// Whether the level of detail changes what `tex` gives: it does not when the
// two filters agree and there are no mipmaps, so callers skip computing it.
inline bool texture_needs_lod(const gl::Texture& tex) {
  return tex.min_mipmap != gl::MipmapFilter::none || tex.min_filter != tex.mag_filter;
}

// The levels and filter that sample `tex` at level of detail `lambda`
// (sections 3.8.8 to 3.8.9): level[0] (and level[1] with weight `blend`, in
// 1/256, when two levels are blended), each filtered by `linear`.
struct LodChoice {
  unsigned level[2] = {0, 0};
  unsigned count = 1;  // levels sampled: 1 or 2
  uint32_t blend = 0;  // weight of level[1]
  bool linear = false;
};

inline LodChoice choose_levels(const gl::Texture& tex, double lambda) {
  LodChoice choice;
  if (!(lambda > lod_switch_point(tex))) {  // magnified (NaN included)
    choice.linear = tex.mag_filter == gl::TexFilter::linear;
    return choice;
  }
  choice.linear = tex.min_filter == gl::TexFilter::linear;
  const unsigned q = tex.levels > 0 ? tex.levels - 1 : 0;  // the last level
  if (tex.min_mipmap == gl::MipmapFilter::none || q == 0) return choice;
  if (tex.min_mipmap == gl::MipmapFilter::nearest) {
    // d = ceil(lambda + 1/2) - 1 for lambda > 1/2, else 0; at most q.
    const double d = lambda <= 0.5 ? 0.0 : std::ceil(lambda + 0.5) - 1.0;
    choice.level[0] = static_cast<unsigned>(std::min(d, static_cast<double>(q)));
    return choice;
  }
  if (lambda >= static_cast<double>(q)) {
    choice.level[0] = q;
    return choice;
  }
  // Levels floor(lambda) and the next, blended by frac(lambda).
  const double d1 = std::floor(lambda);
  choice.level[0] = static_cast<unsigned>(d1);
  choice.level[1] = choice.level[0] + 1;
  choice.blend = static_cast<uint32_t>(std::lround((lambda - d1) * 256.0));
  if (choice.blend == 0) return choice;
  if (choice.blend == 256) {
    choice.level[0] = choice.level[1];
    return choice;
  }
  choice.count = 2;
  return choice;
}

// The colour of `tex` at level-0 texel coordinates (u8, v8), 8 fraction
// bits, and level of detail `lambda`: the one function that samples a
// texture for the rasterizers that mipmap (arm). filter(level, u8, v8,
// linear, out) filters within one level (nearest: texel floor(u); bilinear:
// texels floor(u - 0.5) and the next, weights in 1/256) at that level's
// coordinates; two levels are blended with an 8-bit weight, rounded once.
// Returns the levels and filter it took (for the callers' instruction counts).
template <typename FilterLevel>
LodChoice sample_texture_lod(const gl::Texture& tex, int u8, int v8, double lambda, FilterLevel&& filter,
                             uint8_t out[4]) {
  const LodChoice choice = choose_levels(tex, lambda);
  // Coordinates scale by 2^-level: u8 >> level keeps 8 fraction bits.
  filter(choice.level[0], u8 >> choice.level[0], v8 >> choice.level[0], choice.linear, out);
  if (choice.count == 1) return choice;
  uint8_t next[4];
  filter(choice.level[1], u8 >> choice.level[1], v8 >> choice.level[1], choice.linear, next);
  for (int ch = 0; ch < 4; ++ch)
    out[ch] = static_cast<uint8_t>((out[ch] * (256 - choice.blend) + next[ch] * choice.blend + 128) >> 8);
  return choice;
}

// Level `level` of `tex`: level 0 is the texture's own address and size.
inline gl::TextureLevel texture_level(const gl::Texture& tex, unsigned level) {
  if (level == 0) return {tex.address, tex.width, tex.height};
  return tex.level[level];
}

}  // namespace tessera::renderers
