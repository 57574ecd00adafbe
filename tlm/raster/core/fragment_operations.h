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

#include "raster/datapath/fixed_point.h"

namespace tessera::raster {

// The StateBlock words that the operations read, as stored (command_format.h),
// and the enable flags already decoded from StateBlock::flags.
struct FragmentOperationsState {
  bool depth_test = false, depth_write = true, alpha_test = false, stencil_test = false, blend = false,
       logic_op = false;
  uint32_t depth_func = 1;             // gl::CompareFunc::less
  uint32_t alpha_func = 7;             // func bits 0-7, reference bits 8-15
  uint32_t stencil_func = 0xffff0007;  // func, ref, value mask, write mask
  uint32_t stencil_ops = 0;            // keep, keep, keep
  uint32_t blend_func = 0x00030001;    // one, zero; logic op copy
  uint32_t color_mask = 15;
};

struct FragmentOperationsResult {
  bool pass = false;         // the colour buffer takes `color`
  bool depth_write = false;  // the depth buffer takes the fragment's depth
  uint8_t stencil = 0;       // the stencil buffer's new value
  Rgba8 color;
};

FragmentOperationsResult fragment_operations(const FragmentOperationsState& state, Rgba8 fragment, unorm24 depth,
                                             Rgba8 stored_color, unorm24 stored_depth, stencil8 stored_stencil);

}  // namespace tessera::raster
