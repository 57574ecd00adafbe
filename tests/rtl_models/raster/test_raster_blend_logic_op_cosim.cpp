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
  for (BlendFactor sf : ALL_BLEND_FACTORS)
    for (BlendFactor df : ALL_BLEND_FACTORS)
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

  // States at random (raster_vectors.h), each with a batch of 1 to 64
  // colour pairs at random.
  VectorRng rng(0xb1e4d);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const BlendState s = random_blend_state(rng);
    const unsigned n = random_batch_length(rng());
    src.resize(n);
    dst.resize(n);
    for (unsigned i = 0; i < n; ++i) {
      const ColourPair pair = random_colour_pair(rng);
      src[i] = pair.src;
      dst[i] = pair.dst;
    }
    c.check(s, src, dst);
  }
  report_cosim("blend_logic_op", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
