// See fragment_tests.h for the GL rules implemented here.
#include "fragment_tests.h"

namespace tessera::raster {

uint8_t compare_func_code(CompareFunc func) {
  return static_cast<uint8_t>(static_cast<uint16_t>(func) - 0x0200) & 7;
}

uint8_t stencil_op_code(StencilOp op) {
  switch (op) {
    case StencilOp::KEEP: return 0;
    case StencilOp::ZERO: return 1;
    case StencilOp::REPLACE: return 2;
    case StencilOp::INCR: return 3;
    case StencilOp::DECR: return 4;
    case StencilOp::INVERT: return 5;
  }
  return 7;  // undefined: the Verilog unit keeps the value, as stencil_update does
}

bool compare(CompareFunc func, uint32_t incoming, uint32_t stored) {
  switch (func) {
    case CompareFunc::NEVER: return false;
    case CompareFunc::LESS: return incoming < stored;
    case CompareFunc::EQUAL: return incoming == stored;
    case CompareFunc::LEQUAL: return incoming <= stored;
    case CompareFunc::GREATER: return incoming > stored;
    case CompareFunc::NOTEQUAL: return incoming != stored;
    case CompareFunc::GEQUAL: return incoming >= stored;
    case CompareFunc::ALWAYS: return true;
  }
  return false;
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
  uint32_t result = stored.raw;
  switch (op) {
    case StencilOp::KEEP: break;
    case StencilOp::ZERO: result = 0; break;
    case StencilOp::REPLACE: result = ref.raw; break;
    case StencilOp::INCR: result = stored.raw == 0xff ? 0xff : stored.raw + 1; break;
    case StencilOp::DECR: result = stored.raw == 0 ? 0 : stored.raw - 1; break;
    case StencilOp::INVERT: result = ~stored.raw & 0xff; break;
  }
  return stencil8::from_raw((stored.raw & ~uint32_t{write_mask}) | (result & write_mask));
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
