// See fragment_operations.h for why this is its own translation unit.
#include "raster/core/fragment_operations.h"

#include <iterator>

#include "raster/datapath/blend_logic_op.h"
#include "raster/datapath/fragment_tests.h"

namespace tessera::raster {

namespace {

// Enumerations of gl/renderer.h (0-based) to the datapath's GL enum values.
// A field is cut to its hardware width; a code with no meaning takes the
// datapath's "unknown" behaviour (stencil KEEP, blend factor ZERO).
compare_func to_compare_func(uint32_t code) { return static_cast<compare_func>(0x0200 + (code & 7)); }

stencil_op to_stencil_op(uint32_t code) {
  constexpr stencil_op OPS[] = {stencil_op::KEEP, stencil_op::ZERO, stencil_op::REPLACE,
                                stencil_op::INCR, stencil_op::DECR, stencil_op::INVERT};
  return code < std::size(OPS) ? OPS[code] : stencil_op::KEEP;
}

// gl::BlendFactor's order, which is not the order of the GL enum values.
blend_factor to_blend_factor(uint32_t code) {
  constexpr blend_factor FACTORS[] = {blend_factor::ZERO,
                                      blend_factor::ONE,
                                      blend_factor::SRC_COLOR,
                                      blend_factor::ONE_MINUS_SRC_COLOR,
                                      blend_factor::DST_COLOR,
                                      blend_factor::ONE_MINUS_DST_COLOR,
                                      blend_factor::SRC_ALPHA,
                                      blend_factor::ONE_MINUS_SRC_ALPHA,
                                      blend_factor::DST_ALPHA,
                                      blend_factor::ONE_MINUS_DST_ALPHA,
                                      blend_factor::SRC_ALPHA_SATURATE};
  return code < std::size(FACTORS) ? FACTORS[code] : blend_factor::ZERO;
}

}  // namespace

FragmentOperationsResult fragment_operations(const FragmentOperationsState& state, rgba8 fragment, unorm24 depth,
                                             rgba8 stored_color, unorm24 stored_depth, stencil8 stored_stencil) {
  fragment_test_state tests;
  tests.depth_enable = state.depth_test;
  tests.depth_func = to_compare_func(state.depth_func);
  tests.depth_write_mask = state.depth_write;
  tests.alpha_enable = state.alpha_test;
  tests.alpha_func = to_compare_func(state.alpha_func & 0xff);
  tests.alpha_ref = unorm8::from_raw(state.alpha_func >> 8);
  tests.stencil_enable = state.stencil_test;
  tests.stencil_func = to_compare_func(state.stencil_func & 0xff);
  tests.stencil_ref = stencil8::from_raw(state.stencil_func >> 8);
  tests.stencil_value_mask = uint8_t(state.stencil_func >> 16);
  tests.stencil_write_mask = uint8_t(state.stencil_func >> 24);
  tests.sfail = to_stencil_op(state.stencil_ops & 0xff);
  tests.dpfail = to_stencil_op((state.stencil_ops >> 8) & 0xff);
  tests.dppass = to_stencil_op((state.stencil_ops >> 16) & 0xff);

  const fragment_test_result tested =
      run_fragment_tests(tests, {fragment.a, depth, stored_depth, stored_stencil});
  FragmentOperationsResult result;
  result.pass = tested.pass;
  result.depth_write = tested.depth_write;
  result.stencil = uint8_t(tested.stencil.raw);
  result.color = stored_color;
  if (!tested.pass) return result;

  blend_state blending;
  blending.blend_enable = state.blend;
  blending.src_factor = to_blend_factor(state.blend_func & 0xff);
  blending.dst_factor = to_blend_factor((state.blend_func >> 8) & 0xff);
  blending.logic_op_enable = state.logic_op;
  blending.op = static_cast<logic_op>(0x1500 + ((state.blend_func >> 16) & 15));
  blending.color_mask = uint8_t(state.color_mask & COLOR_MASK_ALL);
  result.color = blend_logic_op(blending, fragment, stored_color);
  return result;
}

}  // namespace tessera::raster
