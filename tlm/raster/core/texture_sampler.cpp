// See texture_sampler.h.
#include "raster/core/texture_sampler.h"

#include <algorithm>
#include <array>

#include "raster/core/little_endian.h"
#include "raster/core/refined_reciprocal.h"
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
  Rgba8 texel;
  if (!filtered_texel(ts, ts.s, ts.t, m_state.texture, m_state.min_filter, m_state.mag_filter, dx, dy, texel))
    return false;
  out = texture_environment(m_state.env, fragment, texel);
  return true;
}

bool TextureSampler::unit_texel(const TriangleSetup& ts, unsigned unit, int dx, int dy, Rgba8& texel) {
  const TextureUnitDraw& u = m_state.unit[unit];
  return filtered_texel(ts, ts.unit_s[unit], ts.unit_t[unit], u.texture, u.min_filter, u.mag_filter, dx, dy, texel);
}

bool TextureSampler::filtered_texel(const TriangleSetup& ts, const AttributePlane& s_plane,
                                    const AttributePlane& t_plane, TextureState tex, TexFilter min_filter,
                                    TexFilter mag_filter, int dx, int dy, Rgba8& texel) {
  const AttributeEvaluation s = evaluate_attribute(s_plane, dx, dy);
  const AttributeEvaluation t = evaluate_attribute(t_plane, dx, dy);
  const AttributeEvaluation q = evaluate_attribute(ts.q, dx, dy);
  q15_16 sc, tc;
  texture_coords(s.value, t.value, q.value, sc, tc);
  tex.filter = mag_filter;
  if (min_filter != mag_filter) {
    // GL's scale factor rho from the texel-space differences to the next
    // pixel in x and in y (as Mesa does per quad); rho > 1 minifies.
    q15_16 sx, tx, sy, ty;
    texture_coords(s.value_next_x, t.value_next_x, q.value_next_x, sx, tx);
    texture_coords(s.value_next_y, t.value_next_y, q.value_next_y, sy, ty);
    const auto texel_delta = [](q15_16 a, q15_16 b, unsigned log2) { return int128(b.raw - a.raw) << log2; };
    const int128 dux = texel_delta(sc, sx, tex.log2_width), dvx = texel_delta(tc, tx, tex.log2_height);
    const int128 duy = texel_delta(sc, sy, tex.log2_width), dvy = texel_delta(tc, ty, tex.log2_height);
    const int128 rho2 = std::max(dux * dux + dvx * dvx, duy * duy + dvy * dvy);
    if (rho2 > (int128{1} << 32)) tex.filter = min_filter;
  }
  const TexelFootprint footprint = texel_lookup(tex, sc, tc);
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

}  // namespace tessera::raster
