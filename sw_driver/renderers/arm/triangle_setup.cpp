// The arm renderer's triangle set-up (triangle_setup.h).
#include "renderers/arm/triangle_setup.h"

#include <algorithm>

#include "renderers/common/fog.h"
#include "renderers/common/texturing.h"

namespace tessera::arm {

void setup_triangle(const DrawContext& c, const gl::Triangle& tri, const int32_t x[3], const int32_t y[3],
                    int32_t area2, PixelMemory& memory, TriangleSetup& s) {
  const gl::RasterState& state = *c.state;
  const int64_t xs[3] = {x[0], x[1], x[2]}, ys[3] = {y[0], y[1], y[2]};
  s.snapped.init(4, xs, ys);  // nonzero: area2 != 0
  if (c.depth_test) {
    int32_t z[3];
    for (int v = 0; v < 3; ++v) z[v] = int32_t(std::min<uint32_t>(tri.v[v].z, 0xffffff) << DEPTH_FRACTION_BITS);
    s.z.setup(z, s.snapped);
  }
  // A textured triangle's colour, 1/w and texture planes follow the
  // vertices before snapping, as the reference's do: snapping moves a
  // vertex by up to 1/32 pixel, which at a minified texel rate of 1.6
  // texels per pixel shifts the texture by 0.05 texel, a colour step of
  // bilinear filtering (README, "Rounding"). They are taken to 1/256
  // pixel (UNSNAPPED_BITS), which leaves 1/512 pixel. Coverage and depth
  // keep the snapped vertices.
  // Only where 1/w varies: on an affine triangle (constant w) the reference's
  // GL_NEAREST texel choices follow the snapped vertices (multitexture's
  // orthographic panels, whose vertices lie 0.2/16 pixel off the grid and
  // whose pixel centres fall on texel edges: 0.4% of the frame took the
  // next texel row with the unsnapped planes).
  const bool varying_w = !(tri.v[0].inv_w == tri.v[1].inv_w && tri.v[1].inv_w == tri.v[2].inv_w);
  if (c.texture && varying_w && has_window_positions(tri)) {
    int64_t xu[3], yu[3];
    for (int v = 0; v < 3; ++v) {
      xu[v] = round_to_int(tri.v[v].x_window * float(1 << UNSNAPPED_BITS));
      yu[v] = round_to_int(tri.v[v].y_window * float(1 << UNSNAPPED_BITS));
    }
    // A sliver the snapping made (or the positions left degenerate) keeps the snapped planes.
    s.use_unsnapped = s.unsnapped.init(UNSNAPPED_BITS, xu, yu) && (s.unsnapped.area > 0) == (area2 > 0);
  }
  const Basis& basis = s.use_unsnapped ? s.unsnapped : s.snapped;
  // Normalised 1/w of each vertex: attributes are interpolated as a/w and
  // 1/w and divided per pixel when the triangle is seen in perspective.
  // The vertex's 1/w is single precision (geometry's); the ratio to the
  // largest is one float division per vertex, and q = 2^30 qn (>= 1).
  float qn[3] = {1.0f, 1.0f, 1.0f};
  int32_t q[3] = {1 << Q_FRACTION_BITS, 1 << Q_FRACTION_BITS, 1 << Q_FRACTION_BITS};
  if (c.gouraud || c.texture || c.fog) {
    float inv_w[3], max_inv_w = 0;
    for (int v = 0; v < 3; ++v) {
      const float w = tri.v[v].inv_w;
      inv_w[v] = (finite(w) && w > 0) ? w : 1.0f;
      max_inv_w = std::max(max_inv_w, inv_w[v]);
    }
    s.perspective = !(inv_w[0] == inv_w[1] && inv_w[1] == inv_w[2]);
    if (s.perspective) {
      for (int v = 0; v < 3; ++v) {
        qn[v] = inv_w[v] / max_inv_w;
        q[v] = std::max<int32_t>(int32_t(qn[v] * float(1 << Q_FRACTION_BITS)), 1);
      }
    }
    s.q.setup(q, basis, true);
  }
  if (c.gouraud) {
    s.perspective_color = s.perspective;
    for (int ch = 0; ch < 4; ++ch) {
      int32_t value[3];
      for (int v = 0; v < 3; ++v) {
        const gl::ScreenVertex& sv = tri.v[v];
        const uint8_t channels[4] = {sv.r, sv.g, sv.b, sv.a};
        // c q 2^16 / 2^30 (< 2^24); the rounding half is added after the
        // division in the perspective case, here otherwise.
        value[v] = s.perspective_color
                       ? int32_t((int64_t{channels[ch]} * q[v]) >> (Q_FRACTION_BITS - COLOR_FRACTION_BITS))
                       : (int32_t{channels[ch]} << COLOR_FRACTION_BITS) + (1 << (COLOR_FRACTION_BITS - 1));
      }
      s.color[ch].setup(value, basis);
    }
  } else {
    const gl::ScreenVertex& pv = tri.v[2];
    s.flat_rgba = uint32_t(pv.r) | uint32_t(pv.g) << 8 | uint32_t(pv.b) << 16 | uint32_t(pv.a) << 24;
  }
  for (unsigned i = 0; i < c.unit_count; ++i) {
    const unsigned u = c.units[i];
    const gl::Texture& tex = state.unit[u].tex;
    // s W and t H in texels (single precision: the vertex's coordinates
    // are geometry's floats; W, H are powers of two, so exact), clamped,
    // then times the vertex's qn.
    float su[3], tv[3], suq[3], tvq[3], largest = 0;
    for (int v = 0; v < 3; ++v) {
      const gl::TexCoord& st = tri.v[v].tex[u];
      su[v] = finite(st.s) ? std::clamp(st.s * float(tex.width), -MAX_TEXELS, MAX_TEXELS) : 0.0f;
      tv[v] = finite(st.t) ? std::clamp(st.t * float(tex.height), -MAX_TEXELS, MAX_TEXELS) : 0.0f;
      suq[v] = su[v] * qn[v];
      tvq[v] = tv[v] * qn[v];
      largest = std::max({largest, suq[v] < 0 ? -suq[v] : suq[v], tvq[v] < 0 ? -tvq[v] : tvq[v]});
    }
    // F, as many fraction bits as keep |s W q 2^F| < 2^30: with |s W qn| <
    // 2^L (L <= 16), F = 30 - L, at most ST_MAX_FRACTION_BITS; at least 14.
    // The largest vertex value then has 29 bits or F is at its most, so a
    // step's rounding (half a unit per pixel, 256 units over a 512-pixel
    // span) stays below 2^-21 of the values even where 1/w falls 1000
    // times across the triangle (tests: PerspectiveTexturingAtTheFormatsExtremes).
    const int length = int(renderers::bit_length(uint32_t(largest) + 1));
    const int bits = std::min(ST_MAX_FRACTION_BITS, 30 - length);
    s.st_bits[i] = bits;
    const float scale = float(1 << bits);
    const int32_t limit = (1 << 30) - 1;
    int32_t sq[3], tq[3];
    for (int v = 0; v < 3; ++v) {
      sq[v] = std::clamp(round_to_int(suq[v] * scale), -limit, limit);
      tq[v] = std::clamp(round_to_int(tvq[v] * scale), -limit, limit);
    }
    s.sq[i].setup(sq, basis, true);
    s.tq[i].setup(tq, basis, true);
    // Minified when the triangle covers more texels than pixels: twice
    // the texel area in 2^-16 texel^2 (coordinates to 1/256 texel, |.| <=
    // 2^23, products below 2^48) against twice the snapped area in 2^-8
    // pixel^2.
    int64_t su8[3], tv8[3];
    for (int v = 0; v < 3; ++v) {
      su8[v] = round_to_int(su[v] * 256.0f);
      tv8[v] = round_to_int(tv[v] * 256.0f);
    }
    const int64_t texel_area = (su8[1] - su8[0]) * (tv8[2] - tv8[0]) - (su8[2] - su8[0]) * (tv8[1] - tv8[0]);
    const bool minified = (texel_area < 0 ? -texel_area : texel_area) > (int64_t{area2 < 0 ? -area2 : area2} << 8);
    s.linear_filter[i] = (minified ? tex.min_filter : tex.mag_filter) == gl::TexFilter::linear;
    s.lod[i] = renderers::texture_needs_lod(tex);
    if (s.lod[i]) {
      s.lod_gradients[i].setup(s.sq[i], s.tq[i], s.q, basis);
      s.linear_filter[i] = false;  // chosen per pixel, charged per pixel
      if (!s.perspective) memory.charge(HostCost::arm_lod);
    }
    memory.charge(HostCost::arm_triangle_texture_unit);
  }
  if (c.fog) {
    // The fog argument (16.16) of each vertex, interpolated as a/w and
    // divided by 1/w per pixel like the Gouraud colours: perspective-correct,
    // as Mesa interpolates its fog coordinate. |a| <= 2^30: 2^-a and the
    // linear clamp saturate long before.
    int32_t fog[3];
    for (int v = 0; v < 3; ++v) {
      const int32_t a = renderers::fog_argument_f(c.fog_coefficients, tri.v[v].fog, MAX_FOG_VALUE);
      fog[v] = int32_t((int64_t{a} * q[v]) >> Q_FRACTION_BITS);
    }
    s.fog.setup(fog, basis);
    memory.charge(HostCost::arm_triangle_fog);
  }
}

}  // namespace tessera::arm
