// See texture_sampler.h.
#include "raster/core/texture_sampler.h"

#include <algorithm>
#include <array>
#include <limits>

#include "common/little_endian.h"
#include "raster/core/refined_reciprocal.h"
#include "raster/datapath/lod_unit.h"
#include "raster/datapath/texel_address.h"
#include "raster/datapath/texture_env.h"

namespace tessera::raster {

namespace {

// 1/q refined. 1/w is positive inside the triangle; the few pixels just
// outside an antialiased edge may extrapolate it to zero or below, which
// counts as the smallest positive q.
Reciprocal inverse_of(int64_t q, RecipMethod method) {
  Reciprocal r;
  refined_reciprocal(uint64_t(std::max<int64_t>(q, 1)), method, r);
  return r;
}

// s = (s/w) / (1/w) from the interpolators' exact sums (24 fraction bits)
// into the q15.16 that texel addressing takes.
q15_16 over_q(int64_t v, const Reciprocal& inv_q) {
  return q15_16{int64_t(std::clamp<int128>(divide(v, inv_q, false, -16), q15_16::MIN_RAW, q15_16::MAX_RAW))};
}

// A TexelBatch over ten arrays of the scratch.
TexelBatch texel_batch(std::array<std::array<uint32_t, TextureScratch::N>, 10>& f) {
  return {f[0].data(),
          f[1].data(),
          f[2].data(),
          f[3].data(),
          f[4].data(),
          f[5].data(),
          {f[6].data(), f[7].data(), f[8].data(), f[9].data()}};
}

}  // namespace

bool TextureSampler::fetch(const uint32_t (&address)[4], unsigned fetches, uint32_t (&texels)[4]) {
  for (unsigned k = 0; k < fetches; ++k) {
    uint8_t raw[4];
    if (!m_run.read(address[k], raw, 4, RasterError::bad_texture)) return false;
    texels[k] = load_le32(raw);
  }
  for (unsigned k = fetches; k < 4; ++k) texels[k] = texels[0];
  m_run.result().texels += fetches;
  m_run.charge(m_run.result().texel_cycles, uint64_t{m_run.costs().texel} * fetches);
  return true;
}

unsigned TextureSampler::sample(const TriangleSetup& ts, const int32_t* dx, const int32_t* dy, unsigned count,
                                uint32_t* rgba) {
  TextureScratch& w = m_scratch;
  const RecipMethod method = m_run.config().recip_method;
  // GL's scale factor rho from the texel-space differences to the next
  // pixel in x and in y (as Mesa does per quad); rho > 1 minifies. Only
  // when the two filters differ.
  const bool choose = m_state.min_filter != m_state.mag_filter;
  const auto plane = [&](const AttributePlane& p, std::array<int64_t, TextureScratch::N>& value,
                         std::array<int64_t, TextureScratch::N>& next_x,
                         std::array<int64_t, TextureScratch::N>& next_y) {
    attribute_batch(
        p, dx, dy, count,
        {value.data(), choose ? next_x.data() : nullptr, choose ? next_y.data() : nullptr, w.output.data()});
  };
  plane(ts.s, w.s, w.s_next_x, w.s_next_y);
  plane(ts.t, w.t, w.t_next_x, w.t_next_y);
  plane(ts.q, w.q, w.q_next_x, w.q_next_y);
  const TextureState& texture = m_state.texture;
  for (unsigned i = 0; i < count; ++i) {
    const Reciprocal inv = inverse_of(w.q[i], method);
    const q15_16 sc = over_q(w.s[i], inv), tc = over_q(w.t[i], inv);
    w.s_coord[i] = int32_t(sc.raw);
    w.t_coord[i] = int32_t(tc.raw);
    w.minified[i] = 0;
    if (!choose) continue;
    const Reciprocal inv_x = inverse_of(w.q_next_x[i], method), inv_y = inverse_of(w.q_next_y[i], method);
    const q15_16 sx = over_q(w.s_next_x[i], inv_x), tx = over_q(w.t_next_x[i], inv_x);
    const q15_16 sy = over_q(w.s_next_y[i], inv_y), ty = over_q(w.t_next_y[i], inv_y);
    // Scaled by a multiply, not a shift: the difference may be negative.
    const auto texel_delta = [](q15_16 a, q15_16 b, unsigned log2) {
      return int128(b.raw - a.raw) * (int128{1} << log2);
    };
    const int128 dux = texel_delta(sc, sx, texture.log2_width), dvx = texel_delta(tc, tx, texture.log2_height);
    const int128 duy = texel_delta(sc, sy, texture.log2_width), dvy = texel_delta(tc, ty, texture.log2_height);
    const int128 rho2 = std::max(dux * dux + dvx * dvx, duy * duy + dvy * dvy);
    w.minified[i] = rho2 > (int128{1} << 32) ? 1 : 0;
  }
  // Every fragment's footprint with either filter (the batch form takes one
  // state), each fragment's by its own.
  TextureState tex = texture;
  tex.filter = m_state.mag_filter;
  texel_lookup_batch(tex, w.s_coord.data(), w.t_coord.data(), count, texel_batch(w.footprint_mag));
  if (choose) {
    tex.filter = m_state.min_filter;
    texel_lookup_batch(tex, w.s_coord.data(), w.t_coord.data(), count, texel_batch(w.footprint_min));
  }
  unsigned done = count;
  for (unsigned i = 0; i < count; ++i) {
    const bool minified = w.minified[i] != 0;
    const auto& f = minified ? w.footprint_min : w.footprint_mag;
    const bool linear = (minified ? m_state.min_filter : m_state.mag_filter) == TexFilter::linear;
    const uint32_t address[4] = {f[6][i], f[7][i], f[8][i], f[9][i]};
    uint32_t texels[4];
    if (!fetch(address, linear ? 4 : 1, texels)) {
      done = i;
      break;
    }
    for (unsigned k = 0; k < 4; ++k) w.texel[k][i] = texels[k];
    w.weight_s[i] = f[2][i];
    w.weight_t[i] = f[5][i];
  }
  // The filtered texels, then the environment.
  texture_filter_env_batch(m_state.env,
                           {{w.texel[0].data(), w.texel[1].data(), w.texel[2].data(), w.texel[3].data()},
                            w.weight_s.data(),
                            w.weight_t.data(),
                            rgba},
                           done, {w.texel_out.data(), w.output.data()});
  std::copy(w.output.data(), w.output.data() + done, rgba);
  return done;
}

void TextureSampler::prepare_unit(const TriangleSetup& ts, unsigned u, const int32_t* dx, const int32_t* dy,
                                  unsigned count) {
  TextureScratch& w = m_scratch;
  TextureScratch::Unit& out = w.unit[u];
  const TextureUnitDraw& unit = m_state.unit[u];
  const AttributePlane &s_plane = ts.unit_s[u], &t_plane = ts.unit_t[u], &q_plane = ts.q;
  const RecipMethod method = m_run.config().recip_method;
  attribute_batch(s_plane, dx, dy, count, {w.s.data(), nullptr, nullptr, w.output.data()});
  attribute_batch(t_plane, dx, dy, count, {w.t.data(), nullptr, nullptr, w.output.data()});
  attribute_batch(q_plane, dx, dy, count, {w.q.data(), nullptr, nullptr, w.output.data()});
  // rho = max(|du/dx|, |dv/dx|, |du/dy|, |dv/dy|) in level 0's texels, 16.16
  // (the lower bound of equation 3.17, as the arm back end and Mesa's
  // softpipe take it), from the derivatives at the pixel's centre: ds/dx =
  // (d(s/w)/dx - s d(1/w)/dx) / (1/w), the planes' gradients with the
  // coordinate and the reciprocal already at hand (one product and one
  // multiplication by the reciprocal per derivative, no further division).
  // Only when the result can depend on it.
  const bool needs_rho = unit.mipmap != TexMipmap::none || unit.min_filter != unit.mag_filter;
  for (unsigned i = 0; i < count; ++i) {
    const Reciprocal inv_q = inverse_of(w.q[i], method);
    const q15_16 sc = over_q(w.s[i], inv_q), tc = over_q(w.t[i], inv_q);
    out.s_coord[i] = int32_t(sc.raw);
    out.t_coord[i] = int32_t(tc.raw);
    uint32_t rho = 0;
    if (needs_rho) {
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
    out.rho[i] = rho;
  }
  lod_unit_batch(unit.min_filter, unit.mag_filter, unit.mipmap, unit.last_level, out.rho.data(), count,
                 {out.lambda.data(), out.flags.data(), out.level0.data(), out.level1.data(), out.weight.data()});
}

bool TextureSampler::unit_texel(unsigned u, unsigned i, Rgba8& texel) {
  const TextureScratch::Unit& prepared = m_scratch.unit[u];
  const TextureUnitDraw& unit = m_state.unit[u];
  const bool linear = (prepared.flags[i] & LOD_LINEAR) != 0;
  // Level k: max(1, w >> k) x max(1, h >> k) texels at its table address;
  // s and t stay normalised, so texel addressing takes the level's sizes.
  const auto level_state = [&](unsigned k) {
    TextureState tex = unit.texture;
    tex.base = unit.level_address[k];
    tex.log2_width = uint8_t(tex.log2_width > k ? tex.log2_width - k : 0);
    tex.log2_height = uint8_t(tex.log2_height > k ? tex.log2_height - k : 0);
    tex.filter = linear ? TexFilter::linear : TexFilter::nearest;
    return tex;
  };
  const q15_16 sc{prepared.s_coord[i]}, tc{prepared.t_coord[i]};
  if (!fetch_filtered(level_state(prepared.level0[i]), sc, tc, texel)) return false;
  if ((prepared.flags[i] & LOD_TWO_LEVELS) == 0) return true;
  Rgba8 next;
  if (!fetch_filtered(level_state(prepared.level1[i]), sc, tc, next)) return false;
  // ((256 - w) a + w b + 128) >> 8: the bilinear filter with weights w and 0.
  texel = bilinear_filter({texel, next, texel, next}, uint8_t(prepared.weight[i]), 0);
  return true;
}

bool TextureSampler::fetch_filtered(const TextureState& tex, q15_16 s, q15_16 t, Rgba8& texel) {
  const TexelFootprint footprint = texel_lookup(tex, s, t);
  uint32_t texels[4];
  const uint32_t address[4] = {footprint.address[0], footprint.address[1], footprint.address[2], footprint.address[3]};
  if (!fetch(address, tex.filter == TexFilter::linear ? 4 : 1, texels)) return false;
  texel = Rgba8::unpack(
      bilinear_filter_word(texels[0], texels[1], texels[2], texels[3], footprint.s.weight, footprint.t.weight));
  return true;
}

}  // namespace tessera::raster
