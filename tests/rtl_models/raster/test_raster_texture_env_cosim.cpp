// Co-simulation: tlm/raster/datapath/texture_env.h against the Verilated
// rtl_models/raster/texture_env.sv, every output bit. Every vector goes
// through the scalar form (texture_filter_env) and through the batch form
// (texture_filter_env_batch) in every variant this machine runs, with the
// other fragments of its environment: 3125 corner fragments a batch, or 1 to
// 64 random ones.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "cosim_support.h"
#include "raster/datapath/texture_env.h"
#include "texture_env_adapter.h"

namespace tessera::raster {
namespace {

// The inputs of one batch, lane by lane.
struct Lanes {
  std::vector<uint32_t> texel[4], weight_s, weight_t, fragment;
  void add(const std::array<uint32_t, 4>& t, uint32_t ws, uint32_t wt, uint32_t f) {
    for (unsigned k = 0; k < 4; ++k) texel[k].push_back(t[k]);
    weight_s.push_back(ws);
    weight_t.push_back(wt);
    fragment.push_back(f);
  }
  void add(const TextureEnvLane& lane) { add(lane.texel, lane.weight_s, lane.weight_t, lane.fragment); }
  size_t size() const { return fragment.size(); }
};

// One environment's fragments, checked together: the batch form takes them
// as one batch.
struct Checker : CosimTally {
  TextureEnvRtl rtl;

  void check(TexEnv mode, const Lanes& in) {
    const size_t n = in.size();
    std::vector<std::vector<uint32_t>> texel_out, fragment_out;
    for (BatchIsa isa : batch_isas()) {
      texel_out.emplace_back(n);
      fragment_out.emplace_back(n);
      texture_filter_env_batch(mode,
                               {{in.texel[0].data(), in.texel[1].data(), in.texel[2].data(), in.texel[3].data()},
                                in.weight_s.data(),
                                in.weight_t.data(),
                                in.fragment.data()},
                               static_cast<unsigned>(n), {texel_out.back().data(), fragment_out.back().data()}, isa);
    }
    for (size_t i = 0; i < n; ++i) {
      const std::array<Rgba8, 4> texels{Rgba8::unpack(in.texel[0][i]), Rgba8::unpack(in.texel[1][i]),
                                        Rgba8::unpack(in.texel[2][i]), Rgba8::unpack(in.texel[3][i])};
      const auto ws = static_cast<uint8_t>(in.weight_s[i]), wt = static_cast<uint8_t>(in.weight_t[i]);
      const Rgba8 fragment = Rgba8::unpack(in.fragment[i]);
      const TextureEnvResult want = texture_filter_env(mode, texels, ws, wt, fragment);
      const TextureEnvResult got = rtl.run(mode, texels, ws, wt, fragment);
      bool same = want.texel == got.texel && want.fragment == got.fragment;
      for (size_t k = 0; k < texel_out.size(); ++k)
        same = same && texel_out[k][i] == got.texel.pack() && fragment_out[k][i] == got.fragment.pack();
      if (count(same)) {
        ADD_FAILURE() << std::hex << "mode " << static_cast<unsigned>(mode) << " texels " << texels[0].pack() << " "
                      << texels[1].pack() << " " << texels[2].pack() << " " << texels[3].pack() << " weights "
                      << unsigned(ws) << "," << unsigned(wt) << " fragment " << fragment.pack() << ": texel "
                      << want.texel.pack() << "/" << got.texel.pack() << " out " << want.fragment.pack() << "/"
                      << got.fragment.pack() << " (or a batch variant)";
      }
    }
  }
};

TEST(TextureEnvCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::array<uint32_t, 5> colours{0x00000000, 0xffffffff, 0x80ff7f01, 0x01807fff, 0xff000080};
  const std::array<uint8_t, 5> weights{0, 1, 128, 254, 255};
  for (TexEnv mode : ALL_TEXTURE_ENV_MODES)
    for (uint32_t t0 : colours) {
      Lanes lanes;
      for (uint32_t t1 : colours)
        for (uint32_t t2 : colours)
          for (uint32_t t3 : colours)
            for (uint8_t ws : weights)
              for (uint8_t wt : weights) lanes.add({t0, t1, t2, t3}, ws, wt, colours[(t0 ^ t3) % 5]);
      c.check(mode, lanes);
    }
  const uint64_t corner_vectors = c.vectors;

  // Environments at random (raster_vectors.h), each with a batch of 1 to 64
  // random fragments.
  VectorRng rng(0x7e4e);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const TexEnv mode = random_texture_env_mode(rng);
    Lanes lanes;
    for (unsigned i = random_batch_length(rng()); i > 0; --i) lanes.add(random_texture_env_lane(rng));
    c.check(mode, lanes);
  }
  report_cosim("texture_env", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
