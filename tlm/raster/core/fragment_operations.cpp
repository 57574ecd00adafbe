// See fragment_operations.h for why this is its own translation unit.
#include "raster/core/fragment_operations.h"

#include "raster/datapath/blend_logic_op.h"
#include "raster/datapath/fragment_tests.h"

namespace tessera::raster {

FragmentOperationsResult fragment_tests_only(const FragmentOperationsState& state, unorm8 alpha, unorm24 depth,
                                             unorm24 stored_depth, stencil8 stored_stencil) {
  FragmentTestState tests;
  tests.depth_enable = state.depth_test;
  tests.depth_func = state.depth_func;
  tests.depth_write_mask = state.depth_write;
  tests.alpha_enable = state.alpha_test;
  tests.alpha_func = state.alpha_func;
  tests.alpha_ref = unorm8::from_raw(state.alpha_ref);
  tests.stencil_enable = state.stencil_test;
  tests.stencil_func = state.stencil_func;
  tests.stencil_ref = stencil8::from_raw(state.stencil_ref);
  tests.stencil_value_mask = state.stencil_value_mask;
  tests.stencil_write_mask = state.stencil_write_mask;
  tests.sfail = state.stencil_fail;
  tests.dpfail = state.depth_fail;
  tests.dppass = state.depth_pass;

  const FragmentTestResult tested = run_fragment_tests(tests, {alpha, depth, stored_depth, stored_stencil});
  FragmentOperationsResult result;
  result.pass = tested.pass;
  result.depth_write = tested.depth_write;
  result.stencil = uint8_t(tested.stencil.raw);
  return result;
}

Rgba8 fragment_color_update(const FragmentOperationsState& state, Rgba8 fragment, Rgba8 stored_color) {
  // Neither blending nor a logic op and every channel writable: the unit
  // passes the fragment (blend_logic_op.h), so the branch-free unit, which
  // computes every factor, is not needed. The state is the triangle's, so
  // this branch is predicted.
  if (!state.blend && !state.logic_op && (state.color_mask & COLOR_MASK_ALL) == COLOR_MASK_ALL) return fragment;
  BlendState blending;
  blending.blend_enable = state.blend;
  blending.src_factor = state.blend_src;
  blending.dst_factor = state.blend_dst;
  blending.logic_op_enable = state.logic_op;
  blending.op = state.logic_op_mode;
  blending.color_mask = uint8_t(state.color_mask & COLOR_MASK_ALL);
  return blend_logic_op(blending, fragment, stored_color);
}

}  // namespace tessera::raster
