// See fragment_operations.h for why this is its own translation unit.
#include "raster/core/fragment_operations.h"

#include "raster/datapath/blend_logic_op.h"
#include "raster/datapath/fragment_tests.h"

namespace tessera::raster {

FragmentOperationsResult fragment_operations(const FragmentOperationsState& state, Rgba8 fragment, unorm24 depth,
                                             Rgba8 stored_color, unorm24 stored_depth, stencil8 stored_stencil) {
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

  const FragmentTestResult tested = run_fragment_tests(tests, {fragment.a, depth, stored_depth, stored_stencil});
  FragmentOperationsResult result;
  result.pass = tested.pass;
  result.depth_write = tested.depth_write;
  result.stencil = uint8_t(tested.stencil.raw);
  result.color = stored_color;
  if (!tested.pass) return result;

  BlendState blending;
  blending.blend_enable = state.blend;
  blending.src_factor = state.blend_src;
  blending.dst_factor = state.blend_dst;
  blending.logic_op_enable = state.logic_op;
  blending.op = state.logic_op_mode;
  blending.color_mask = uint8_t(state.color_mask & COLOR_MASK_ALL);
  result.color = blend_logic_op(blending, fragment, stored_color);
  return result;
}

}  // namespace tessera::raster
