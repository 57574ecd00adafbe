// Texel arithmetic the software back ends share (arm in its span loop,
// ap-tile when it textures the frame it reads back from the array): wrap
// modes, the bilinear blend of four texels with 8-bit weights, the level of
// detail and mipmap level choice, and the texture environments on RGBA8
// (every ES 1.1 mode and the GL_COMBINE functions), with products of 0.8
// codes rounded to nearest exactly (sw_driver/renderers/arm/README.md,
// "Rounding").
#pragma once

#include <algorithm>
#include <climits>
#include <cstdint>

#include "common/little_endian.h"
#include "gl/renderer.h"
#include "renderers/common/fixed_math.h"

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
    default: break;  // BLEND, ADD, COMBINE: apply_texture_unit
  }
  return rgba;
}

// GL_BLEND and GL_ADD (ES 1.1 table 3.15, RGBA textures): BLEND is
// C = Cf (1 - Ct) + Cc Ct with one rounding per channel, as DECAL; ADD is
// C = min(Cf + Ct, 1) (exact); both take A = Af At (rounded as MODULATE).
inline uint32_t apply_blend_env(uint32_t rgba, const uint8_t texel[4], const uint8_t env_color[4]) {
  uint32_t out = mul8(rgba >> 24, texel[3]) << 24;
  for (int ch = 0; ch < 3; ++ch) {
    const uint32_t f = (rgba >> (8 * ch)) & 0xff, t = texel[ch];
    out |= div255(f * (255 - t) + env_color[ch] * t) << (8 * ch);
  }
  return out;
}
inline uint32_t apply_add_env(uint32_t rgba, const uint8_t texel[4]) {
  uint32_t out = mul8(rgba >> 24, texel[3]) << 24;
  for (int ch = 0; ch < 3; ++ch) out |= std::min<uint32_t>(((rgba >> (8 * ch)) & 0xff) + texel[ch], 255) << (8 * ch);
  return out;
}

// GL_COMBINE (ES 1.1 section 3.7.12). Each argument is a 0.8 code a (the
// operand applied to its source: a, 255 - a, or the source's alpha); the
// function's value is computed exactly in units of 1/510 of a code, where
// every function of table 3.18 is an integer n:
//   REPLACE      510 a0                  MODULATE   2 a0 a1
//   ADD          510 (a0 + a1)           SUBTRACT   510 (a0 - a1)
//   ADD_SIGNED   510 (a0 + a1) - 65025   (a0 + a1 - 0.5 on the 0..1 scale)
//   INTERPOLATE  2 (a0 a2 + a1 (255 - a2))
//   DOT3_RGB(A)  2 sum over r, g, b of (2 a0 - 255) (2 a1 - 255)
//                (4 ((r0 - 0.5)(r1 - 0.5) + ...) on the 0..1 scale)
// then multiplied by the scale (1, 2 or 4), rounded to nearest once (halves
// up: floor((n scale + 255) / 510)) and clamped to [0, 255]. MODULATE with
// scale 1 is therefore exactly the MODULATE environment's mul8, and no
// intermediate result is rounded or clamped before the scale, as the
// specification's formulas read.
// Every value fits an int32: |n| <= 2 * 3 * 255^2 (DOT3) before the scale
// of at most 4, below 2^21. The rounding divides by 510 without a division
// instruction: floor(m / 510) = floor(floor(m / 2) / 255) for m >= 0, and
// floor(h / 255) = (h + 1 + ((h + 1) >> 8)) >> 8 for h < 65790, which
// covers every m below the clamp at 256 * 510 (the rasterizer's combiner,
// tlm/raster/datapath/texture_combiner.h, rounds the same way).
inline int32_t combine_value(gl::CombineFunc func, const int32_t a[3]) {
  switch (func) {
    case gl::CombineFunc::replace: return 510 * a[0];
    case gl::CombineFunc::modulate: return 2 * a[0] * a[1];
    case gl::CombineFunc::add: return 510 * (a[0] + a[1]);
    case gl::CombineFunc::add_signed: return 510 * (a[0] + a[1]) - 65025;
    case gl::CombineFunc::interpolate: return 2 * (a[0] * a[2] + a[1] * (255 - a[2]));
    case gl::CombineFunc::subtract: return 510 * (a[0] - a[1]);
    default: return 0;  // DOT3 takes all three channels: combine_dot3
  }
}
inline int32_t combine_dot3(const int32_t a0[3], const int32_t a1[3]) {
  int32_t sum = 0;
  for (int ch = 0; ch < 3; ++ch) sum += (2 * a0[ch] - 255) * (2 * a1[ch] - 255);
  return 2 * sum;
}
inline uint32_t combine_round(int32_t value, unsigned scale) {
  const int32_t m = value * static_cast<int32_t>(scale) + 255;
  if (m < 0) return 0;
  if (m >= 256 * 510) return 255;
  const uint32_t h = static_cast<uint32_t>(m) >> 1;
  return (h + 1 + ((h + 1) >> 8)) >> 8;
}

