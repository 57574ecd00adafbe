// Co-simulation: tlm/raster/datapath/blend_logic_op.h against the Verilated
// rtl_models/raster/blend_logic_op.sv, every output bit. Every vector goes
// through the scalar form (blend_logic_op) and through the batch form
// (blend_logic_op_batch) in every variant this machine runs, with the other
// colour pairs of its state: the 36 pairs of the corner colours, or 1 to 64
// random ones.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "blend_logic_op_adapter.h"
#include "cosim_support.h"
#include "raster/datapath/blend_logic_op.h"

namespace tessera::raster {
namespace {

// Every factor, plus a code without an entry (must act as ZERO on both sides).
constexpr std::array<BlendFactor, 12> ALL_FACTORS{BlendFactor::zero,
                                                  BlendFactor::one,
                                                  BlendFactor::src_color,
                                                  BlendFactor::one_minus_src_color,
                                                  BlendFactor::src_alpha,
                                                  BlendFactor::one_minus_src_alpha,
                                                  BlendFactor::dst_alpha,
                                                  BlendFactor::one_minus_dst_alpha,
                                                  BlendFactor::dst_color,
                                                  BlendFactor::one_minus_dst_color,
                                                  BlendFactor::src_alpha_saturate,
                                                  static_cast<BlendFactor>(15)};

// One state's colour pairs, checked together: the batch form takes them as
// one batch.
struct Checker : CosimTally {
  BlendLogicOpRtl rtl;

  void check(const BlendState& s, const std::vector<uint32_t>& src, const std::vector<uint32_t>& dst) {
    const size_t n = src.size();
    std::vector<std::vector<uint32_t>> out;
    for (BatchIsa isa : batch_isas()) {
      out.emplace_back(n);
      blend_logic_op_batch(s, src.data(), dst.data(), static_cast<unsigned>(n), out.back().data(), isa);
    }
    for (size_t i = 0; i < n; ++i) {
      const Rgba8 want = blend_logic_op(s, Rgba8::unpack(src[i]), Rgba8::unpack(dst[i]));
      const Rgba8 got = rtl.run(s, Rgba8::unpack(src[i]), Rgba8::unpack(dst[i]));
      bool same = want == got;
      for (const auto& batch : out) same = same && batch[i] == got.pack();
      if (count(same)) {
        ADD_FAILURE() << std::hex << "src " << src[i] << " dst " << dst[i] << " blend " << s.blend_enable << " sf "
                      << static_cast<unsigned>(s.src_factor) << " df " << static_cast<unsigned>(s.dst_factor)
                      << " logic " << s.logic_op_enable << " op " << static_cast<unsigned>(s.op) << " mask "
                      << unsigned(s.color_mask) << ": " << want.pack() << "/" << got.pack() << " (or a batch variant)";
      }
    }
  }
};

TEST(BlendLogicOpCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::vector<uint32_t> colours{0x00000000, 0xffffffff, 0x807f0180, 0x01fe7f00, 0xff00ff80, 0x7f80fe01};
  // Every pair of the colours, under each state.
  std::vector<uint32_t> src, dst;
  for (uint32_t sc : colours)
    for (uint32_t dc : colours) {
      src.push_back(sc);
      dst.push_back(dc);
    }
  unsigned states = 0;
  for (BlendFactor sf : ALL_FACTORS)
    for (BlendFactor df : ALL_FACTORS)
      for (uint32_t enables = 0; enables < 4; ++enables)
        for (uint8_t mask : {uint8_t{0}, uint8_t{5}, uint8_t{15}}) {
          BlendState s;
          s.blend_enable = enables & 1;
          s.logic_op_enable = enables & 2;
          s.src_factor = sf;
          s.dst_factor = df;
          s.op = static_cast<LogicOp>(states++ % 16);
          s.color_mask = mask;
          c.check(s, src, dst);
        }
  for (uint16_t op = 0; op < 16; ++op)
    for (uint8_t mask = 0; mask < 16; ++mask) {
      BlendState s;
      s.logic_op_enable = true;
      s.op = static_cast<LogicOp>(op);
      s.color_mask = mask;
      c.check(s, src, dst);
    }
  const uint64_t corner_vectors = c.vectors;

  // States at random, each with a batch of 1 to 64 colour pairs at random.
  std::mt19937_64 rng(0xb1e4d);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const uint64_t a = rng();
    BlendState s;
    s.blend_enable = (a & 3) != 0;  // mostly blending: it has the arithmetic
    s.logic_op_enable = ((a >> 2) & 7) == 0;
    s.src_factor = ALL_FACTORS[((a >> 5) & 0xff) % ALL_FACTORS.size()];
    s.dst_factor = ALL_FACTORS[((a >> 13) & 0xff) % ALL_FACTORS.size()];
    s.op = static_cast<LogicOp>((a >> 21) & 15);
    s.color_mask = ((a >> 25) & 3) == 0 ? static_cast<uint8_t>((a >> 27) & 15) : COLOR_MASK_ALL;
    const unsigned n = random_batch_length(a >> 32);
    src.resize(n);
    dst.resize(n);
    for (unsigned i = 0; i < n; ++i) {
      const uint64_t b = rng();
      src[i] = static_cast<uint32_t>(b);
      dst[i] = static_cast<uint32_t>(b >> 32);
    }
    c.check(s, src, dst);
  }
  report_cosim("blend_logic_op", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
