// See fragment_tests.h for the GL rules implemented here.
#include "fragment_tests.h"

namespace tessera::raster {

bool compare(CompareFunc func, uint32_t incoming, uint32_t stored) {
  return compare_passes(func, incoming, stored);
}

bool alpha_test(CompareFunc func, unorm8 alpha, unorm8 ref) {
  return compare(func, alpha.raw, ref.raw);
}

bool depth_test(CompareFunc func, unorm24 incoming, unorm24 stored) {
  return compare(func, incoming.raw, stored.raw);
}

bool stencil_test(CompareFunc func, stencil8 ref, uint8_t value_mask, stencil8 stored) {
  return compare(func, ref.raw & value_mask, stored.raw & value_mask);
}

stencil8 stencil_update(StencilOp op, stencil8 stored, stencil8 ref, uint8_t write_mask) {
  return stencil8::from_raw(
      stencil_op_result(op, static_cast<uint8_t>(stored.raw), static_cast<uint8_t>(ref.raw), write_mask));
}

FragmentTestResult run_fragment_tests(const FragmentTestState& state, const FragmentTestInput& in) {
  FragmentTestResult r;
  r.alpha_pass = !state.alpha_enable || alpha_test(state.alpha_func, in.alpha, state.alpha_ref);
  r.stencil_pass = !state.stencil_enable ||
                   stencil_test(state.stencil_func, state.stencil_ref, state.stencil_value_mask, in.stored_stencil);
  r.depth_pass = !state.depth_enable || depth_test(state.depth_func, in.depth, in.stored_depth);
  r.pass = r.alpha_pass && r.stencil_pass && r.depth_pass;

  r.stencil = in.stored_stencil;
  if (r.alpha_pass && state.stencil_enable) {
    const StencilOp op = !r.stencil_pass ? state.sfail : (!r.depth_pass ? state.dpfail : state.dppass);
    r.stencil = stencil_update(op, in.stored_stencil, state.stencil_ref, state.stencil_write_mask);
  }
  r.depth_write = r.pass && state.depth_enable && state.depth_write_mask;
  return r;
}

}  // namespace tessera::raster
