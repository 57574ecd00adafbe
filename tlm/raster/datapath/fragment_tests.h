// Per-fragment tests of OpenGL 1.2 ("Per-Fragment Operations"): alpha test,
// stencil test and stencil update, depth test.
//
// Formats (rasterizer interface): alpha and its reference unorm 0.8, depth
// unorm 0.24, stencil 8.0. All comparisons are exact integer comparisons of
// the codes (no rounding anywhere in this block).
//
// Compare functions and stencil operations are the codes of
// common/fixed_function.def (CompareFunc, StencilOp), the numbers the Verilog
// unit's 3-bit fields take. The incoming quantity is on the left, as in the
// GL spec:
//   alpha    alpha_fragment  func  alpha_ref
//   stencil  (ref & value_mask)  func  (stored & value_mask)
//   depth    z_fragment  func  z_stored
// INCR and DECR saturate at 255 and 0 (GL 1.2 has no wrapping variants); a
// stencil code without an entry (6, 7) keeps the stored value.
// The result is written through the stencil write mask:
//   new = (stored & ~write_mask) | (op(stored) & write_mask).
//
// Sequence (GL 1.2 alpha, stencil and depth buffer tests):
//   - a disabled test passes;
//   - a fragment that fails the alpha test is discarded and changes nothing;
//   - with the stencil test enabled, a stencil failure applies sfail, else a
//     depth failure applies dpfail, else dppass (with the depth test
//     disabled the fragment counts as passing it, so dppass applies); with
//     the stencil test disabled the stencil buffer is left alone;
//   - the depth buffer is written (with the fragment's z) only when the depth
//     test is enabled, the depth write mask is set and every test passed.
#pragma once

#include <cstdint>

#include "common/fixed_function.h"
#include "fixed_point.h"

namespace tessera::raster {

bool compare(CompareFunc func, uint32_t incoming, uint32_t stored);
bool alpha_test(CompareFunc func, unorm8 alpha, unorm8 ref);
bool depth_test(CompareFunc func, unorm24 incoming, unorm24 stored);
bool stencil_test(CompareFunc func, stencil8 ref, uint8_t value_mask, stencil8 stored);
stencil8 stencil_update(StencilOp op, stencil8 stored, stencil8 ref, uint8_t write_mask);

struct FragmentTestState {
  bool alpha_enable = false;
  CompareFunc alpha_func = CompareFunc::always;
  unorm8 alpha_ref;
  bool stencil_enable = false;
  CompareFunc stencil_func = CompareFunc::always;
  stencil8 stencil_ref;
  uint8_t stencil_value_mask = 0xff;
  uint8_t stencil_write_mask = 0xff;
  StencilOp sfail = StencilOp::keep;
  StencilOp dpfail = StencilOp::keep;
  StencilOp dppass = StencilOp::keep;
  bool depth_enable = false;
  CompareFunc depth_func = CompareFunc::less;
  bool depth_write_mask = true;
};

struct FragmentTestInput {
  unorm8 alpha;
  unorm24 depth;
  unorm24 stored_depth;
  stencil8 stored_stencil;
};

struct FragmentTestResult {
  bool alpha_pass = false;
  bool stencil_pass = false;
  bool depth_pass = false;
  bool pass = false;         // all three: the fragment goes on to blending
  stencil8 stencil;          // value to store (the old one when unchanged)
  bool depth_write = false;  // store the fragment's depth
};

// Everything the Verilog unit fragment_tests.sv computes, in one call.
FragmentTestResult run_fragment_tests(const FragmentTestState& state, const FragmentTestInput& in);

}  // namespace tessera::raster
