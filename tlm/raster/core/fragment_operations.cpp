// See fragment_operations.h.
#include "raster/core/fragment_operations.h"

#include <algorithm>

#include "raster/datapath/blend_logic_op.h"

namespace tessera::raster {

void fragment_tests(const FragmentOperationsState& state, const uint32_t* alpha, const uint32_t* depth,
                    const uint32_t* stored_depth, const uint32_t* stored_stencil, unsigned count, uint32_t* flags,
                    uint32_t* stencil) {
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
  run_fragment_tests_batch(tests, {alpha, depth, stored_depth, stored_stencil}, count, {flags, stencil});
}

void fragment_color_update(const FragmentOperationsState& state, const uint32_t* fragment, const uint32_t* stored,
                           unsigned count, uint32_t* out) {
  // Neither blending nor a logic op and every channel writable: the unit
  // passes the fragment (blend_logic_op.h), so the unit, which computes
  // every factor, is not needed.
  if (!state.blend && !state.logic_op && (state.color_mask & COLOR_MASK_ALL) == COLOR_MASK_ALL) {
    std::copy(fragment, fragment + count, out);
    return;
  }
  BlendState blending;
  blending.blend_enable = state.blend;
  blending.src_factor = state.blend_src;
  blending.dst_factor = state.blend_dst;
  blending.logic_op_enable = state.logic_op;
  blending.op = state.logic_op_mode;
  blending.color_mask = uint8_t(state.color_mask & COLOR_MASK_ALL);
  blend_logic_op_batch(blending, fragment, stored, count, out);
}

}  // namespace tessera::raster
