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
CompareFunc to_compare_func(uint32_t code) {
  return static_cast<CompareFunc>(0x0200 + (code & 7));
}

StencilOp to_stencil_op(uint32_t code) {
  constexpr StencilOp OPS[] = {StencilOp::KEEP, StencilOp::ZERO, StencilOp::REPLACE,
                               StencilOp::INCR, StencilOp::DECR, StencilOp::INVERT};
  return code < std::size(OPS) ? OPS[code] : StencilOp::KEEP;
}

// gl::BlendFactor's order, which is not the order of the GL enum values.
BlendFactor to_blend_factor(uint32_t code) {
  constexpr BlendFactor FACTORS[] = {BlendFactor::ZERO,
                                     BlendFactor::ONE,
                                     BlendFactor::SRC_COLOR,
                                     BlendFactor::ONE_MINUS_SRC_COLOR,
                                     BlendFactor::DST_COLOR,
                                     BlendFactor::ONE_MINUS_DST_COLOR,
                                     BlendFactor::SRC_ALPHA,
                                     BlendFactor::ONE_MINUS_SRC_ALPHA,
                                     BlendFactor::DST_ALPHA,
                                     BlendFactor::ONE_MINUS_DST_ALPHA,
                                     BlendFactor::SRC_ALPHA_SATURATE};
  return code < std::size(FACTORS) ? FACTORS[code] : BlendFactor::ZERO;
}

}  // namespace

FragmentOperationsResult fragment_operations(const FragmentOperationsState& state, Rgba8 fragment, unorm24 depth,
                                             Rgba8 stored_color, unorm24 stored_depth, stencil8 stored_stencil) {
  FragmentTestState tests;
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

  const FragmentTestResult tested = run_fragment_tests(tests, {fragment.a, depth, stored_depth, stored_stencil});
  FragmentOperationsResult result;
  result.pass = tested.pass;
  result.depth_write = tested.depth_write;
  result.stencil = uint8_t(tested.stencil.raw);
  result.color = stored_color;
  if (!tested.pass) return result;

  BlendState blending;
  blending.blend_enable = state.blend;
  blending.src_factor = to_blend_factor(state.blend_func & 0xff);
  blending.dst_factor = to_blend_factor((state.blend_func >> 8) & 0xff);
  blending.logic_op_enable = state.logic_op;
  blending.op = static_cast<LogicOp>(0x1500 + ((state.blend_func >> 16) & 15));
  blending.color_mask = uint8_t(state.color_mask & COLOR_MASK_ALL);
  result.color = blend_logic_op(blending, fragment, stored_color);
  return result;
}

}  // namespace tessera::raster
