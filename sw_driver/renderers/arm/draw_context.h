// The arm renderer's per-draw decisions: what a draw's state asks of each
// span and pixel, and what the host is charged for it (internal to the
// renderer; arm_rasterizer.h).
#pragma once

#include <cstdint>

#include "gl/renderer.h"
#include "renderers/arm/arm_rasterizer.h"
#include "renderers/common/fog.h"

namespace tessera::arm {

struct DrawContext {
  const gl::RasterState* state = nullptr;
  int clip_x0 = 0, clip_x1 = -1, clip_y0 = 0, clip_y1 = -1;  // inclusive, GL coordinates
  bool depth_test = false, depth_write = false;
  bool stencil_test = false, stencil_writes = false;
  bool alpha_test = false, texture = false, gouraud = false;
  // The texture units drawn, in order (enabled, with a usable texture).
  unsigned units[gl::MAX_TEXTURE_UNITS] = {};
  unsigned unit_count = 0;
  bool fog = false;
  renderers::FogCoefficientsF fog_coefficients;
  uint32_t fog_rgba = 0;
  bool late_tests = false;  // alpha test first, then stencil and depth
  bool color_write = false, needs_destination = false, blend = false, logic_op = false;
  uint32_t color_write_mask = 0;  // packed bits that are written
  // What the host is charged for (sw_driver/costs): attributes set up and
  // stepped, texture environments applied per shaded pixel (GL_COMBINE
  // apart), whether a written pixel reads the destination back.
  unsigned attributes = 0;
  unsigned environments = 0, combines = 0, combine_arguments = 0;
  bool reads_destination = false;
};

// The context of a draw in `buffers` with `state`; false when the clip
// rectangle (screen and scissor box) is empty.
bool make_draw_context(const gl::RasterState& state, const FrameBuffers& buffers, DrawContext& c);

}  // namespace tessera::arm
