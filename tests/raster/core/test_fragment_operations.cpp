// The per-fragment operations (tlm/raster/core/fragment_operations.h) on
// single fragments: the depth test's eight functions, the stencil test and
// its three ops through the write mask, the alpha test, blending, the logic
// op and the colour mask. Expected values follow GL 1.2's per-fragment
// operations as datapath/fragment_tests.h and blend_logic_op.h state them:
// the incoming value on the left of the compare function, stencil
// (ref & mask) func (stored & mask), new stencil = (stored & ~write_mask) |
// (op & write_mask), INCR and DECR saturating; blend factors on 0.8 codes
// with mul(a, b) = round(a b / 255) and the sum saturated at 255.
#include <gtest/gtest.h>

#include <vector>

#include "raster/core/fragment_operations.h"

using namespace tessera::raster;
using tessera::BlendFactor;
using tessera::CompareFunc;
using tessera::LogicOp;
using tessera::StencilOp;

namespace {

struct Fragment {
  uint32_t alpha = 255, depth = 0, stored_depth = 0, stored_stencil = 0;
};
struct Outcome {
  uint32_t flags, stencil;
};

std::vector<Outcome> test_fragments(const FragmentOperationsState& state, const std::vector<Fragment>& fragments) {
  const unsigned n = unsigned(fragments.size());
  std::vector<uint32_t> alpha(n), depth(n), stored_depth(n), stored_stencil(n), flags(n), stencil(n);
  for (unsigned i = 0; i < n; ++i) {
    alpha[i] = fragments[i].alpha;
    depth[i] = fragments[i].depth;
    stored_depth[i] = fragments[i].stored_depth;
    stored_stencil[i] = fragments[i].stored_stencil;
  }
  fragment_tests(state, alpha.data(), depth.data(), stored_depth.data(), stored_stencil.data(), n, flags.data(),
                 stencil.data());
  std::vector<Outcome> out;
  for (unsigned i = 0; i < n; ++i) out.push_back({flags[i], stencil[i]});
  return out;
}

bool passes(const Outcome& o) {
  return (o.flags & FRAGMENT_PASS) != 0;
}

TEST(FragmentOperations, DepthTestFunctionsCompareIncomingWithStored) {
  // Incoming just below, equal to and just above the stored 0x800000.
  const std::vector<Fragment> fragments = {
      {255, 0x7fffff, 0x800000, 0}, {255, 0x800000, 0x800000, 0}, {255, 0x800001, 0x800000, 0}};
  struct Case {
    CompareFunc func;
    bool below, equal, above;
  };
  const Case cases[] = {{CompareFunc::never, false, false, false},  {CompareFunc::less, true, false, false},
                        {CompareFunc::equal, false, true, false},   {CompareFunc::lequal, true, true, false},
                        {CompareFunc::greater, false, false, true}, {CompareFunc::notequal, true, false, true},
                        {CompareFunc::gequal, false, true, true},   {CompareFunc::always, true, true, true}};
  for (const Case& c : cases) {
    FragmentOperationsState state;
    state.depth_test = true;
    state.depth_func = c.func;
    const std::vector<Outcome> o = test_fragments(state, fragments);
    const bool expected[3] = {c.below, c.equal, c.above};
    for (unsigned i = 0; i < 3; ++i) {
      EXPECT_EQ((o[i].flags & FRAGMENT_DEPTH_PASS) != 0, expected[i]) << int(c.func) << " " << i;
      EXPECT_EQ(passes(o[i]), expected[i]) << int(c.func) << " " << i;
      // The depth is written where the test passed, with depth writes on.
      EXPECT_EQ((o[i].flags & FRAGMENT_DEPTH_WRITE) != 0, expected[i]) << int(c.func) << " " << i;
    }
  }
}

TEST(FragmentOperations, DepthIsWrittenOnlyWithTheTestAndTheWriteMask) {
  const std::vector<Fragment> one = {{255, 1, 2, 0}};
  FragmentOperationsState state;  // GL's defaults: depth test off, depth writes on
  EXPECT_TRUE(passes(test_fragments(state, one)[0]));
  EXPECT_EQ(test_fragments(state, one)[0].flags & FRAGMENT_DEPTH_WRITE, 0u);
  state.depth_test = true;
  EXPECT_NE(test_fragments(state, one)[0].flags & FRAGMENT_DEPTH_WRITE, 0u);
  state.depth_write = false;
  EXPECT_TRUE(passes(test_fragments(state, one)[0]));
  EXPECT_EQ(test_fragments(state, one)[0].flags & FRAGMENT_DEPTH_WRITE, 0u);
}

TEST(FragmentOperations, StencilOpsFollowTheTestsThroughTheWriteMask) {
  FragmentOperationsState state;
  state.stencil_test = true;
  state.stencil_func = CompareFunc::equal;
  state.stencil_ref = 5;
  state.stencil_value_mask = 0x0f;  // compares the low four bits
  state.depth_test = true;          // LESS
  state.stencil_fail = StencilOp::incr;
  state.depth_fail = StencilOp::decr;
  state.depth_pass = StencilOp::invert;
  const std::vector<Fragment> fragments = {
      {255, 0x100, 0x800000, 0x06},     // 6 != 5: stencil fails -> INCR: 7
      {255, 0x900000, 0x800000, 0x35},  // 0x35 & 0x0f = 5: passes; depth fails -> DECR: 0x34
      {255, 0x100, 0x800000, 0x35},     // both pass -> INVERT: 0xca
      {255, 0x100, 0x800000, 0xff},     // 15 != 5 -> INCR saturates: 0xff
      {255, 0x100, 0x800000, 0x00},     // 0 != 5 -> INCR: 1
  };
  std::vector<Outcome> o = test_fragments(state, fragments);
  EXPECT_EQ(o[0].stencil, 0x07u);
  EXPECT_EQ(o[1].stencil, 0x34u);
  EXPECT_EQ(o[2].stencil, 0xcau);
  EXPECT_EQ(o[3].stencil, 0xffu);
  EXPECT_EQ(o[4].stencil, 0x01u);
  EXPECT_EQ(o[0].flags & FRAGMENT_STENCIL_PASS, 0u);
  EXPECT_NE(o[1].flags & FRAGMENT_STENCIL_PASS, 0u);
  EXPECT_FALSE(passes(o[0]));
  EXPECT_FALSE(passes(o[1]));
  EXPECT_TRUE(passes(o[2]));
  // Write mask 0xf0: INVERT's 0xca only in the high bits: 0xc0 | 0x05.
  state.stencil_write_mask = 0xf0;
  o = test_fragments(state, fragments);
  EXPECT_EQ(o[2].stencil, 0xc5u);
  EXPECT_EQ(o[0].stencil, 0x06u);  // INCR's 0x07 differs only in the masked bits
  // ZERO, KEEP, REPLACE (the reference).
  state.stencil_write_mask = 0xff;
  state.stencil_fail = StencilOp::zero;
  state.depth_fail = StencilOp::keep;
  state.depth_pass = StencilOp::replace;
  o = test_fragments(state, fragments);
  EXPECT_EQ(o[0].stencil, 0x00u);
  EXPECT_EQ(o[1].stencil, 0x35u);
  EXPECT_EQ(o[2].stencil, 0x05u);
}

TEST(FragmentOperations, AFragmentFailingTheAlphaTestChangesNothing) {
  FragmentOperationsState state;
  state.alpha_test = true;
  state.alpha_func = CompareFunc::gequal;
  state.alpha_ref = 128;
  state.stencil_test = true;  // ALWAYS, but every op would change the stencil
  state.stencil_fail = state.depth_fail = state.depth_pass = StencilOp::invert;
  const std::vector<Outcome> o = test_fragments(state, {{127, 0, 0, 0x0f}, {128, 0, 0, 0x0f}});
  EXPECT_FALSE(passes(o[0]));
  EXPECT_EQ(o[0].flags & FRAGMENT_ALPHA_PASS, 0u);
  EXPECT_EQ(o[0].stencil, 0x0fu);
  EXPECT_TRUE(passes(o[1]));
  EXPECT_EQ(o[1].stencil, 0xf0u);
}

uint32_t rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return r | g << 8 | b << 16 | a << 24;
}

