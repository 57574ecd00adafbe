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

// The GL compare function `func` of two codes (incoming on the left).
constexpr bool compare(CompareFunc func, uint32_t incoming, uint32_t stored) {
  const unsigned code = static_cast<unsigned>(func);
  const unsigned order = unsigned{incoming >= stored} + unsigned{incoming > stored};  // 0 <, 1 ==, 2 >
  return ((code >> order) & unsigned{code < 8}) & 1;
}

namespace fragment_tests_detail {
constexpr bool compare_matches_table() {
  for (unsigned code = 0; code < 256; ++code)
    for (uint32_t a = 0; a < 3; ++a)
      for (uint32_t b = 0; b < 3; ++b)
        if (compare(static_cast<CompareFunc>(code), a, b) != compare_passes(static_cast<CompareFunc>(code), a, b))
          return false;
  return true;
}
static_assert(compare_matches_table(), "the compare codes are no longer GL's bit pattern");
}  // namespace fragment_tests_detail

constexpr bool alpha_test(CompareFunc func, unorm8 alpha, unorm8 ref) {
  return compare(func, alpha.raw, ref.raw);
}

constexpr bool depth_test(CompareFunc func, unorm24 incoming, unorm24 stored) {
  return compare(func, incoming.raw, stored.raw);
}

constexpr bool stencil_test(CompareFunc func, stencil8 ref, uint8_t value_mask, stencil8 stored) {
  return compare(func, ref.raw & value_mask, stored.raw & value_mask);
}

// stencil_op_result of common/fixed_function.h without a branch: the eight
// codes' results side by side, the code picks one (codes above 7 keep).
constexpr stencil8 stencil_update(StencilOp op, stencil8 stored, stencil8 ref, uint8_t write_mask) {
  const uint32_t s = stored.raw & 0xff;
  const uint32_t results[8] = {s, 0, ref.raw & 0xff, s + uint32_t{s != 0xff}, s - uint32_t{s != 0}, ~s & 0xff, s, s};
  const unsigned code = static_cast<unsigned>(op);
  const uint32_t result = results[code & 7] & (code < 8 ? 0xffu : 0u);
  const uint32_t kept = code < 8 ? 0u : s;
  return stencil8::from_raw((s & ~uint32_t{write_mask}) | ((result | kept) & write_mask));
}

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
constexpr FragmentTestResult run_fragment_tests(const FragmentTestState& state, const FragmentTestInput& in) {
  FragmentTestResult r;
  r.alpha_pass = !state.alpha_enable || alpha_test(state.alpha_func, in.alpha, state.alpha_ref);
  r.stencil_pass = !state.stencil_enable ||
                   stencil_test(state.stencil_func, state.stencil_ref, state.stencil_value_mask, in.stored_stencil);
  r.depth_pass = !state.depth_enable || depth_test(state.depth_func, in.depth, in.stored_depth);
  r.pass = r.alpha_pass & r.stencil_pass & r.depth_pass;

  // sfail, dpfail or dppass, then the update through the write mask; kept
  // when the alpha test failed or the stencil test is off.
  const StencilOp op = !r.stencil_pass ? state.sfail : (!r.depth_pass ? state.dpfail : state.dppass);
  const stencil8 updated = stencil_update(op, in.stored_stencil, state.stencil_ref, state.stencil_write_mask);
  r.stencil = (r.alpha_pass & state.stencil_enable) ? updated : in.stored_stencil;
  r.depth_write = r.pass & state.depth_enable & state.depth_write_mask;
  return r;
}

}  // namespace tessera::raster
