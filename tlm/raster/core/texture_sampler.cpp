// See texture_sampler.h.
#include "raster/core/texture_sampler.h"

#include <algorithm>
#include <array>
#include <limits>

#include "raster/core/little_endian.h"
#include "raster/core/refined_reciprocal.h"
#include "raster/datapath/lod_unit.h"
#include "raster/datapath/texel_address.h"
#include "raster/datapath/texture_env.h"

namespace tessera::raster {

// s = (s/w) / (1/w) from the interpolators' exact sums (24 fraction bits).
void TextureSampler::texture_coords(attribute_sum s, attribute_sum t, attribute_sum q, q15_16& s_out,
                                    q15_16& t_out) const {
  // 1/w is positive inside the triangle; the few pixels just outside an
  // antialiased edge may extrapolate it to zero or below.
  Reciprocal inv_q;
  refined_reciprocal(uint64_t(std::max<int64_t>(q.raw, 1)), m_run.config().recip_method, inv_q);
  const auto to_q15_16 = [&](attribute_sum v) {
    const int128 r = divide(v.raw, inv_q, false, -16);
    return q15_16{int64_t(std::clamp<int128>(r, q15_16::MIN_RAW, q15_16::MAX_RAW))};
  };
  s_out = to_q15_16(s);
  t_out = to_q15_16(t);
}

bool TextureSampler::sample(const TriangleSetup& ts, int dx, int dy, Rgba8 fragment, Rgba8& out) {
  const AttributeEvaluation s = evaluate_attribute(ts.s, dx, dy);
  const AttributeEvaluation t = evaluate_attribute(ts.t, dx, dy);
  const AttributeEvaluation q = evaluate_attribute(ts.q, dx, dy);
  q15_16 sc, tc;
  texture_coords(s.value, t.value, q.value, sc, tc);
  TextureState tex = m_state.texture;
  tex.filter = m_state.mag_filter;
  if (m_state.min_filter != m_state.mag_filter) {
    // GL's scale factor rho from the texel-space differences to the next
    // pixel in x and in y (as Mesa does per quad); rho > 1 minifies.
    q15_16 sx, tx, sy, ty;
    texture_coords(s.value_next_x, t.value_next_x, q.value_next_x, sx, tx);
    texture_coords(s.value_next_y, t.value_next_y, q.value_next_y, sy, ty);
    const auto texel_delta = [](q15_16 a, q15_16 b, unsigned log2) { return int128(b.raw - a.raw) << log2; };
    const int128 dux = texel_delta(sc, sx, tex.log2_width), dvx = texel_delta(tc, tx, tex.log2_height);
    const int128 duy = texel_delta(sc, sy, tex.log2_width), dvy = texel_delta(tc, ty, tex.log2_height);
    const int128 rho2 = std::max(dux * dux + dvx * dvx, duy * duy + dvy * dvy);
    if (rho2 > (int128{1} << 32)) tex.filter = m_state.min_filter;
  }
  // The filtered texel, then the environment: texture_filter_env's two steps.
  Rgba8 texel;
  if (!fetch_filtered(tex, sc, tc, texel)) return false;
  out = texture_environment(m_state.env, fragment, texel);
  return true;
}

bool TextureSampler::unit_texel(const TriangleSetup& ts, unsigned unit, int dx, int dy, Rgba8& texel) {
  return sample_unit(m_state.unit[unit], ts.unit_s[unit], ts.unit_t[unit], ts.q, dx, dy, texel);
}

bool TextureSampler::fetch_filtered(const TextureState& tex, q15_16 s, q15_16 t, Rgba8& texel) {
  const TexelFootprint footprint = texel_lookup(tex, s, t);
  const unsigned fetches = tex.filter == TexFilter::linear ? 4 : 1;
  std::array<Rgba8, 4> texels;
  for (unsigned k = 0; k < fetches; ++k) {
    uint8_t raw[4];
    if (!m_run.read(footprint.address[k], raw, 4, RasterError::bad_texture)) return false;
    texels[k] = Rgba8::unpack(load_le32(raw));
  }
  for (unsigned k = fetches; k < 4; ++k) texels[k] = texels[0];
  m_run.result().texels += fetches;
  m_run.charge(m_run.result().texel_cycles, uint64_t{m_run.costs().texel} * fetches);
  texel = bilinear_filter(texels, footprint.s.weight, footprint.t.weight);
  return true;
}

bool TextureSampler::sample_unit(const TextureUnitDraw& unit, const AttributePlane& s_plane,
                                 const AttributePlane& t_plane, const AttributePlane& q_plane, int dx, int dy,
                                 Rgba8& texel) {
  const attribute_sum s = attribute_at(s_plane, dx, dy), t = attribute_at(t_plane, dx, dy);
  const attribute_sum q = attribute_at(q_plane, dx, dy);
  // s = (s/w) / (1/w) as texture_coords divides (1/w is positive inside
  // the triangle; an antialiased edge's outside pixels may reach 0).
  Reciprocal inv_q;
  refined_reciprocal(uint64_t(std::max<int64_t>(q.raw, 1)), m_run.config().recip_method, inv_q);
  const auto over_q = [&](attribute_sum v) {
    return q15_16{int64_t(std::clamp<int128>(divide(v.raw, inv_q, false, -16), q15_16::MIN_RAW, q15_16::MAX_RAW))};
  };
  const q15_16 sc = over_q(s), tc = over_q(t);
  // rho = max(|du/dx|, |dv/dx|, |du/dy|, |dv/dy|) in level 0's texels, 16.16
  // (the lower bound of equation 3.17, as the arm back end and Mesa's
  // softpipe take it), from the derivatives at the pixel's centre: ds/dx =
  // (d(s/w)/dx - s d(1/w)/dx) / (1/w), the planes' gradients with the
  // coordinate and the reciprocal already at hand (one product and one
  // multiplication by the reciprocal per derivative, no further division).
  // Only when the result can depend on it.
  uint32_t rho = 0;
  if (unit.mipmap != TexMipmap::none || unit.min_filter != unit.mag_filter) {
    const auto texel_derivative = [&](int64_t grad, q15_16 coord, int64_t grad_q, unsigned log2) {
      const int128 n = int128(attribute_word40(grad)) * 65536 - int128(coord.raw) * attribute_word40(grad_q);
      const int128 d = divide(n, inv_q, false);  // q15.16 per pixel
      return (d < 0 ? -d : d) << log2;           // in texels
    };
    const unsigned lw = unit.texture.log2_width, lh = unit.texture.log2_height;
    const int128 largest = std::max({texel_derivative(s_plane.grad_x, sc, q_plane.grad_x, lw),
                                     texel_derivative(t_plane.grad_x, tc, q_plane.grad_x, lh),
                                     texel_derivative(s_plane.grad_y, sc, q_plane.grad_y, lw),
                                     texel_derivative(t_plane.grad_y, tc, q_plane.grad_y, lh)});
    rho = uint32_t(std::min<int128>(largest, std::numeric_limits<uint32_t>::max()));
  }
  const LodResult lod = lod_unit(rho, unit.min_filter, unit.mag_filter, unit.mipmap, unit.last_level);
  // Level k: max(1, w >> k) x max(1, h >> k) texels at its table address;
  // s and t stay normalised, so texel addressing takes the level's sizes.
  const auto level_state = [&](unsigned k) {
    TextureState tex = unit.texture;
    tex.base = unit.level_address[k];
    tex.log2_width = uint8_t(tex.log2_width > k ? tex.log2_width - k : 0);
    tex.log2_height = uint8_t(tex.log2_height > k ? tex.log2_height - k : 0);
    tex.filter = lod.linear ? TexFilter::linear : TexFilter::nearest;
    return tex;
  };
  if (!fetch_filtered(level_state(lod.level[0]), sc, tc, texel)) return false;
  if (!lod.two_levels) return true;
  Rgba8 next;
  if (!fetch_filtered(level_state(lod.level[1]), sc, tc, next)) return false;
  // ((256 - w) a + w b + 128) >> 8: the bilinear filter with weights w and 0.
  texel = bilinear_filter({texel, next, texel, next}, lod.weight, 0);
  return true;
}

}  // namespace tessera::raster
