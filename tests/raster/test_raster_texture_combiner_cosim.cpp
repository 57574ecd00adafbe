// Co-simulation: tlm/raster/datapath/texture_combiner.h against the
// Verilated rtl_models/raster/texture_combiner.sv, every output bit. The
// corner vectors take every environment and base format code (those
// without an entry included) with every pair of combiner functions and
// scales; the random ones take random combiner words, reserved bits
// included, so every source, operand and scale code is drawn.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "cosim_support.h"
#include "raster/datapath/texture_combiner.h"
#include "texture_combiner_adapter.h"

namespace tessera::raster {
namespace {

struct Checker : CosimTally {
  TextureCombinerRtl rtl;

  void check(uint32_t env, uint32_t base, Rgba8 primary, Rgba8 previous, Rgba8 texel, Rgba8 env_color,
             uint32_t rgb_word, uint32_t alpha_word) {
    TextureUnitEnv unit;
    unit.env = from_code<TexEnv>(env);
    unit.base_format = from_code<TexBaseFormat>(base);
    unit.env_color = env_color;
    unit.rgb = CombineStage::decode(rgb_word);
    unit.alpha = CombineStage::decode(alpha_word);
    const Rgba8 want = texture_combiner(unit, primary, previous, texel);
    const Rgba8 got = rtl.run(unit.env, unit.base_format, primary, previous, texel, env_color, rgb_word, alpha_word);
    if (count(want == got)) {
      ADD_FAILURE() << std::hex << "env " << env << " base " << base << " rgb " << rgb_word << " alpha " << alpha_word
                    << " p " << primary.pack() << " f " << previous.pack() << " t " << texel.pack() << " c "
                    << env_color.pack() << ": " << want.pack() << "/" << got.pack();
    }
  }
};

TEST(TextureCombinerCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::array<uint32_t, 4> colours{0x00000000, 0xffffffff, 0x80ff7f01, 0x01807fff};
  for (uint32_t env = 0; env < 8; ++env)
    for (uint32_t base = 0; base < 8; ++base)
      for (uint32_t k = 0; k < colours.size(); ++k)
        c.check(env, base, Rgba8::unpack(colours[k]), Rgba8::unpack(colours[(k + 1) % 4]),
                Rgba8::unpack(colours[(k + 2) % 4]), Rgba8::unpack(colours[(k + 3) % 4]), 0x02013301u, 0x02222301u);
  // Every function pair and scale pair, sources and operands spread over the codes.
  for (uint32_t rgb_func = 0; rgb_func < 8; ++rgb_func)
    for (uint32_t alpha_func = 0; alpha_func < 8; ++alpha_func)
      for (uint32_t scales = 0; scales < 16; ++scales)
        for (uint32_t k = 0; k < colours.size(); ++k) {
          const uint32_t spread = (rgb_func * 0x9e3779b9u + alpha_func * 0x7f4a7c15u + k * 0x5bd1e995u) & 0x03330330u;
          c.check(5, k, Rgba8::unpack(colours[k]), Rgba8::unpack(colours[(k + 1) % 4] ^ 0x00552211u),
                  Rgba8::unpack(colours[(k + 2) % 4] ^ 0x11223344u), Rgba8::unpack(colours[(k + 3) % 4]),
                  rgb_func | spread | (scales & 3) << 28, alpha_func | (spread >> 4) | (scales >> 2) << 28);
        }
  const uint64_t corner_vectors = c.vectors;

  std::mt19937_64 rng(0xc0b1);
  for (uint64_t i = 0; i < RANDOM_VECTORS; ++i) {
    const uint64_t a = rng(), b = rng(), d = rng();
    // Half the vectors take COMBINE, the rest any code.
    const uint32_t env = (d & 1) != 0 ? 5u : static_cast<uint32_t>(d >> 1) & 7;
    c.check(env, static_cast<uint32_t>(d >> 4) & 7, Rgba8::unpack(static_cast<uint32_t>(a)),
            Rgba8::unpack(static_cast<uint32_t>(a >> 32)), Rgba8::unpack(static_cast<uint32_t>(b)),
            Rgba8::unpack(static_cast<uint32_t>(b >> 32)), static_cast<uint32_t>(d >> 8),
            static_cast<uint32_t>(d >> 32) ^ static_cast<uint32_t>(a >> 16));
  }
  report_cosim("texture_combiner", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
