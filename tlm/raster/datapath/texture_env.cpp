// See texture_env.h for the filter weights, environments and rounding.
#include "texture_env.h"

namespace tessera::raster {

namespace {

std::array<uint32_t, 4> channels(Rgba8 c) {
  return {c.r.raw, c.g.raw, c.b.raw, c.a.raw};
}

Rgba8 from_channels(const std::array<uint32_t, 4>& c) {
  return {unorm8::from_raw(c[0]), unorm8::from_raw(c[1]), unorm8::from_raw(c[2]), unorm8::from_raw(c[3])};
}

}  // namespace

uint32_t div255_round(uint32_t x) {
  const uint32_t t = x + 128;
  return (t + (t >> 8)) >> 8;
}

Rgba8 bilinear_filter(const std::array<Rgba8, 4>& texels, uint8_t weight_s, uint8_t weight_t) {
  const uint32_t a = weight_s;
  const uint32_t b = weight_t;
  const std::array<uint32_t, 4> w{(256 - a) * (256 - b), a * (256 - b), (256 - a) * b, a * b};
  std::array<uint32_t, 4> out{};
  for (unsigned c = 0; c < 4; ++c) {
    uint32_t sum = 0;
    for (unsigned k = 0; k < 4; ++k) {
      sum += w[k] * channels(texels[k])[c];
    }
    out[c] = (sum + (1u << 15)) >> 16;
  }
  return from_channels(out);
}

Rgba8 texture_environment(TexEnv mode, Rgba8 fragment, Rgba8 texel) {
  const auto f = channels(fragment);
  const auto t = channels(texel);
  std::array<uint32_t, 4> out = f;  // also for a code without an entry
  switch (mode) {
    case TexEnv::replace: out = t; break;
    case TexEnv::modulate:
      for (unsigned c = 0; c < 4; ++c) {
        out[c] = div255_round(f[c] * t[c]);
      }
      break;
    case TexEnv::decal:
      for (unsigned c = 0; c < 3; ++c) {
        out[c] = div255_round(f[c] * (255 - t[3]) + t[c] * t[3]);
      }
      break;
  }
  return from_channels(out);
}

TextureEnvResult texture_filter_env(TexEnv mode, const std::array<Rgba8, 4>& texels, uint8_t weight_s, uint8_t weight_t,
                                    Rgba8 fragment) {
  TextureEnvResult r;
  r.texel = bilinear_filter(texels, weight_s, weight_t);
  r.fragment = texture_environment(mode, fragment, r.texel);
  return r;
}

}  // namespace tessera::raster
