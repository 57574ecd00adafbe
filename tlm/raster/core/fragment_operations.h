// The per-fragment operations after the scissor (alpha, stencil and depth
// tests, blending, logic op, colour mask) on a batch of fragments
// (fragment_batch.h), through the batch forms of the datapath units
// fragment_tests and blend_logic_op, with the state decoded once per batch.
#pragma once

#include <cstdint>

#include "common/fixed_function.h"
#include "raster/datapath/fragment_tests.h"

namespace tessera::raster {

// The state the operations read, decoded from the StateBlock
// (command_format.h) with the codes of common/fixed_function.def; the
// defaults are GL's.
struct FragmentOperationsState {
  bool depth_test = false, depth_write = true, alpha_test = false, stencil_test = false, blend = false,
       logic_op = false;
  CompareFunc depth_func = CompareFunc::less;
  CompareFunc alpha_func = CompareFunc::always;
  uint8_t alpha_ref = 0;
  CompareFunc stencil_func = CompareFunc::always;
  uint8_t stencil_ref = 0, stencil_value_mask = 0xff, stencil_write_mask = 0xff;
  StencilOp stencil_fail = StencilOp::keep, depth_fail = StencilOp::keep, depth_pass = StencilOp::keep;
  BlendFactor blend_src = BlendFactor::one, blend_dst = BlendFactor::zero;
  LogicOp logic_op_mode = LogicOp::copy;
  uint8_t color_mask = 15;
};

// In two steps, so that the shader can compute the fragments' colours only
// where they are needed: the tests of `count` fragments (alpha 0.8, read
// with the alpha test only; depth 0.24; the tile's stored depth and
// stencil), giving FRAGMENT_* flags and the stencil value to store each;
// then, for fragments that passed, blending or logic op and the colour mask
// (packed RGBA8 words), giving the colour to store.
void fragment_tests(const FragmentOperationsState& state, const uint32_t* alpha, const uint32_t* depth,
                    const uint32_t* stored_depth, const uint32_t* stored_stencil, unsigned count, uint32_t* flags,
                    uint32_t* stencil);
void fragment_color_update(const FragmentOperationsState& state, const uint32_t* fragment, const uint32_t* stored,
                           unsigned count, uint32_t* out);

}  // namespace tessera::raster
