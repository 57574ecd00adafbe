// Co-simulation: tlm/raster/datapath/blend_logic_op.h against the Verilated
// rtl_models/raster/blend_logic_op.sv, every output bit.
#include <gtest/gtest.h>

#include <array>
#include <random>

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

struct Checker : CosimTally {
  BlendLogicOpRtl rtl;

  void check(const BlendState& s, Rgba8 src, Rgba8 dst) {
    const Rgba8 want = blend_logic_op(s, src, dst);
    const Rgba8 got = rtl.run(s, src, dst);
    if (count(want == got)) {
      ADD_FAILURE() << std::hex << "src " << src.pack() << " dst " << dst.pack() << " blend " << s.blend_enable
                    << " sf " << static_cast<unsigned>(s.src_factor) << " df " << static_cast<unsigned>(s.dst_factor)
                    << " logic " << s.logic_op_enable << " op " << static_cast<unsigned>(s.op) << " mask "
                    << unsigned(s.color_mask) << ": " << want.pack() << "/" << got.pack();
    }
  }
};

TEST(BlendLogicOpCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  const std::array<uint32_t, 6> colours{0x00000000, 0xffffffff, 0x807f0180, 0x01fe7f00, 0xff00ff80, 0x7f80fe01};
  for (BlendFactor sf : ALL_FACTORS)
    for (BlendFactor df : ALL_FACTORS)
      for (uint32_t enables = 0; enables < 4; ++enables)
        for (uint8_t mask : {uint8_t{0}, uint8_t{5}, uint8_t{15}})
          for (uint32_t sc : colours)
            for (uint32_t dc : colours) {
              BlendState s;
              s.blend_enable = enables & 1;
              s.logic_op_enable = enables & 2;
              s.src_factor = sf;
              s.dst_factor = df;
              s.op = static_cast<LogicOp>(c.vectors % 16);
              s.color_mask = mask;
              c.check(s, Rgba8::unpack(sc), Rgba8::unpack(dc));
            }
  for (uint16_t op = 0; op < 16; ++op)
    for (uint8_t mask = 0; mask < 16; ++mask)
      for (uint32_t sc : colours)
        for (uint32_t dc : colours) {
          BlendState s;
          s.logic_op_enable = true;
          s.op = static_cast<LogicOp>(op);
          s.color_mask = mask;
          c.check(s, Rgba8::unpack(sc), Rgba8::unpack(dc));
        }
  const uint64_t corner_vectors = c.vectors;

  std::mt19937_64 rng(0xb1e4d);
  for (uint64_t i = 0; i < RANDOM_VECTORS; ++i) {
    const uint64_t a = rng();
    const uint64_t b = rng();
    BlendState s;
    s.blend_enable = (a & 3) != 0;  // mostly blending: it has the arithmetic
    s.logic_op_enable = ((a >> 2) & 7) == 0;
    s.src_factor = ALL_FACTORS[((a >> 5) & 0xff) % ALL_FACTORS.size()];
    s.dst_factor = ALL_FACTORS[((a >> 13) & 0xff) % ALL_FACTORS.size()];
    s.op = static_cast<LogicOp>((a >> 21) & 15);
    s.color_mask = ((a >> 25) & 3) == 0 ? static_cast<uint8_t>((a >> 27) & 15) : COLOR_MASK_ALL;
    c.check(s, Rgba8::unpack(static_cast<uint32_t>(b)), Rgba8::unpack(static_cast<uint32_t>(b >> 32)));
  }
  report_cosim("blend_logic_op", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
