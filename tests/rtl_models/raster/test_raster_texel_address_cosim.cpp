// Co-simulation: tlm/raster/datapath/texel_address.h against the Verilated
// rtl_models/raster/texel_address.sv, every output bit. Every vector goes
// through the scalar form (texel_lookup) and through the batch form
// (texel_lookup_batch) in every variant this machine runs, with the other
// coordinate pairs of its texture state: a corner state's pairs of the
// corner coordinates, or 1 to 64 random ones.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "cosim_support.h"
#include "raster/datapath/texel_address.h"
#include "texel_address_adapter.h"

namespace tessera::raster {
namespace {

struct BatchBuffers {
  std::vector<uint32_t> field[10];
  explicit BatchBuffers(size_t n) {
    for (auto& f : field) f.resize(n);
  }
  TexelBatch view() {
    return {field[0].data(),
            field[1].data(),
            field[2].data(),
            field[3].data(),
            field[4].data(),
            field[5].data(),
            {field[6].data(), field[7].data(), field[8].data(), field[9].data()}};
  }
};

// One texture's coordinate pairs, checked together: the batch form takes
// them as one batch.
struct Checker : CosimTally {
  TexelAddressRtl rtl;

  void check(const TextureState& st, const std::vector<int32_t>& s, const std::vector<int32_t>& t) {
    const size_t n = s.size();
    std::vector<BatchBuffers> batches;
    for (BatchIsa isa : batch_isas()) {
      batches.emplace_back(n);
      texel_lookup_batch(st, s.data(), t.data(), static_cast<unsigned>(n), batches.back().view(), isa);
    }
    const auto same_axis = [](const TexelAxis& a, const TexelAxis& b) {
      return a.index0 == b.index0 && a.index1 == b.index1 && a.weight == b.weight;
    };
    for (size_t i = 0; i < n; ++i) {
      const TexelFootprint want = texel_lookup(st, q15_16{s[i]}, q15_16{t[i]});
      const TexelFootprint got = rtl.lookup(st, q15_16{s[i]}, q15_16{t[i]});
      bool same = same_axis(want.s, got.s) && same_axis(want.t, got.t) && want.address == got.address;
      for (BatchBuffers& b : batches) {
        const uint32_t expected[10] = {got.s.index0, got.s.index1,   got.s.weight,   got.t.index0,   got.t.index1,
                                       got.t.weight, got.address[0], got.address[1], got.address[2], got.address[3]};
        for (unsigned f = 0; f < 10; ++f) same = same && b.field[f][i] == expected[f];
      }
      if (count(same)) {
        ADD_FAILURE() << "s " << s[i] << " t " << t[i] << " log2 " << int(st.log2_width) << "x" << int(st.log2_height)
                      << " wrap " << static_cast<unsigned>(st.wrap_s) << "/" << static_cast<unsigned>(st.wrap_t)
                      << " filter " << static_cast<unsigned>(st.filter) << ": i " << int(want.s.index0) << ","
                      << int(want.s.index1) << "/" << int(got.s.index0) << "," << int(got.s.index1) << " j "
                      << int(want.t.index0) << "," << int(want.t.index1) << "/" << int(got.t.index0) << ","
                      << int(got.t.index1) << " weights " << int(want.s.weight) << "," << int(want.t.weight) << "/"
                      << int(got.s.weight) << "," << int(got.t.weight) << " addr00 " << want.address[0] << "/"
                      << got.address[0] << " (or a batch variant)";
      }
    }
  }
};

TEST(TexelAddressCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  // Coordinates at the format extremes, at 0, +-1/2 texel and +-1 around 0
  // and 1, for every size (and the oversized log2 values), both wraps on
  // each axis, both filters.
  const std::array<int64_t, 15> coords{q15_16::MIN_RAW, q15_16::MAX_RAW, 0,      1,       -1,
                                       0x8000,          -0x8000,         0xffff, 0x10000, 0x10001,
                                       0x7fff,          -0x10000,        0x180,  0xff80,  0x12345678};
  const std::array<TexWrap, 2> wraps{TexWrap::repeat, TexWrap::clamp_to_edge};
  const std::array<TexFilter, 2> filters{TexFilter::nearest, TexFilter::linear};
  for (uint8_t lw = 0; lw < 16; ++lw)
    for (uint8_t lh : {uint8_t{0}, uint8_t{3}, uint8_t{8}, uint8_t{9}})
      for (TexWrap ws : wraps)
        for (TexWrap wt : wraps)
          for (TexFilter f : filters)
            for (int64_t parity = 0; parity < 2; ++parity) {
              // Every pair of coordinates; the base by the parity of s.
              TextureState st;
              st.base = parity != 0 ? 0xffff'fff0u : 0x0010'0000u;
              st.log2_width = lw;
              st.log2_height = lh;
              st.wrap_s = ws;
              st.wrap_t = wt;
              st.filter = f;
              std::vector<int32_t> s_batch, t_batch;
              for (int64_t s : coords)
                for (int64_t t : coords)
                  if ((s & 1) == parity) {
                    s_batch.push_back(static_cast<int32_t>(s));
                    t_batch.push_back(static_cast<int32_t>(t));
                  }
              c.check(st, s_batch, t_batch);
            }
  const uint64_t corner_vectors = c.vectors;

  // Textures at random (raster_vectors.h), each with a batch of 1 to 64
  // coordinate pairs.
  VectorRng rng(0x7e8e1);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const TextureState st = random_texture_state(rng);
    std::vector<int32_t> s(random_batch_length(rng())), t(s.size());
    for (size_t i = 0; i < s.size(); ++i) {
      const TexCoords pair = random_tex_coords(rng);
      s[i] = pair.s;
      t[i] = pair.t;
    }
    c.check(st, s, t);
  }
  report_cosim("texel_address", c, corner_vectors);
}

// Wrap codes without an entry in fixed_function.def (2, 3) act as REPEAT in
// both models: the same footprint as REPEAT, bit for bit.
TEST(TexelAddressCosim, UnknownWrapCodesActAsRepeat) {
  Checker c;
  TexelAddressRtl reference;
  std::mt19937_64 rng(0x3a9);
  for (uint32_t code = 2; code < 4; ++code) {
    for (int i = 0; i < 10000; ++i) {
      const uint64_t a = rng();
      TextureState st;
      st.log2_width = static_cast<uint8_t>(a % 9);
      st.log2_height = static_cast<uint8_t>((a >> 4) % 9);
      st.filter = from_code<TexFilter>(static_cast<uint32_t>(a >> 8));
      st.wrap_s = from_code<TexWrap>(code);
      st.wrap_t = from_code<TexWrap>(code);
      const q15_16 s{sign_extend(a >> 12, 20)}, t{sign_extend(a >> 32, 20)};
      c.check(st, {static_cast<int32_t>(s.raw)}, {static_cast<int32_t>(t.raw)});
      TextureState repeat = st;
      repeat.wrap_s = repeat.wrap_t = TexWrap::repeat;
      const TexelFootprint want = reference.lookup(repeat, s, t);
      const TexelFootprint got = reference.lookup(st, s, t);
      ASSERT_EQ(got.address, want.address) << code;
      ASSERT_EQ(got.s.weight, want.s.weight) << code;
    }
  }
  EXPECT_EQ(c.vectors, 20000u);
  EXPECT_EQ(c.mismatches, 0u);
}

}  // namespace
}  // namespace tessera::raster
