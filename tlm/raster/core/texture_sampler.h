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
  bool sample(const TriangleSetup& setup, int dx, int dy, Rgba8 fragment, Rgba8& out);

  // With StateFlag::texture_units: texture unit `unit`'s filtered texel at
  // (dx, dy), before its environment (texture_combiner); false when a texel
  // fetch failed.
  bool unit_texel(const TriangleSetup& setup, unsigned unit, int dx, int dy, Rgba8& texel);

 private:
  // The filtered texel of `texture` at the coordinates of planes s and t
  // (over the setup's q): the minification or magnification filter, the
  // texel addresses and fetches, the bilinear filter.
  bool filtered_texel(const TriangleSetup& setup, const AttributePlane& s_plane, const AttributePlane& t_plane,
                      TextureState tex, TexFilter min_filter, TexFilter mag_filter, int dx, int dy, Rgba8& texel);

  // The perspective division into the q15.16 that texel addressing takes.
  void texture_coords(attribute_sum s, attribute_sum t, attribute_sum q, q15_16& s_out, q15_16& t_out) const;

  RunContext& m_run;
  const DrawState& m_state;
};

}  // namespace tessera::raster
