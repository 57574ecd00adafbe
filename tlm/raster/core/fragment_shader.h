// Shading of one fragment, in GL's order after the scissor (which bounds the
// traversal): interpolated colour (interpolation.h), texturing
// (TextureSampler), coverage into alpha with polygon_smooth, then the alpha,
// stencil and depth tests, blending or logic op and the colour mask
// (fragment_operations.h), and the results in the tile cache; counts the
// fragments written (README.md, "Per-fragment operations").
#pragma once

#include "raster/core/draw_state.h"
#include "raster/core/run_context.h"
#include "raster/core/texture_sampler.h"
#include "raster/core/tile_cache.h"
#include "raster/core/triangle_setup.h"
#include "raster/datapath/fixed_point.h"

namespace tessera::raster {

class FragmentShader {
 public:
  FragmentShader(RunContext& run, TileCache& tile, const DrawState& state)
      : m_run(run), m_tile(tile), m_state(state), m_sampler(run, state) {}

  // The fragment at GL pixel (px, py), inside the tile, with its coverage
  // (255 without polygon_smooth).
  void shade(const TriangleSetup& setup, int px, int py, unorm8 coverage);

 private:
  bool shaded_color(const TriangleSetup& setup, int dx, int dy, unorm8 coverage, Rgba8& color);

  RunContext& m_run;
  TileCache& m_tile;
  const DrawState& m_state;
  TextureSampler m_sampler;
};

}  // namespace tessera::raster
