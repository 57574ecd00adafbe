// Co-simulation: tlm/raster/datapath/texture_env.h against the Verilated
// rtl_models/raster/texture_env.sv, every output bit.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "cosim_support.h"
#include "raster/datapath/texture_env.h"
#include "texture_env_adapter.h"

namespace tessera::raster {
namespace {

// Every environment of the unit, plus code 3 (BLEND, the combiner's: the
// fragment passes on both sides).
constexpr std::array<TexEnv, 4> ALL_MODES{TexEnv::replace, TexEnv::modulate, TexEnv::decal, static_cast<TexEnv>(3)};

struct Checker : CosimTally {
  TextureEnvRtl rtl;

  void check(TexEnv mode, const std::array<Rgba8, 4>& texels, uint8_t ws, uint8_t wt, Rgba8 fragment) {
    const TextureEnvResult want = texture_filter_env(mode, texels, ws, wt, fragment);
    const TextureEnvResult got = rtl.run(mode, texels, ws, wt, fragment);
    if (count(want.texel == got.texel && want.fragment == got.fragment)) {
      ADD_FAILURE() << std::hex << "mode " << static_cast<unsigned>(mode) << " texels " << texels[0].pack() << " "
                    << texels[1].pack() << " " << texels[2].pack() << " " << texels[3].pack() << " weights "
                    << unsigned(ws) << "," << unsigned(wt) << " fragment " << fragment.pack() << ": texel "
                    << want.texel.pack() << "/" << got.texel.pack() << " out " << want.fragment.pack() << "/"
                    << got.fragment.pack();
    }
  }
};

TEST(TextureEnvCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::array<uint32_t, 5> colours{0x00000000, 0xffffffff, 0x80ff7f01, 0x01807fff, 0xff000080};
  const std::array<uint8_t, 5> weights{0, 1, 128, 254, 255};
  for (TexEnv mode : ALL_MODES)
    for (uint32_t t0 : colours)
      for (uint32_t t1 : colours)
        for (uint32_t t2 : colours)
          for (uint32_t t3 : colours)
            for (uint8_t ws : weights)
              for (uint8_t wt : weights) {
                const std::array<Rgba8, 4> texels{Rgba8::unpack(t0), Rgba8::unpack(t1), Rgba8::unpack(t2),
                                                  Rgba8::unpack(t3)};
                c.check(mode, texels, ws, wt, Rgba8::unpack(colours[(t0 ^ t3) % 5]));
              }
  const uint64_t corner_vectors = c.vectors;

  std::mt19937_64 rng(0x7e4e);
  for (uint64_t i = 0; i < RANDOM_VECTORS; ++i) {
    const uint64_t a = rng();
    const uint64_t b = rng();
    const uint64_t d = rng();
    const std::array<Rgba8, 4> texels{
        Rgba8::unpack(static_cast<uint32_t>(a)), Rgba8::unpack(static_cast<uint32_t>(a >> 32)),
        Rgba8::unpack(static_cast<uint32_t>(b)), Rgba8::unpack(static_cast<uint32_t>(b >> 32))};
    c.check(ALL_MODES[d & 3], texels, static_cast<uint8_t>(d >> 8), static_cast<uint8_t>(d >> 16),
            Rgba8::unpack(static_cast<uint32_t>(d >> 32)));
  }
  report_cosim("texture_env", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
