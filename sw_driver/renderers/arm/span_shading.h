// The arm renderer's span shading: the interpolants of one span, the pixel
// loops that shade it (texturing, fog, the alpha, stencil and depth tests)
// into the span's scratch rows, and the span's charges to the host
// (internal to the renderer; formats and rounding: arm_rasterizer.h).
#pragma once

#include <cstdint>

#include "gl/renderer.h"
#include "renderers/arm/draw_context.h"
#include "renderers/arm/pixel_memory.h"
#include "renderers/arm/triangle_setup.h"

namespace tessera::arm {

// The span's scratch rows (ArmRasterizer's, sized to the screen's width).
struct SpanRows {
  const uint16_t* depth_old;  // the depth buffer's values, when depth-tested
  uint16_t* depth_new;        // the pixels' depths
  uint8_t* stencil_new;       // the stencil values after the tests (loaded first)
  uint8_t* pass;              // 1 where the pixel passed every test
  uint32_t* source;           // the shaded colour, RGBA8 as r | g << 8 | b << 16 | a << 24
};

// What one span did, for its charges. At most 512 pixels: 32-bit counts.
struct SpanCounts {
  uint32_t shaded = 0, texel_calls = 0, passed = 0, color_divisions = 0, fog_divisions = 0;
  // Where the level of detail chooses per pixel: its computations, the
  // texels it samples, the blends of two levels.
  uint32_t lods = 0, lod_nearest = 0, lod_linear = 0, mipmap_blends = 0;
};

// Shades the n pixels of row j from x_first into `rows`.
void shade_pixels(const DrawContext& c, const TriangleSetup& s, int j, int x_first, int n, const SpanRows& rows,
                  PixelMemory& memory, SpanCounts& counts);

// The span's host time (sw_driver/costs): per span, per pixel walked, per
// pixel shaded and its texels, divisions and environments, per pixel
// written.
void charge_span(const DrawContext& c, const TriangleSetup& s, int n, const SpanCounts& counts, PixelMemory& memory);

}  // namespace tessera::arm
