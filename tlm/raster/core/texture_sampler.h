// Texturing of a batch of fragments (fragment_batch.h): s/w and t/w divided
// by 1/w with the refined reciprocal (the perspective division), the choice
// between the minification and magnification filter by GL's scale factor
// rho or the LOD unit's levels, the texel addresses (texel_address), the
// fetches through the port (one per texel, fragment by fragment as the
// hardware issues them; a refused one is the run's bad_texture, at the
// texel), and the bilinear filter with the texture environment
// (texture_env). README.md, "Texture coordinates", "Per-fragment
// operations" and "Texture sampling".
#pragma once

#include <array>
#include <cstdint>

#include "raster/core/draw_state.h"
#include "raster/core/fragment_batch.h"
#include "raster/core/run_context.h"
#include "raster/core/triangle_setup.h"
#include "raster/datapath/attribute_interpolator.h"
#include "raster/datapath/fixed_point.h"

namespace tessera::raster {

// The sampler's working arrays, one entry a fragment of a batch.
struct TextureScratch {
  static constexpr unsigned N = FragmentBatch::CAPACITY;
  // The s/w, t/w and 1/w planes at the fragments and at their neighbours
  // in x and y; the interpolator's (unused) outputs.
  std::array<int64_t, N> s, t, q, s_next_x, t_next_x, q_next_x, s_next_y, t_next_y, q_next_y;
  std::array<uint32_t, N> output;
  // The StateBlock's texture: each fragment's q15.16 coordinates and filter
  // (1: minified, the minification filter), the footprints with either
  // filter, the texels and weights the bilinear filter takes.
  std::array<int32_t, N> s_coord, t_coord;
  std::array<uint32_t, N> minified;
  std::array<std::array<uint32_t, N>, 10> footprint_mag, footprint_min;  // TexelBatch's fields
  std::array<std::array<uint32_t, N>, 4> texel;
  std::array<uint32_t, N> weight_s, weight_t, texel_out;
  // Texture units: each unit's coordinates and the LOD unit's results.
  struct Unit {
    std::array<int32_t, N> s_coord, t_coord;
    std::array<uint32_t, N> rho, flags, level0, level1, weight;
    std::array<int32_t, N> lambda;
  };
  std::array<Unit, MAX_TEXTURE_UNITS> unit;
};

class TextureSampler {
 public:
  TextureSampler(RunContext& run, const DrawState& state, TextureScratch& scratch)
      : m_run(run), m_state(state), m_scratch(scratch) {}

  // The StateBlock's texture (without StateFlag::texture_units) on `count`
  // fragments at offsets (dx[i], dy[i]) from the setup's reference pixel:
  // rgba[i], the fragment's colour, through the texture environment with
  // its filtered texel. Returns count, or the index of the fragment whose
  // texel fetch failed (the colours before it are done).
  unsigned sample(const TriangleSetup& setup, const int32_t* dx, const int32_t* dy, unsigned count, uint32_t* rgba);

  // With StateFlag::texture_units, in two steps so that the fetches can go
  // fragment by fragment and unit by unit: unit u's coordinates at the
  // fragments, rho (from the coordinates' derivatives at the pixel, the
  // planes' gradients over 1/w) and the LOD unit's levels (lod_unit.h);
  // then fragment i's filtered texel of unit u, before its environment:
  // each level max(1, w >> k) x max(1, h >> k) texels at its level table
  // address, filtered within the level, two levels blended with the 8-bit
  // weight (README.md, "Texture sampling"); false when a fetch failed.
  void prepare_unit(const TriangleSetup& setup, unsigned unit, const int32_t* dx, const int32_t* dy, unsigned count);
  bool unit_texel(unsigned unit, unsigned i, Rgba8& texel);

 private:
  // The texels of `tex`'s footprint at (s, t), fetched (one, or four with
  // LINEAR) and filtered; false when a fetch failed.
  bool fetch_filtered(const TextureState& tex, q15_16 s, q15_16 t, Rgba8& texel);
  // The fetches of one footprint (addresses, 1 or 4) into texels[]; false
  // when one failed. Counts and charges the texels of a complete footprint.
  bool fetch(const uint32_t (&address)[4], unsigned fetches, uint32_t (&texels)[4]);

  RunContext& m_run;
  const DrawState& m_state;
  TextureScratch& m_scratch;
};

}  // namespace tessera::raster
