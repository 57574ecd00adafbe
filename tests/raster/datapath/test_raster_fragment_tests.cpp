// Unit tests of the per-fragment tests (tlm/raster/datapath/fragment_tests.h).
#include <gtest/gtest.h>

#include <array>

#include "raster/datapath/fragment_tests.h"

namespace tessera::raster {
namespace {

constexpr std::array<CompareFunc, 8> ALL_FUNCS{CompareFunc::never,  CompareFunc::less,    CompareFunc::equal,
                                               CompareFunc::lequal, CompareFunc::greater, CompareFunc::notequal,
                                               CompareFunc::gequal, CompareFunc::always};

TEST(FragmentTests, CompareFunctionsAreCodedInGlOrder) {
  EXPECT_EQ(gl_enum_of(CompareFunc::never), 0x0200u);
  EXPECT_EQ(gl_enum_of(StencilOp::keep), 0x1E00u);
  EXPECT_EQ(gl_enum_of(StencilOp::invert), 0x150Au);
  for (size_t i = 0; i < ALL_FUNCS.size(); ++i) {
    EXPECT_EQ(code_of(ALL_FUNCS[i]), i);
    EXPECT_EQ(gl_enum_of(ALL_FUNCS[i]), 0x0200u + i);
  }
}

TEST(FragmentTests, DepthCompareTruthTable) {
  // Expected results for incoming < stored, ==, > in GL order NEVER..ALWAYS.
  const std::array<std::array<bool, 3>, 8> table{{{false, false, false},
                                                  {true, false, false},
                                                  {false, true, false},
                                                  {true, true, false},
                                                  {false, false, true},
                                                  {true, false, true},
                                                  {false, true, true},
                                                  {true, true, true}}};
  const unorm24 mid = unorm24::from_raw(0x800000);
  for (size_t f = 0; f < 8; ++f) {
    EXPECT_EQ(depth_test_passes(ALL_FUNCS[f], unorm24::from_raw(0x7fffff), mid), table[f][0]) << f;
    EXPECT_EQ(depth_test_passes(ALL_FUNCS[f], mid, mid), table[f][1]) << f;
    EXPECT_EQ(depth_test_passes(ALL_FUNCS[f], unorm24::from_raw(0x800001), mid), table[f][2]) << f;
  }
  EXPECT_FALSE(depth_test_passes(CompareFunc::less, mid, mid));
  EXPECT_TRUE(depth_test_passes(CompareFunc::less, unorm24::from_raw(0), unorm24::from_raw(0xffffff)));
  EXPECT_FALSE(depth_test_passes(CompareFunc::greater, unorm24::from_raw(0xffffff), unorm24::from_raw(0xffffff)));
}

TEST(FragmentTests, AlphaCompareAgainstReference) {
  EXPECT_TRUE(alpha_test_passes(CompareFunc::gequal, unorm8{128}, unorm8{128}));
  EXPECT_FALSE(alpha_test_passes(CompareFunc::greater, unorm8{128}, unorm8{128}));
  EXPECT_TRUE(alpha_test_passes(CompareFunc::greater, unorm8{129}, unorm8{128}));
  EXPECT_FALSE(alpha_test_passes(CompareFunc::less, unorm8{0}, unorm8{0}));
}

TEST(FragmentTests, StencilCompareUsesValueMaskOnBothSides) {
  // ref 0x13 & 0x0f = 3, stored 0xf3 & 0x0f = 3: EQUAL despite different high bits.
  EXPECT_TRUE(stencil_test_passes(CompareFunc::equal, stencil8{0x13}, 0x0f, stencil8{0xf3}));
  EXPECT_FALSE(stencil_test_passes(CompareFunc::equal, stencil8{0x13}, 0xff, stencil8{0xf3}));
  // GL: LESS passes when ref < stored.
  EXPECT_TRUE(stencil_test_passes(CompareFunc::less, stencil8{1}, 0xff, stencil8{2}));
  EXPECT_FALSE(stencil_test_passes(CompareFunc::less, stencil8{2}, 0xff, stencil8{1}));
  // Mask 0: everything compares equal.
  EXPECT_TRUE(stencil_test_passes(CompareFunc::equal, stencil8{0xaa}, 0x00, stencil8{0x55}));
}

TEST(FragmentTests, StencilOperationsSaturateAndMask) {
  const stencil8 ref{0x5a};
  EXPECT_EQ(stencil_update(StencilOp::keep, stencil8{0x12}, ref, 0xff).raw, 0x12u);
  EXPECT_EQ(stencil_update(StencilOp::zero, stencil8{0x12}, ref, 0xff).raw, 0x00u);
  EXPECT_EQ(stencil_update(StencilOp::replace, stencil8{0x12}, ref, 0xff).raw, 0x5au);
  EXPECT_EQ(stencil_update(StencilOp::incr, stencil8{0x12}, ref, 0xff).raw, 0x13u);
  EXPECT_EQ(stencil_update(StencilOp::incr, stencil8{0xff}, ref, 0xff).raw, 0xffu);
  EXPECT_EQ(stencil_update(StencilOp::decr, stencil8{0x12}, ref, 0xff).raw, 0x11u);
  EXPECT_EQ(stencil_update(StencilOp::decr, stencil8{0x00}, ref, 0xff).raw, 0x00u);
  EXPECT_EQ(stencil_update(StencilOp::invert, stencil8{0x12}, ref, 0xff).raw, 0xedu);
  // Write mask 0x0f: only the low nibble changes.
  EXPECT_EQ(stencil_update(StencilOp::invert, stencil8{0x12}, ref, 0x0f).raw, 0x1du);
  EXPECT_EQ(stencil_update(StencilOp::replace, stencil8{0xf0}, ref, 0x0f).raw, 0xfau);
  EXPECT_EQ(stencil_update(StencilOp::incr, stencil8{0x0f}, ref, 0x0f).raw, 0x00u);  // 0x10 masked
  EXPECT_EQ(stencil_update(StencilOp::zero, stencil8{0xff}, ref, 0x00).raw, 0xffu);
}

TEST(FragmentTests, SequenceFollowsGl) {
  FragmentTestState s;
  s.alpha_enable = true;
  s.alpha_func = CompareFunc::greater;
  s.alpha_ref = unorm8{100};
  s.stencil_enable = true;
  s.stencil_func = CompareFunc::equal;
  s.stencil_ref = stencil8{1};
  s.sfail = StencilOp::incr;
  s.dpfail = StencilOp::zero;
  s.dppass = StencilOp::replace;
  s.depth_enable = true;
  s.depth_func = CompareFunc::less;
  FragmentTestInput in{unorm8{200}, unorm24{10}, unorm24{20}, stencil8{1}};

  FragmentTestResult r = run_fragment_tests(s, in);
  EXPECT_TRUE(r.pass);
  EXPECT_TRUE(r.depth_write);
  EXPECT_EQ(r.stencil.raw, 1u);  // REPLACE with ref 1

  in.depth = unorm24{30};  // depth fails: dpfail
  r = run_fragment_tests(s, in);
  EXPECT_FALSE(r.pass);
  EXPECT_FALSE(r.depth_write);
  EXPECT_EQ(r.stencil.raw, 0u);

  in.stored_stencil = stencil8{7};  // stencil fails: sfail
  r = run_fragment_tests(s, in);
  EXPECT_FALSE(r.stencil_pass);
  EXPECT_EQ(r.stencil.raw, 8u);

  in.alpha = unorm8{100};  // alpha fails: nothing changes
  r = run_fragment_tests(s, in);
  EXPECT_FALSE(r.alpha_pass);
  EXPECT_EQ(r.stencil.raw, 7u);
  EXPECT_FALSE(r.depth_write);

  // Depth test disabled: counts as passed for the stencil (dppass), never written.
  s.alpha_enable = false;
  s.depth_enable = false;
  in = FragmentTestInput{unorm8{0}, unorm24{30}, unorm24{20}, stencil8{1}};
  s.dppass = StencilOp::invert;
  r = run_fragment_tests(s, in);
  EXPECT_TRUE(r.pass);
  EXPECT_FALSE(r.depth_write);
  EXPECT_EQ(r.stencil.raw, 0xfeu);

  // Stencil test disabled: stencil untouched whatever the ops say.
  s.stencil_enable = false;
  s.depth_enable = true;
  s.depth_write_mask = false;
  in.depth = unorm24{10};
  r = run_fragment_tests(s, in);
  EXPECT_TRUE(r.pass);
  EXPECT_FALSE(r.depth_write);  // masked
  EXPECT_EQ(r.stencil.raw, 1u);
}

}  // namespace
}  // namespace tessera::raster
