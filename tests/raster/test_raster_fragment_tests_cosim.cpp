// Co-simulation: tlm/raster/datapath/fragment_tests.h against the Verilated
// rtl_models/raster/fragment_tests.sv, every output bit. Every vector goes
// through the scalar form (run_fragment_tests) and through the batch form
// (run_fragment_tests_batch) in every variant this machine runs, with the
// other fragments of its state: 5 for a corner state, 1 to 64 at random.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "cosim_support.h"
#include "fragment_tests_adapter.h"
#include "raster/datapath/fragment_tests.h"

namespace tessera::raster {
namespace {

constexpr std::array<CompareFunc, 8> ALL_FUNCS{CompareFunc::never,  CompareFunc::less,    CompareFunc::equal,
                                               CompareFunc::lequal, CompareFunc::greater, CompareFunc::notequal,
                                               CompareFunc::gequal, CompareFunc::always};
// Every operation, plus a code without an entry (kept on both sides).
constexpr std::array<StencilOp, 7> ALL_OPS{StencilOp::keep,          StencilOp::zero, StencilOp::replace,
                                           StencilOp::incr,          StencilOp::decr, StencilOp::invert,
                                           static_cast<StencilOp>(7)};

// One state's fragments, checked together: the batch form takes them as
// one batch.
struct Checker : CosimTally {
  FragmentTestsRtl rtl;

