// Unit tests of the per-fragment tests (tlm/raster/datapath/fragment_tests.h).
#include <gtest/gtest.h>

#include <array>

#include "raster/datapath/fragment_tests.h"

namespace tessera::raster {
namespace {

constexpr std::array<compare_func, 8> ALL_FUNCS{compare_func::NEVER,   compare_func::LESS,     compare_func::EQUAL,
                                                compare_func::LEQUAL,  compare_func::GREATER,  compare_func::NOTEQUAL,
                                                compare_func::GEQUAL,  compare_func::ALWAYS};

TEST(FragmentTests, EnumsHaveGlValues) {
    EXPECT_EQ(static_cast<uint16_t>(compare_func::NEVER), 0x0200);
    EXPECT_EQ(static_cast<uint16_t>(compare_func::ALWAYS), 0x0207);
    EXPECT_EQ(static_cast<uint16_t>(stencil_op::KEEP), 0x1E00);
    EXPECT_EQ(static_cast<uint16_t>(stencil_op::INVERT), 0x150A);
    for (size_t i = 0; i < ALL_FUNCS.size(); ++i) {
        EXPECT_EQ(compare_func_code(ALL_FUNCS[i]), i);
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
        EXPECT_EQ(depth_test(ALL_FUNCS[f], unorm24::from_raw(0x7fffff), mid), table[f][0]) << f;
        EXPECT_EQ(depth_test(ALL_FUNCS[f], mid, mid), table[f][1]) << f;
        EXPECT_EQ(depth_test(ALL_FUNCS[f], unorm24::from_raw(0x800001), mid), table[f][2]) << f;
    }
    EXPECT_FALSE(depth_test(compare_func::LESS, mid, mid));
    EXPECT_TRUE(depth_test(compare_func::LESS, unorm24::from_raw(0), unorm24::from_raw(0xffffff)));
    EXPECT_FALSE(depth_test(compare_func::GREATER, unorm24::from_raw(0xffffff), unorm24::from_raw(0xffffff)));
}

TEST(FragmentTests, AlphaCompareAgainstReference) {
    EXPECT_TRUE(alpha_test(compare_func::GEQUAL, unorm8{128}, unorm8{128}));
    EXPECT_FALSE(alpha_test(compare_func::GREATER, unorm8{128}, unorm8{128}));
    EXPECT_TRUE(alpha_test(compare_func::GREATER, unorm8{129}, unorm8{128}));
    EXPECT_FALSE(alpha_test(compare_func::LESS, unorm8{0}, unorm8{0}));
}

TEST(FragmentTests, StencilCompareUsesValueMaskOnBothSides) {
    // ref 0x13 & 0x0f = 3, stored 0xf3 & 0x0f = 3: EQUAL despite different high bits.
    EXPECT_TRUE(stencil_test(compare_func::EQUAL, stencil8{0x13}, 0x0f, stencil8{0xf3}));
    EXPECT_FALSE(stencil_test(compare_func::EQUAL, stencil8{0x13}, 0xff, stencil8{0xf3}));
    // GL: LESS passes when ref < stored.
    EXPECT_TRUE(stencil_test(compare_func::LESS, stencil8{1}, 0xff, stencil8{2}));
    EXPECT_FALSE(stencil_test(compare_func::LESS, stencil8{2}, 0xff, stencil8{1}));
    // Mask 0: everything compares equal.
    EXPECT_TRUE(stencil_test(compare_func::EQUAL, stencil8{0xaa}, 0x00, stencil8{0x55}));
}

TEST(FragmentTests, StencilOperationsSaturateAndMask) {
    const stencil8 ref{0x5a};
    EXPECT_EQ(stencil_update(stencil_op::KEEP, stencil8{0x12}, ref, 0xff).raw, 0x12u);
    EXPECT_EQ(stencil_update(stencil_op::ZERO, stencil8{0x12}, ref, 0xff).raw, 0x00u);
    EXPECT_EQ(stencil_update(stencil_op::REPLACE, stencil8{0x12}, ref, 0xff).raw, 0x5au);
    EXPECT_EQ(stencil_update(stencil_op::INCR, stencil8{0x12}, ref, 0xff).raw, 0x13u);
    EXPECT_EQ(stencil_update(stencil_op::INCR, stencil8{0xff}, ref, 0xff).raw, 0xffu);
    EXPECT_EQ(stencil_update(stencil_op::DECR, stencil8{0x12}, ref, 0xff).raw, 0x11u);
    EXPECT_EQ(stencil_update(stencil_op::DECR, stencil8{0x00}, ref, 0xff).raw, 0x00u);
    EXPECT_EQ(stencil_update(stencil_op::INVERT, stencil8{0x12}, ref, 0xff).raw, 0xedu);
    // Write mask 0x0f: only the low nibble changes.
    EXPECT_EQ(stencil_update(stencil_op::INVERT, stencil8{0x12}, ref, 0x0f).raw, 0x1du);
    EXPECT_EQ(stencil_update(stencil_op::REPLACE, stencil8{0xf0}, ref, 0x0f).raw, 0xfau);
    EXPECT_EQ(stencil_update(stencil_op::INCR, stencil8{0x0f}, ref, 0x0f).raw, 0x00u); // 0x10 masked
    EXPECT_EQ(stencil_update(stencil_op::ZERO, stencil8{0xff}, ref, 0x00).raw, 0xffu);
}

TEST(FragmentTests, SequenceFollowsGl) {
    fragment_test_state s;
    s.alpha_enable = true;
    s.alpha_func = compare_func::GREATER;
    s.alpha_ref = unorm8{100};
    s.stencil_enable = true;
    s.stencil_func = compare_func::EQUAL;
    s.stencil_ref = stencil8{1};
    s.sfail = stencil_op::INCR;
    s.dpfail = stencil_op::ZERO;
    s.dppass = stencil_op::REPLACE;
    s.depth_enable = true;
    s.depth_func = compare_func::LESS;
    fragment_test_input in{unorm8{200}, unorm24{10}, unorm24{20}, stencil8{1}};

    fragment_test_result r = run_fragment_tests(s, in);
    EXPECT_TRUE(r.pass);
    EXPECT_TRUE(r.depth_write);
    EXPECT_EQ(r.stencil.raw, 1u); // REPLACE with ref 1

    in.depth = unorm24{30}; // depth fails: dpfail
    r = run_fragment_tests(s, in);
    EXPECT_FALSE(r.pass);
    EXPECT_FALSE(r.depth_write);
    EXPECT_EQ(r.stencil.raw, 0u);

    in.stored_stencil = stencil8{7}; // stencil fails: sfail
    r = run_fragment_tests(s, in);
    EXPECT_FALSE(r.stencil_pass);
    EXPECT_EQ(r.stencil.raw, 8u);

    in.alpha = unorm8{100}; // alpha fails: nothing changes
    r = run_fragment_tests(s, in);
    EXPECT_FALSE(r.alpha_pass);
    EXPECT_EQ(r.stencil.raw, 7u);
    EXPECT_FALSE(r.depth_write);

    // Depth test disabled: counts as passed for the stencil (dppass), never written.
    s.alpha_enable = false;
    s.depth_enable = false;
    in = fragment_test_input{unorm8{0}, unorm24{30}, unorm24{20}, stencil8{1}};
    s.dppass = stencil_op::INVERT;
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
    EXPECT_FALSE(r.depth_write); // masked
    EXPECT_EQ(r.stencil.raw, 1u);
}

} // namespace
} // namespace tessera::raster
