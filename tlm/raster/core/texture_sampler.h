// Texturing of one fragment: s/w and t/w divided by 1/w with the refined
// reciprocal (the perspective division), the choice between the
// minification and magnification filter by GL's scale factor rho, the texel
// addresses (texel_address), the fetches through the port (one per texel; a
// refused one is the run's bad_texture, at the texel), and the bilinear
// filter with the texture environment (texture_env). README.md, "Texture
// coordinates" and "Per-fragment operations".
#pragma once

#include "raster/core/draw_state.h"
#include "raster/core/run_context.h"
#include "raster/core/triangle_setup.h"
#include "raster/datapath/attribute_interpolator.h"
#include "raster/datapath/fixed_point.h"

namespace tessera::raster {

class TextureSampler {
 public:
  TextureSampler(RunContext& run, const DrawState& state) : m_run(run), m_state(state) {}

  // The fragment's colour after the texture environment, at the offset
  // (dx, dy) from the setup's reference pixel; false when a texel fetch failed.
  // The StateBlock's texture (without StateFlag::texture_units).
  bool sample(const TriangleSetup& setup, int dx, int dy, Rgba8 fragment, Rgba8& out);

  // With StateFlag::texture_units: texture unit `unit`'s filtered texel at
  // (dx, dy), before its environment (texture_combiner): sample_unit with
  // the unit's planes; false when a texel fetch failed.
  bool unit_texel(const TriangleSetup& setup, unsigned unit, int dx, int dy, Rgba8& texel);

  // One texture unit's filtered texel, before its environment, at (dx, dy):
  // the scale factor rho from the coordinates' derivatives at the pixel
  // (the planes' gradients over 1/w), the level(s) the LOD unit (lod_unit.h) chooses, each
  // level max(1, w >> k) x max(1, h >> k) texels at its level table address,
  // filtered within the level, two levels blended with the 8-bit weight
  // (README.md, "Texture sampling"). s, t, q are the unit's planes (s/w,
  // t/w, 1/w). false when a texel fetch failed.
  bool sample_unit(const TextureUnitDraw& unit, const AttributePlane& s, const AttributePlane& t,
                   const AttributePlane& q, int dx, int dy, Rgba8& texel);

 private:
  // The texels of `tex`'s footprint at (s, t), fetched (one, or four with
  // LINEAR) and filtered; false when a fetch failed.
  bool fetch_filtered(const TextureState& tex, q15_16 s, q15_16 t, Rgba8& texel);

  // The perspective division into the q15.16 that texel addressing takes.
  void texture_coords(attribute_sum s, attribute_sum t, attribute_sum q, q15_16& s_out, q15_16& t_out) const;

  RunContext& m_run;
  const DrawState& m_state;
};

}  // namespace tessera::raster
