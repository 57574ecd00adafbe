// Co-simulation: tlm/raster/datapath/texture_combiner.h against the
// Verilated rtl_models/raster/texture_combiner.sv, every output bit. The
// corner vectors take every environment and base format code (those
// without an entry included) with every pair of combiner functions and
// scales; the random ones take random combiner words, reserved bits
// included, so every source, operand and scale code is drawn. Every vector
// goes through the scalar form (texture_combiner) and through the batch form
// (texture_combiner_batch) in every variant this machine runs, with the
// other fragments of its unit state (1 to 64 at random).
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "cosim_support.h"
#include "raster/datapath/texture_combiner.h"
#include "texture_combiner_adapter.h"

namespace tessera::raster {
namespace {

// The colours of one batch, lane by lane.
struct Lanes {
  std::vector<uint32_t> primary, previous, texel;
  void add(uint32_t p, uint32_t f, uint32_t t) {
    primary.push_back(p);
    previous.push_back(f);
    texel.push_back(t);
  }
  void add(const CombinerLane& lane) { add(lane.primary, lane.previous, lane.texel); }
};

// One unit state's fragments, checked together: the batch form takes them
// as one batch.
struct Checker : CosimTally {
  TextureCombinerRtl rtl;

  void check(uint32_t env, uint32_t base, Rgba8 env_color, uint32_t rgb_word, uint32_t alpha_word, const Lanes& in) {
    const TextureUnitEnv unit = CombinerState{env, base, env_color, rgb_word, alpha_word}.unit();
    const size_t n = in.primary.size();
    std::vector<std::vector<uint32_t>> out;
    for (BatchIsa isa : batch_isas()) {
      out.emplace_back(n);
      texture_combiner_batch(unit, in.primary.data(), in.previous.data(), in.texel.data(), static_cast<unsigned>(n),
                             out.back().data(), isa);
    }
    for (size_t i = 0; i < n; ++i) {
      const Rgba8 primary = Rgba8::unpack(in.primary[i]), previous = Rgba8::unpack(in.previous[i]),
                  texel = Rgba8::unpack(in.texel[i]);
      const Rgba8 want = texture_combiner(unit, primary, previous, texel);
      const Rgba8 got = rtl.run(unit.env, unit.base_format, primary, previous, texel, env_color, rgb_word, alpha_word);
      bool same = want == got;
      for (const auto& batch : out) same = same && batch[i] == got.pack();
      if (count(same)) {
        ADD_FAILURE() << std::hex << "env " << env << " base " << base << " rgb " << rgb_word << " alpha " << alpha_word
                      << " p " << primary.pack() << " f " << previous.pack() << " t " << texel.pack() << " c "
                      << env_color.pack() << ": " << want.pack() << "/" << got.pack() << " (or a batch variant)";
      }
    }
  }
};

TEST(TextureCombinerCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::array<uint32_t, 4> colours{0x00000000, 0xffffffff, 0x80ff7f01, 0x01807fff};
  for (uint32_t env = 0; env < 8; ++env)
    for (uint32_t base = 0; base < 8; ++base)
      for (uint32_t k = 0; k < colours.size(); ++k) {
        Lanes lanes;
        lanes.add(colours[k], colours[(k + 1) % 4], colours[(k + 2) % 4]);
        c.check(env, base, Rgba8::unpack(colours[(k + 3) % 4]), 0x02013301u, 0x02222301u, lanes);
      }
  // Every function pair and scale pair, sources and operands spread over the codes.
  for (uint32_t rgb_func = 0; rgb_func < 8; ++rgb_func)
    for (uint32_t alpha_func = 0; alpha_func < 8; ++alpha_func)
      for (uint32_t scales = 0; scales < 16; ++scales)
        for (uint32_t k = 0; k < colours.size(); ++k) {
          const uint32_t spread = (rgb_func * 0x9e3779b9u + alpha_func * 0x7f4a7c15u + k * 0x5bd1e995u) & 0x03330330u;
          Lanes lanes;
          lanes.add(colours[k], colours[(k + 1) % 4] ^ 0x00552211u, colours[(k + 2) % 4] ^ 0x11223344u);
          c.check(5, k, Rgba8::unpack(colours[(k + 3) % 4]), rgb_func | spread | (scales & 3) << 28,
                  alpha_func | (spread >> 4) | (scales >> 2) << 28, lanes);
        }
  const uint64_t corner_vectors = c.vectors;

  // Unit states at random (raster_vectors.h: half of them COMBINE), each
  // with a batch of 1 to 64 random fragments.
  VectorRng rng(0xc0b1);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const CombinerState s = random_combiner_state(rng);
    Lanes lanes;
    for (unsigned i = random_batch_length(rng()); i > 0; --i) lanes.add(random_combiner_lane(rng));
    c.check(s.env, s.base_format, s.env_color, s.rgb_word, s.alpha_word, lanes);
  }
  report_cosim("texture_combiner", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
