// Traversal: the pixels a triangle can cover, walked top row first (the
// memory order of the tile), each decided by the three edge functions with
// the fill rule or, with polygon_smooth, given the EASA coverage; the
// fragments go to the shader in batches (README.md, "Traversal and
// coverage" and "Batches").
#pragma once

#include "raster/core/command_decoder.h"
#include "raster/core/draw_state.h"
#include "raster/core/fragment_shader.h"
#include "raster/core/rect.h"
#include "raster/core/run_context.h"
#include "raster/core/triangle_setup.h"

namespace tessera::raster {

// The pixels whose centre (16 p + 8 in 9.4) can be inside the triangle (one
// more on each side with polygon_smooth, whose coverage reaches the pixels
// just outside the edges), cut to the tile and the scissor box; the scissor
// test is done here, by not generating the fragments.
Rect traversal_box(const TriangleVertices& vertices, bool smooth, const Rect& tile, const DrawState& state);

// Visits every pixel of `box`, gathers the fragments into the workspace's
// batch and shades them batch by batch, counts them, and charges one
// fragment cycle per pixel visited; stops at the fragment whose texel fetch
// fails the run.
void traverse(RunContext& run, const TriangleSetup& setup, const Rect& box, bool smooth, ShadingWorkspace& work,
              FragmentShader& shader);

}  // namespace tessera::raster