  void check(const FragmentTestState& s, const std::vector<FragmentTestInput>& fragments) {
    const size_t n = fragments.size();
    std::vector<uint32_t> alpha(n), depth(n), stored_depth(n), stored_stencil(n);
    for (size_t i = 0; i < n; ++i) {
      alpha[i] = fragments[i].alpha.raw;
      depth[i] = fragments[i].depth.raw;
      stored_depth[i] = fragments[i].stored_depth.raw;
      stored_stencil[i] = fragments[i].stored_stencil.raw;
    }
    std::vector<std::vector<uint32_t>> flags, stencil;
    for (BatchIsa isa : batch_isas()) {
      flags.emplace_back(n);
      stencil.emplace_back(n);
      run_fragment_tests_batch(s, {alpha.data(), depth.data(), stored_depth.data(), stored_stencil.data()},
                               static_cast<unsigned>(n), {flags.back().data(), stencil.back().data()}, isa);
    }
    for (size_t i = 0; i < n; ++i) {
      const FragmentTestResult want = run_fragment_tests(s, fragments[i]);
      const FragmentTestResult got = rtl.run(s, fragments[i]);
      const uint32_t got_flags = (got.alpha_pass ? FRAGMENT_ALPHA_PASS : 0) |
                                 (got.stencil_pass ? FRAGMENT_STENCIL_PASS : 0) |
                                 (got.depth_pass ? FRAGMENT_DEPTH_PASS : 0) | (got.pass ? FRAGMENT_PASS : 0) |
                                 (got.depth_write ? FRAGMENT_DEPTH_WRITE : 0);
      bool same = want.alpha_pass == got.alpha_pass && want.stencil_pass == got.stencil_pass &&
                  want.depth_pass == got.depth_pass && want.pass == got.pass && want.stencil == got.stencil &&
                  want.depth_write == got.depth_write;
      for (size_t k = 0; k < flags.size(); ++k)
        same = same && flags[k][i] == got_flags && stencil[k][i] == got.stencil.raw;
      if (count(same)) {
        ADD_FAILURE() << "vector " << vectors << ": alpha " << want.alpha_pass << "/" << got.alpha_pass << " stencil "
                      << want.stencil_pass << "/" << got.stencil_pass << " depth " << want.depth_pass << "/"
                      << got.depth_pass << " pass " << want.pass << "/" << got.pass << " stencil value "
                      << want.stencil.raw << "/" << got.stencil.raw << " depth write " << want.depth_write << "/"
                      << got.depth_write << " (or a batch variant)";
      }
    }
  }
};

TEST(FragmentTestsCosim, CornerAndRandomVectorsMatchBitForBit) {
  Checker c;
  std::mt19937_64 rng(0xf7a6);

  // Every compare function on every test against below/equal/above at the
  // format extremes, and every stencil operation in every slot.
  const std::array<uint32_t, 3> alpha_refs{0, 128, 255};
  const std::array<uint32_t, 5> depths{0, 1, 0x7fffff, 0xfffffe, 0xffffff};
  const std::array<uint32_t, 4> stencils{0, 1, 0x80, 0xff};
  for (CompareFunc af : ALL_FUNCS)
    for (CompareFunc sf : ALL_FUNCS)
      for (CompareFunc df : ALL_FUNCS)
        for (StencilOp op : ALL_OPS)
          for (uint32_t enables = 0; enables < 8; ++enables)
            for (uint32_t k = 0; k < 6; ++k) {
              FragmentTestState s;
              s.alpha_enable = enables & 1;
              s.stencil_enable = enables & 2;
              s.depth_enable = enables & 4;
              s.alpha_func = af;
              s.stencil_func = sf;
              s.depth_func = df;
              s.alpha_ref = unorm8{alpha_refs[k % 3]};
              s.stencil_ref = stencil8{stencils[k % 4]};
              s.stencil_value_mask = k < 3 ? 0xff : 0x0f;
              s.stencil_write_mask = k & 1 ? 0xff : 0x3c;
              s.sfail = op;
              s.dpfail = ALL_OPS[(static_cast<size_t>(k) + 1) % ALL_OPS.size()];
              s.dppass = ALL_OPS[(static_cast<size_t>(k) + 2) % ALL_OPS.size()];
              s.depth_write_mask = k != 5;
              std::vector<FragmentTestInput> fragments;
              for (uint32_t v = 0; v < 5; ++v)
                fragments.push_back({unorm8{alpha_refs[v % 3]}, unorm24{depths[v]}, unorm24{depths[(v + k) % 5]},
                                     stencil8{stencils[(v + k) % 4]}});
              c.check(s, fragments);
            }
  const uint64_t corner_vectors = c.vectors;

  // States at random, each with a batch of 1 to 64 fragments at random.
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const uint64_t a = rng();
    const uint64_t b = rng();
    FragmentTestState s;
    s.alpha_enable = a & 1;
    s.stencil_enable = (a >> 1) & 1;
    s.depth_enable = (a >> 2) & 1;
    s.depth_write_mask = (a >> 3) & 1;
    s.alpha_func = ALL_FUNCS[(a >> 4) & 7];
    s.stencil_func = ALL_FUNCS[(a >> 7) & 7];
    s.depth_func = ALL_FUNCS[(a >> 10) & 7];
    s.sfail = ALL_OPS[((a >> 13) & 0xff) % ALL_OPS.size()];
    s.dpfail = ALL_OPS[((a >> 21) & 0xff) % ALL_OPS.size()];
    s.dppass = ALL_OPS[((a >> 29) & 0xff) % ALL_OPS.size()];
    s.alpha_ref = unorm8::from_raw(static_cast<uint32_t>(a >> 37));
    s.stencil_ref = stencil8::from_raw(static_cast<uint32_t>(a >> 45));
    s.stencil_value_mask = static_cast<uint8_t>(a >> 53);
    s.stencil_write_mask = static_cast<uint8_t>(b);
    std::vector<FragmentTestInput> fragments(random_batch_length(b >> 8));
    for (FragmentTestInput& in : fragments) {
      const uint64_t f = rng();
      in.alpha = unorm8::from_raw(static_cast<uint32_t>(f >> 8));
      in.stored_stencil = stencil8::from_raw(static_cast<uint32_t>(f >> 16));
      in.depth = unorm24::from_raw(static_cast<uint32_t>(f >> 24));
      // A quarter of the vectors compare equal values, which random ones never would.
      in.stored_depth = ((f >> 62) == 0) ? in.depth : unorm24::from_raw(static_cast<uint32_t>(rng()));
      if ((f >> 61) & 1) {
        in.alpha = s.alpha_ref;
      }
    }
    c.check(s, fragments);
  }
  report_cosim("fragment_tests", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
