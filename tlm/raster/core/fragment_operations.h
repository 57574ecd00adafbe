// The per-fragment operations after the scissor (alpha, stencil and depth
// tests, blending, logic op, colour mask) on the datapath units
// fragment_tests and blend_logic_op, behind an interface that names neither.
//
// Why a separate translation unit: command_format.h declares the unscoped
// enumerators raster::depth_test, alpha_test, stencil_test, blend and
// logic_op, and the datapath headers fragment_tests.h and blend_logic_op.h
// declare functions and an enum with the same names in the same namespace,
// so no file can include both. tile_rasterizer.cpp includes the contract and
// this header; fragment_operations.cpp includes the datapath units.
#pragma once

#include <cstdint>

#include "common/fixed_function.h"
#include "raster/datapath/fixed_point.h"

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

struct FragmentOperationsResult {
  bool pass = false;         // the colour buffer takes `color`
  bool depth_write = false;  // the depth buffer takes the fragment's depth
  uint8_t stencil = 0;       // the stencil buffer's new value
  Rgba8 color;
};

// In two steps, so that the shader can compute the fragment's colour only
// when it is needed: the tests (which read the colour's alpha only with the
// alpha test enabled; `color` of the result is left unset), then, for a
// fragment that passed, blending or logic op and the colour mask.
FragmentOperationsResult fragment_tests_only(const FragmentOperationsState& state, unorm8 alpha, unorm24 depth,
                                             unorm24 stored_depth, stencil8 stored_stencil);
Rgba8 fragment_color_update(const FragmentOperationsState& state, Rgba8 fragment, Rgba8 stored_color);

}  // namespace tessera::raster
