// Per-fragment tests of OpenGL 1.2 ("Per-Fragment Operations"): alpha test,
// stencil test and stencil update, depth test. Inline and branch-free
// (fragment_test_bits); the batch form (run_fragment_tests_batch, batch.h)
// takes fragments under one state.
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

#include "batch.h"
#include "common/fixed_function.h"
#include "fixed_point.h"

namespace tessera::raster {

// The GL compare function `func` of two codes (incoming on the left), as 1
// or 0: bit 0 of the code passes "less", bit 1 "equal", bit 2 "greater".
// Conditional expressions rather than bools converted to integers, and no
// shift by a per-fragment amount: the forms the batch loop vectorises.
constexpr uint32_t compare_bit(CompareFunc func, uint32_t incoming, uint32_t stored) {
  const uint32_t code = static_cast<uint32_t>(func);
  const uint32_t less = incoming < stored ? 1u : 0u;
  const uint32_t greater = incoming > stored ? 1u : 0u;
  const uint32_t equal = 1u - less - greater;
  const uint32_t valid = code < 8 ? 1u : 0u;
  return ((less & code) | (equal & (code >> 1)) | (greater & (code >> 2))) & valid;
}

constexpr bool compare(CompareFunc func, uint32_t incoming, uint32_t stored) {
  return compare_bit(func, incoming, stored) != 0;
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

constexpr bool alpha_test_passes(CompareFunc func, unorm8 alpha, unorm8 ref) {
  return compare(func, alpha.raw, ref.raw);
}

constexpr bool depth_test_passes(CompareFunc func, unorm24 incoming, unorm24 stored) {
  return compare(func, incoming.raw, stored.raw);
}

constexpr bool stencil_test_passes(CompareFunc func, stencil8 ref, uint8_t value_mask, stencil8 stored) {
  return compare(func, ref.raw & value_mask, stored.raw & value_mask);
}

// stencil_op_result of common/fixed_function.h without a branch: the eight
// codes' results side by side, the code picks one (codes above 7 keep).
constexpr stencil8 stencil_update(StencilOp op, stencil8 stored, stencil8 ref, uint8_t write_mask) {
  const uint32_t s = stored.raw & 0xff;
  const uint32_t result = select_code<uint32_t>(static_cast<unsigned>(op), s, s, 0, ref.raw & 0xff,
                                                s + (s != 0xff ? 1u : 0u), s - (s != 0 ? 1u : 0u), ~s & 0xff);
  return stencil8::from_raw((s & ~uint32_t{write_mask}) | (result & write_mask));
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

// The results of run_fragment_tests as bits of one word.
constexpr uint32_t FRAGMENT_ALPHA_PASS = 1;
constexpr uint32_t FRAGMENT_STENCIL_PASS = 2;
constexpr uint32_t FRAGMENT_DEPTH_PASS = 4;
constexpr uint32_t FRAGMENT_PASS = 8;
constexpr uint32_t FRAGMENT_DEPTH_WRITE = 16;

struct FragmentTestBits {
  uint32_t flags;    // FRAGMENT_*
  uint32_t stencil;  // value to store (the old one when unchanged)
};

// The tests on integer codes (alpha 0.8, depth 0.24, stencil 8.0; the bits
// above a code's width are ignored), what run_fragment_tests and the batch
// form share. A disabled test passes by an OR with 1, the writes are
// enabled by an AND: no conditional depends on the state, so that the batch
// loop has no branch.
constexpr FragmentTestBits fragment_test_bits(const FragmentTestState& state, uint32_t alpha_code, uint32_t depth_code,
                                              uint32_t stored_depth_code, uint32_t stored_stencil_code) {
  const uint32_t stored_stencil = stored_stencil_code & 0xff;
  const uint32_t value_mask = state.stencil_value_mask;
  const uint32_t alpha_pass =
      compare_bit(state.alpha_func, alpha_code & 0xff, state.alpha_ref.raw) | uint32_t{!state.alpha_enable};
  const uint32_t stencil_pass =
      compare_bit(state.stencil_func, state.stencil_ref.raw & value_mask, stored_stencil & value_mask) |
      uint32_t{!state.stencil_enable};
  const uint32_t depth_pass = compare_bit(state.depth_func, depth_code & 0xffffff, stored_depth_code & 0xffffff) |
                              uint32_t{!state.depth_enable};
  const uint32_t pass = alpha_pass & stencil_pass & depth_pass;

  // sfail, dpfail or dppass, then the update through the write mask; kept
  // when the alpha test failed or the stencil test is off.
  const StencilOp op = stencil_pass == 0 ? state.sfail : (depth_pass == 0 ? state.dpfail : state.dppass);
  const uint32_t updated =
      stencil_update(op, stencil8::from_raw(stored_stencil), state.stencil_ref, state.stencil_write_mask).raw;
  const uint32_t update = alpha_pass & uint32_t{state.stencil_enable};
  const uint32_t depth_write = pass & uint32_t{state.depth_enable} & uint32_t{state.depth_write_mask};
  return {alpha_pass * FRAGMENT_ALPHA_PASS | stencil_pass * FRAGMENT_STENCIL_PASS | depth_pass * FRAGMENT_DEPTH_PASS |
              pass * FRAGMENT_PASS | depth_write * FRAGMENT_DEPTH_WRITE,
          update != 0 ? updated : stored_stencil};
}

// Everything the Verilog unit fragment_tests.sv computes, in one call.
constexpr FragmentTestResult run_fragment_tests(const FragmentTestState& state, const FragmentTestInput& in) {
  const FragmentTestBits bits =
      fragment_test_bits(state, in.alpha.raw, in.depth.raw, in.stored_depth.raw, in.stored_stencil.raw);
  FragmentTestResult r;
  r.alpha_pass = (bits.flags & FRAGMENT_ALPHA_PASS) != 0;
  r.stencil_pass = (bits.flags & FRAGMENT_STENCIL_PASS) != 0;
  r.depth_pass = (bits.flags & FRAGMENT_DEPTH_PASS) != 0;
  r.pass = (bits.flags & FRAGMENT_PASS) != 0;
  r.stencil = stencil8::from_raw(bits.stencil);
  r.depth_write = (bits.flags & FRAGMENT_DEPTH_WRITE) != 0;
  return r;
}

// Batch form (batch.h): `count` fragments under one state, each input and
// output field an array of 32-bit codes (no output array may overlap an
// input array).
struct FragmentTestBatchInput {
  const uint32_t* alpha;           // 0.8
  const uint32_t* depth;           // 0.24
  const uint32_t* stored_depth;    // 0.24
  const uint32_t* stored_stencil;  // 8.0
};
struct FragmentTestBatch {
  uint32_t* flags;    // FRAGMENT_*
  uint32_t* stencil;  // value to store
};

struct FragmentTestKernel {
  TESSERA_BATCH_KERNEL void run(const FragmentTestState& state, const FragmentTestBatchInput& in, unsigned count,
                                const FragmentTestBatch& out) {
    loop(state, in.alpha, in.depth, in.stored_depth, in.stored_stencil, count, out.flags, out.stencil);
  }
  // `state` by value: a copy that no store of the loop can change.
  TESSERA_BATCH_KERNEL void loop(const FragmentTestState state, const uint32_t* __restrict alpha,
                                 const uint32_t* __restrict depth, const uint32_t* __restrict stored_depth,
                                 const uint32_t* __restrict stored_stencil, unsigned count, uint32_t* __restrict flags,
                                 uint32_t* __restrict stencil) {
    for (unsigned i = 0; i < count; ++i) {
      const FragmentTestBits r = fragment_test_bits(state, alpha[i], depth[i], stored_depth[i], stored_stencil[i]);
      flags[i] = r.flags;
      stencil[i] = r.stencil;
    }
  }
};

void run_fragment_tests_batch(const FragmentTestState& state, const FragmentTestBatchInput& in, unsigned count,
                              const FragmentTestBatch& out, BatchIsa isa = best_batch_isa());

}  // namespace tessera::raster