uint32_t update(const FragmentOperationsState& state, uint32_t fragment, uint32_t stored) {
  uint32_t out = 0;
  fragment_color_update(state, &fragment, &stored, 1, &out);
  return out;
}

TEST(FragmentOperations, BlendingSourceAlphaAndAdditiveSaturation) {
  FragmentOperationsState state;
  state.blend = true;
  state.blend_src = BlendFactor::src_alpha;
  state.blend_dst = BlendFactor::one_minus_src_alpha;
  // S = (200, 100, 0, 128), D = (0, 100, 255, 255); As = 128, 1 - As = 127:
  // R mul(200, 128) = round(100.39) = 100, + 0;
  // G mul(100, 128) = round(50.20) = 50, + mul(100, 127) = round(49.80) = 50;
  // B 0 + mul(255, 127) = 127; A mul(128, 128) = round(64.25) = 64, + 127.
  EXPECT_EQ(update(state, rgba(200, 100, 0, 128), rgba(0, 100, 255, 255)), rgba(100, 100, 127, 191));
  state.blend_src = state.blend_dst = BlendFactor::one;
  // 300, 300, 255, 383: saturated at 255.
  EXPECT_EQ(update(state, rgba(200, 100, 0, 128), rgba(100, 200, 255, 255)), rgba(255, 255, 255, 255));
  EXPECT_EQ(update(state, rgba(1, 2, 3, 4), rgba(10, 20, 30, 40)), rgba(11, 22, 33, 44));
}

TEST(FragmentOperations, ColourMaskKeepsTheStoredChannels) {
  FragmentOperationsState state;
  EXPECT_EQ(update(state, 0x44332211, 0xddccbbaa), 0x44332211u);  // no blend, every channel: the fragment
  state.color_mask = 5;                                           // R and B
  EXPECT_EQ(update(state, 0x44332211, 0xddccbbaa), 0xdd33bb11u);
  state.color_mask = 0;
  EXPECT_EQ(update(state, 0x44332211, 0xddccbbaa), 0xddccbbaau);
}

TEST(FragmentOperations, LogicOpTakesThePlaceOfBlending) {
  FragmentOperationsState state;
  state.logic_op = true;
  state.logic_op_mode = LogicOp::xor_;
  state.blend = true;  // bypassed while the logic op is on
  state.blend_src = state.blend_dst = BlendFactor::one;
  EXPECT_EQ(update(state, 0x0f0f0f0f, 0xff00ff00), 0xf00ff00fu);
  state.logic_op_mode = LogicOp::invert;  // ~d
  state.color_mask = 1;                   // R only
  EXPECT_EQ(update(state, 0x0f0f0f0f, 0xff00ff00), 0xff00ffffu);
}

}  // namespace