// The argument of `stage` number i for channel ch (0..2 colour, 3 alpha);
// sources[] holds the RGBA8 colours indexed by gl::CombineSource.
inline int32_t combine_argument(const gl::CombineStage& stage, int i, int ch, const uint32_t sources[4]) {
  const uint32_t color = sources[static_cast<int>(stage.source[i])];
  const int32_t c = static_cast<int32_t>((color >> (8 * ch)) & 0xff), alpha = static_cast<int32_t>(color >> 24);
  switch (stage.operand[i]) {
    case gl::CombineOperand::src_color: return c;
    case gl::CombineOperand::one_minus_src_color: return 255 - c;
    case gl::CombineOperand::src_alpha: return alpha;
    case gl::CombineOperand::one_minus_src_alpha: return 255 - alpha;
  }
  return c;
}

inline uint32_t apply_combine(const gl::TextureUnit& unit, uint32_t previous, uint32_t primary,
                              const uint8_t texel[4]) {
  const uint32_t texture_rgba =
      uint32_t{texel[0]} | uint32_t{texel[1]} << 8 | uint32_t{texel[2]} << 16 | uint32_t{texel[3]} << 24;
  const uint32_t constant = uint32_t{unit.env_color[0]} | uint32_t{unit.env_color[1]} << 8 |
                            uint32_t{unit.env_color[2]} << 16 | uint32_t{unit.env_color[3]} << 24;
  // Indexed by gl::CombineSource: texture, constant, primary colour, previous.
  const uint32_t sources[4] = {texture_rgba, constant, primary, previous};
  const gl::CombineStage& rgb = unit.combine_rgb;
  const gl::CombineStage& alpha = unit.combine_alpha;
  uint32_t out = 0;
  const bool dot3 = rgb.func == gl::CombineFunc::dot3_rgb || rgb.func == gl::CombineFunc::dot3_rgba;
  if (dot3) {
    int32_t a0[3], a1[3];
    for (int ch = 0; ch < 3; ++ch) {
      a0[ch] = combine_argument(rgb, 0, ch, sources);
      a1[ch] = combine_argument(rgb, 1, ch, sources);
    }
    const int32_t dot = combine_dot3(a0, a1);
    const uint32_t value = combine_round(dot, rgb.scale);
    out = value | value << 8 | value << 16;
    // DOT3_RGBA puts the dot product in alpha too, the alpha function unused;
    // each result is then scaled by its own scale (ES 1.1 section 3.7.12:
    // "the RGB and ALPHA results ... multiplied by RGB_SCALE and
    // ALPHA_SCALE, respectively", as Mesa does).
    if (rgb.func == gl::CombineFunc::dot3_rgba) return out | combine_round(dot, alpha.scale) << 24;
  } else {
    for (int ch = 0; ch < 3; ++ch) {
      const int32_t a[3] = {combine_argument(rgb, 0, ch, sources), combine_argument(rgb, 1, ch, sources),
                            combine_argument(rgb, 2, ch, sources)};
      out |= combine_round(combine_value(rgb.func, a), rgb.scale) << (8 * ch);
    }
  }
  const int32_t a[3] = {combine_argument(alpha, 0, 3, sources), combine_argument(alpha, 1, 3, sources),
                        combine_argument(alpha, 2, 3, sources)};
  return out | combine_round(combine_value(alpha.func, a), alpha.scale) << 24;
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

// One texture unit applied to the fragment: `previous` is the colour the
// units before it produced (the primary colour for the first), `primary`
// the interpolated fragment colour, `texel` the unit's filtered texel as
// the texture holds it (missing components expanded). For MODULATE and
// REPLACE the components the unit's base format lacks are filled from
// `previous` first (fill_missing_components, table 3.15); BLEND, ADD and
// DECAL give the table's result from the expanded texel, and GL_COMBINE
// takes it as it is.
inline uint32_t apply_texture_unit(const gl::TextureUnit& unit, uint32_t previous, uint32_t primary,
                                   const uint8_t texel[4]) {
  gl::TexEnv code;
  if (gl::hardware_tex_env(unit.env, &code)) {
    uint8_t filled[4] = {texel[0], texel[1], texel[2], texel[3]};
    fill_missing_components(unit.tex, code, previous, filled);
    return apply_tex_env(code, previous, filled);
  }
  switch (unit.env) {
    case gl::TexEnvMode::blend: return apply_blend_env(previous, texel, unit.env_color);
    case gl::TexEnvMode::add: return apply_add_env(previous, texel);
    default: return apply_combine(unit, previous, primary, texel);
  }
}

// The system-memory address of texel (i, j), already wrapped, of `tex`'s
// level 0 (RGBA8, rows of `width` texels).
inline uint32_t texel_address(const gl::Texture& tex, int i, int j) {
  return tex.address + (static_cast<uint32_t>(j) * tex.width + static_cast<uint32_t>(i)) * 4;
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
// the level boundaries by several rows away from the reference.)
// In 16.16 fixed point: the four derivatives' magnitudes are given in a
// common unit 2^scale texels per pixel (scale in 16.16), lambda =
// log2_q16(max) + scale; LOD_MAGNIFIED for a texture that does not move
// (rho = 0).
inline constexpr int32_t LOD_MAGNIFIED = INT32_MIN;
inline constexpr int32_t LOD_ONE = 65536;

inline int32_t texture_lod_q16(uint64_t ux, uint64_t vx, uint64_t uy, uint64_t vy, int32_t scale) {
  const uint64_t largest = std::max({ux, vx, uy, vy});
  return largest == 0 ? LOD_MAGNIFIED : log2_q16(largest) + scale;
}

// The switch point c between magnification (lambda <= c) and minification,
// in 16.16: 0.5 for a LINEAR magnification filter with a NEAREST_MIPMAP_*
// minification filter, 0 otherwise (section 3.8.9), so that a magnified
// texture's edge to level 1 is not sharper than the magnified image.
inline int32_t lod_switch_point(const gl::Texture& tex) {
  return tex.mag_filter == gl::TexFilter::linear && tex.min_filter == gl::TexFilter::nearest &&
                 tex.min_mipmap != gl::MipmapFilter::none
             ? LOD_ONE / 2
             : 0;
}

// Whether the level of detail changes what `tex` gives: it does not when the
// two filters agree and there are no mipmaps, so callers skip computing it.
inline bool texture_needs_lod(const gl::Texture& tex) {
  return tex.min_mipmap != gl::MipmapFilter::none || tex.min_filter != tex.mag_filter;
}

// Levels and filter chosen for one sample (choose_levels_q16).
struct LodChoice {
  unsigned level[2] = {0, 0};
  unsigned count = 1;  // levels sampled: 1 or 2
  uint32_t blend = 0;  // weight of level[1]
  bool linear = false;
};

// The levels and filter that sample `tex` at level of detail `lambda`
// (16.16; sections 3.8.8 to 3.8.9): magnified when lambda <= c (the switch
// point; LOD_MAGNIFIED included), level[0] (and level[1] with weight
// `blend`, in 1/256, when two levels are blended), each filtered by
// `linear`. *_MIPMAP_NEAREST takes level ceil(lambda + 1/2) - 1 (0 up to
// lambda = 1/2), at most the last; *_MIPMAP_LINEAR levels floor(lambda) and
// the next, blended by frac(lambda) * 256 rounded to nearest (halves up).
inline LodChoice choose_levels_q16(const gl::Texture& tex, int32_t lambda) {
  LodChoice choice;
  if (lambda == LOD_MAGNIFIED || lambda <= lod_switch_point(tex)) {
    choice.linear = tex.mag_filter == gl::TexFilter::linear;
    return choice;
  }
  choice.linear = tex.min_filter == gl::TexFilter::linear;
  const unsigned q = tex.levels > 0 ? tex.levels - 1 : 0;  // the last level
  if (tex.min_mipmap == gl::MipmapFilter::none || q == 0) return choice;
  if (tex.min_mipmap == gl::MipmapFilter::nearest) {
    // d = ceil(lambda + 1/2) - 1 for lambda > 1/2, else 0; at most q.
    const int32_t d = lambda <= LOD_ONE / 2 ? 0 : ((lambda + LOD_ONE / 2 + (LOD_ONE - 1)) >> 16) - 1;
    choice.level[0] = std::min(static_cast<unsigned>(d), q);
    return choice;
  }
  if (lambda >= static_cast<int32_t>(q) * LOD_ONE) {
    choice.level[0] = q;
    return choice;
  }
  // Levels floor(lambda) and the next, blended by frac(lambda).
  choice.level[0] = static_cast<unsigned>(lambda >> 16);
  choice.level[1] = choice.level[0] + 1;
  choice.blend = ((static_cast<uint32_t>(lambda) & 0xffff) + 128) >> 8;
  if (choice.blend == 0) return choice;
  if (choice.blend == 256) {
    choice.level[0] = choice.level[1];
    return choice;
  }
  choice.count = 2;
  return choice;
}

// The colour of `tex` at level-0 texel coordinates (u8, v8), 8 fraction
// bits, and level of detail `lambda` (16.16): the one function that samples
// a texture for the rasterizers that mipmap (arm). filter(level, u8, v8,
// linear, out) filters within one level (nearest: texel floor(u); bilinear:
// texels floor(u - 0.5) and the next, weights in 1/256) at that level's
// coordinates (u8 >> level keeps 8 fraction bits); two levels are blended
// with an 8-bit weight, rounded once. Returns the levels and filter it took
// (for the callers' instruction counts).
template <typename FilterLevel>
LodChoice sample_texture_lod_q16(const gl::Texture& tex, int u8, int v8, int32_t lambda, FilterLevel&& filter,
                                 uint8_t out[4]) {
  const LodChoice choice = choose_levels_q16(tex, lambda);
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
