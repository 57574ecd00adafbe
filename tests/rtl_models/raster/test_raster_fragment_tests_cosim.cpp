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

  // Every compare function on every test against below/equal/above at the
  // format extremes, and every stencil operation in every slot.
  const std::array<uint32_t, 3> alpha_refs{0, 128, 255};
  const std::array<uint32_t, 5> depths{0, 1, 0x7fffff, 0xfffffe, 0xffffff};
  const std::array<uint32_t, 4> stencils{0, 1, 0x80, 0xff};
  for (CompareFunc af : ALL_COMPARE_FUNCS)
    for (CompareFunc sf : ALL_COMPARE_FUNCS)
      for (CompareFunc df : ALL_COMPARE_FUNCS)
        for (StencilOp op : ALL_STENCIL_OPS)
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
              s.dpfail = ALL_STENCIL_OPS[(static_cast<size_t>(k) + 1) % ALL_STENCIL_OPS.size()];
              s.dppass = ALL_STENCIL_OPS[(static_cast<size_t>(k) + 2) % ALL_STENCIL_OPS.size()];
              s.depth_write_mask = k != 5;
              std::vector<FragmentTestInput> fragments;
              for (uint32_t v = 0; v < 5; ++v)
                fragments.push_back({unorm8{alpha_refs[v % 3]}, unorm24{depths[v]}, unorm24{depths[(v + k) % 5]},
                                     stencil8{stencils[(v + k) % 4]}});
              c.check(s, fragments);
            }
  const uint64_t corner_vectors = c.vectors;

  // States at random (raster_vectors.h), each with a batch of 1 to 64
  // fragments at random.
  VectorRng rng(0xf7a6);
  while (c.vectors - corner_vectors < RANDOM_VECTORS) {
    const FragmentTestState s = random_fragment_test_state(rng);
    std::vector<FragmentTestInput> fragments(random_batch_length(rng()));
    for (FragmentTestInput& in : fragments) in = random_fragment(rng, s);
    c.check(s, fragments);
  }
  report_cosim("fragment_tests", c, corner_vectors);
}

}  // namespace
}  // namespace tessera::raster
