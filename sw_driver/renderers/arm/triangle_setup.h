// The arm renderer's triangle set-up: the attribute planes of one triangle
// (depth, colour, 1/w, texture coordinates and their level-of-detail
// gradients, fog), in the formats of arm_rasterizer.h (internal to the
// renderer).
#pragma once

#include <cstdint>

#include "gl/renderer.h"
#include "renderers/arm/draw_context.h"
#include "renderers/arm/pixel_memory.h"
#include "renderers/arm/planes.h"

namespace tessera::arm {

struct TriangleSetup {
  // Depth follows the snapped vertices; colour, q, the texture coordinates
  // and fog follow `attributes`, the unsnapped positions of a perspective
  // textured triangle (draw_triangle), else the same snapped frame.
  Basis snapped, unsnapped;
  bool use_unsnapped = false;
  Plane z, color[4], q, fog;
  Plane sq[gl::MAX_TEXTURE_UNITS], tq[gl::MAX_TEXTURE_UNITS];  // per unit of DrawContext::units
  int st_bits[gl::MAX_TEXTURE_UNITS] = {};                     // F: s q and t q are s W q 2^F, t H q 2^F
  LodGradients lod_gradients[gl::MAX_TEXTURE_UNITS];
  uint32_t flat_rgba = 0;
  bool perspective = false;        // the vertices' 1/w differ
  bool perspective_color = false;  // Gouraud colours divided by q per pixel, as GL interpolates them
  bool linear_filter[gl::MAX_TEXTURE_UNITS] = {};
  // Per unit: the level of detail chooses filter and levels (texturing.h).
  bool lod[gl::MAX_TEXTURE_UNITS] = {};
};

// Sets up `s` for `tri`, whose snapped 9.4 vertices are x, y with twice the
// area area2 (nonzero), and charges the host for its texture units and fog.
void setup_triangle(const DrawContext& c, const gl::Triangle& tri, const int32_t x[3], const int32_t y[3],
                    int32_t area2, PixelMemory& memory, TriangleSetup& s);

}  // namespace tessera::arm
