// Texel arithmetic the software back ends share (arm in its span loop,
// ap-tile when it textures the frame it reads back from the array): wrap
// modes, the bilinear blend of four texels with 8-bit weights, and the
// texture environments on RGBA8, with products of 0.8 codes rounded to
// nearest exactly (sw_driver/renderers/arm/README.md, "Rounding").
#pragma once

#include <algorithm>
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

}  // namespace tessera::renderers
