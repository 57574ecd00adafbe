// Shading of a batch of fragments (fragment_batch.h), in GL's order after
// the scissor (which bounds the traversal): interpolated colour
// (interpolation.h), texturing (TextureSampler, the texture combiner),
// fog, coverage into alpha with polygon_smooth, then the alpha, stencil and
// depth tests, blending or logic op and the colour mask
// (fragment_operations.h), and the results in the tile cache; counts the
// fragments written (README.md, "Per-fragment operations" and "Batches").
#pragma once

#include <array>
#include <cstdint>

#include "raster/core/draw_state.h"
#include "raster/core/fragment_batch.h"
#include "raster/core/interpolation.h"
#include "raster/core/run_context.h"
#include "raster/core/texture_sampler.h"
#include "raster/core/tile_cache.h"
#include "raster/core/triangle_setup.h"

namespace tessera::raster {

// The shading stages' arrays, one entry a fragment of a batch. Allocated
// once per run: the core runs on a SystemC thread, whose stack is small.
struct ShadingWorkspace {
  static constexpr unsigned N = FragmentBatch::CAPACITY;
  FragmentBatch batch;
  InterpolationScratch interpolation;
  TextureScratch texture;
  // By batch index: colour (packed RGBA8), its alpha code, depth, the
  // tile's depth and stencil and buffer index, the tests' flags and
  // stencil value.
  std::array<uint32_t, N> color, alpha, depth, stored_depth, stored_stencil, tile_index, flags, stencil;
  // The fragments that passed the tests, in order: batch index, offsets,
  // coverage, colour, the tile's colour and the colour to store.
  std::array<uint32_t, N> passed, passed_coverage, passed_color, stored_color, written;
  std::array<int32_t, N> passed_dx, passed_dy;
  // Texturing and fog: each unit's filtered texels, the primary colour, the
  // fog arguments and factors, a second colour array for the units that
  // take one colour in and give another out.
  std::array<std::array<uint32_t, N>, MAX_TEXTURE_UNITS> texel;
  std::array<uint32_t, N> primary, fog_factor, color_out;
  std::array<int32_t, N> fog;
  // The traversal's rows with polygon_smooth: the edge function's batch
  // outputs and the pixels' coverage.
  std::array<int32_t, N + 1> edge_value;
  std::array<int32_t, N> edge_value_next_y, edge_distance;
  std::array<uint32_t, N> edge_inside, edge_coverage, coverage;
};

class FragmentShader {
 public:
  FragmentShader(RunContext& run, TileCache& tile, const DrawState& state, ShadingWorkspace& work)
      : m_run(run), m_tile(tile), m_state(state), m_work(work), m_sampler(run, state, work.texture) {}

  // Shades the batch's fragments in order. Returns the index of the
  // fragment whose texel fetch failed (the run has failed then; the
  // fragments before it were shaded, it and those after it not), or
  // batch.size().
  unsigned shade(const TriangleSetup& setup, const FragmentBatch& batch);

 private:
  // The colours of `count` fragments (offsets, coverage) in order:
  // interpolated, textured, fogged, alpha times the coverage with
  // polygon_smooth. Returns count, or the index of the fragment whose texel
  // fetch failed (the colours before it are complete).
  unsigned shaded_colors(const TriangleSetup& setup, const int32_t* dx, const int32_t* dy, const uint32_t* coverage,
                         unsigned count, uint32_t* rgba);

  RunContext& m_run;
  TileCache& m_tile;
  const DrawState& m_state;
  ShadingWorkspace& m_work;
  TextureSampler m_sampler;
};

}  // namespace tessera::raster
