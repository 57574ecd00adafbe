// Fog unit of the rasterizer's fragment pipeline (texture, fog, then the
// fragment operations, as in Crisu et al.'s pipeline and OpenGL ES 1.1,
// section 3.8): the fog factor of the fragment's interpolated fog argument
// and the blend of its colour with the fog colour. The arithmetic is
// common/fog.h's, written once for every renderer: the factor from the
// 256-entry 2^-x table (fog_exp2_table.def, unsigned 0.16, largest error of
// the 8-bit factor 0.82 of a code, measured exhaustively), the blend rounded
// once per channel. Combinational; its Verilog twin is
// rtl_models/raster/fog_unit.sv.
//
// Ports: mode (FogMode, 2 bits), the fog argument (signed 16.16, 32 bits),
// the fragment colour and the fog colour (RGBA8; the fog colour's alpha is
// not used); out: the factor (unorm8, 255 = no fog) and the colour, whose
// alpha is the fragment's.
#pragma once

#include <cstdint>

#include "batch.h"
#include "common/fixed_function.h"
#include "common/fog.h"
#include "fixed_point.h"

namespace tessera::raster {

struct FogUnitResult {
  uint8_t factor = 255;
  Rgba8 color;
};

// Inline and branch-free: a table read (exp, exp2) and a clamp (linear), the
// mode picking one, a multiply-add per channel. The batch form
// (fog_unit_batch, batch.h) takes fragments under one mode and fog colour.
inline FogUnitResult fog_unit(FogMode mode, int32_t argument, Rgba8 fragment, Rgba8 fog_color) {
  FogUnitResult r;
  r.factor = fog_factor(mode, argument);
  r.color = Rgba8::unpack(fog_blend(r.factor, fragment.pack(), fog_color.pack()));
  return r;
}

// Batch form (batch.h): `count` fragments under one mode and fog colour,
// colours as packed words (Rgba8::pack).
struct FogBatch {
  uint32_t* factor;
  uint32_t* color;
};

struct FogKernel {
  TESSERA_BATCH_KERNEL void run(FogMode mode, Rgba8 fog_color, const int32_t* argument, const uint32_t* fragment,
                                unsigned count, const FogBatch& out) {
    loop(mode, fog_color.pack(), argument, fragment, count, out.factor, out.color);
  }
  // fog_unit's two steps on packed words.
  TESSERA_BATCH_KERNEL void loop(FogMode mode, uint32_t fog_color, const int32_t* __restrict argument,
                                 const uint32_t* __restrict fragment, unsigned count, uint32_t* __restrict factor,
                                 uint32_t* __restrict color) {
    for (unsigned i = 0; i < count; ++i) {
      const uint8_t f = fog_factor(mode, argument[i]);
      factor[i] = f;
      color[i] = fog_blend(f, fragment[i], fog_color);
    }
  }
};

void fog_unit_batch(FogMode mode, Rgba8 fog_color, const int32_t* argument, const uint32_t* fragment, unsigned count,
                    const FogBatch& out, BatchIsa isa = best_batch_isa());

}  // namespace tessera::raster
