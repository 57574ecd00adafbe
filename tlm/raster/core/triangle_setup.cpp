// See triangle_setup.h; the arithmetic is stated in README.md, "Triangle
// setup", "Colour" and "Texture coordinates".
#include "raster/core/triangle_setup.h"

#include <cmath>

namespace tessera::raster {

namespace {

constexpr double TEXCOORD_LIMIT = 32767.0;  // |s/w| after normalisation, inside q15.24

}  // namespace

bool set_up_triangle(const TriangleVertices& vin, const DrawState& state, RecipMethod method, TriangleSetup& ts) {
  const auto vx = [&](unsigned k) { return int64_t{vin[k].x}; };
  const auto vy = [&](unsigned k) { return int64_t{vin[k].y}; };
  // Twice the signed area, 9.4 x 9.4 = 8 fraction bits; > 0 is counter-clockwise.
  const int64_t area = (vx(1) - vx(0)) * (vy(2) - vy(0)) - (vx(2) - vx(0)) * (vy(1) - vy(0));
  const uint64_t magnitude = uint64_t(area < 0 ? -area : area);
  Reciprocal inv_area;
  if (!refined_reciprocal(magnitude, method, inv_area)) return false;  // zero area: operand 0

  // Edges oriented clockwise (interior on their right, E > 0; edge_function.h).
  const std::array<unsigned, 3> order = area > 0 ? std::array<unsigned, 3>{0, 2, 1} : std::array<unsigned, 3>{0, 1, 2};
  for (unsigned k = 0; k < 3; ++k) {
    const TriangleVertex& a = vin[order[k]];
    const TriangleVertex& b = vin[order[(k + 1) % 3]];
    ts.edges[k] = {q9_4::from_raw(a.x), q9_4::from_raw(a.y), q9_4::from_raw(b.x), q9_4::from_raw(b.y)};
    const q10_4 l1 = edge_l1_length(ts.edges[k]);
    // Crisu et al.: |dx| + |dy| < 2^-4 is culled, so 1/X <= 16.
    if (l1.raw == 0 || l1.raw > RECIP_OPERAND_MAX) return false;
    ts.edge_recip[k] = reciprocal_fixed(l1, method);
  }

  ts.ref_x = int(vin[0].x >> 4);
  ts.ref_y = int(vin[0].y >> 4);
  const int64_t ref_dx = 16 * ts.ref_x + 8 - vx(0), ref_dy = 16 * ts.ref_y + 8 - vy(0);
  const bool negative = area < 0;
  // Plane through the three vertex words (in the kind's fraction): gradient
  // = 16 N / area (N in word x 9.4 units), start at the reference pixel
  // centre; every quotient is one multiplication by the refined reciprocal.
  const auto plane = [&](AttributeKind kind, const std::array<int64_t, 3>& w) {
    const int128 nx = int128(w[1] - w[0]) * (vy(2) - vy(0)) - int128(w[2] - w[0]) * (vy(1) - vy(0));
    const int128 ny = int128(w[2] - w[0]) * (vx(1) - vx(0)) - int128(w[1] - w[0]) * (vx(2) - vx(0));
    const int64_t grad_x = saturate_word(divide(nx * 16, inv_area, negative));
    const int64_t grad_y = saturate_word(divide(ny * 16, inv_area, negative));
    const int64_t start = saturate_word(int128(w[0]) + divide(nx * ref_dx + ny * ref_dy, inv_area, negative));
    return attribute_plane_from_raw(kind, start, grad_x, grad_y);
  };

  ts.flat = state.has(StateFlag::flat_shading);
  ts.flat_color = vin[2].color;
  ts.depth = plane(AttributeKind::depth, {int64_t{vin[0].z} << 8, int64_t{vin[1].z} << 8, int64_t{vin[2].z} << 8});

  // 1/w of the vertices scaled by one power of two so that the largest lies
  // in [1/2, 1): every ratio a = (a/w) / (1/w) is unchanged and the scaling
  // is exact.
  const bool units = state.has(StateFlag::texture_units);
  const bool texture = state.has(StateFlag::texture) && !units;
  bool usable_w = true;
  double max_inv_w = 0;
  for (const TriangleVertex& v : vin) {
    usable_w = usable_w && std::isfinite(v.inv_w) && v.inv_w > 0;
    max_inv_w = std::max(max_inv_w, double(v.inv_w));
  }
  int exponent = 0;
  std::frexp(max_inv_w, &exponent);
  const auto scaled = [&](float value) { return std::ldexp(double(value), -exponent); };
  std::array<int64_t, 3> q{};
  for (unsigned k = 0; k < 3 && usable_w; ++k)
    q[k] = std::llround(std::ldexp(scaled(vin[k].inv_w), TEXCOORD_FRACTION_BITS));
  if (usable_w) ts.q = plane(AttributeKind::texcoord, q);

  // Gouraud colours are perspective-correct (GL 1.5 equation 3.6) when the
  // vertices' 1/w differ; with equal 1/w (orthographic) c/w over 1/w is c,
  // and the plain planes give it without a division. A triangle without
  // usable 1/w keeps screen-linear colours rather than being lost.
  ts.perspective_color = !ts.flat && usable_w && !(vin[0].inv_w == vin[1].inv_w && vin[1].inv_w == vin[2].inv_w);
  if (!ts.flat) {
    for (unsigned ch = 0; ch < 4; ++ch) {
      const auto channel = [&](unsigned k) {
        const int64_t code = (vin[k].color.pack() >> (8 * ch)) & 0xff;
        // c/w in colour words: code * 2^16 * (q_k / 2^24), rounded.
        if (ts.perspective_color) return int64_t((int128(code) * q[k] + (int64_t{1} << 7)) >> 8);
        return code << 16;
      };
      ts.color[ch] = plane(AttributeKind::color, {channel(0), channel(1), channel(2)});
    }
  }

  if (state.has(StateFlag::fog)) {
    ts.perspective_fog = usable_w && !(vin[0].inv_w == vin[1].inv_w && vin[1].inv_w == vin[2].inv_w);
    const auto word = [&](unsigned k) {
      // argument/w in 16.16 words: argument * q_k / 2^24, rounded (|word| < 2^31).
      if (ts.perspective_fog) return int64_t((int128(vin[k].fog) * q[k] + (int64_t{1} << 23)) >> 24);
      return int64_t{vin[k].fog};
    };
    ts.fog = plane(AttributeKind::texcoord, {word(0), word(1), word(2)});
  }

  if (texture) {
    if (!usable_w) return false;
    for (const TriangleVertex& v : vin)
      if (!std::isfinite(v.s_over_w) || !std::isfinite(v.t_over_w)) return false;
    std::array<int64_t, 3> s, t;
    for (unsigned k = 0; k < 3; ++k) {
      const double values[3] = {scaled(vin[k].s_over_w), scaled(vin[k].t_over_w), scaled(vin[k].inv_w)};
      for (double value : values)
        if (std::fabs(value) > TEXCOORD_LIMIT) return false;
      s[k] = std::llround(std::ldexp(values[0], TEXCOORD_FRACTION_BITS));
      t[k] = std::llround(std::ldexp(values[1], TEXCOORD_FRACTION_BITS));
    }
    ts.s = plane(AttributeKind::texcoord, s);
    ts.t = plane(AttributeKind::texcoord, t);
  }
  if (units) {
    // Every enabled unit's coordinates, as the single texture's above.
    if (!usable_w) return false;
    for (unsigned u = 0; u < state.unit_count; ++u) {
      std::array<int64_t, 3> s, t;
      for (unsigned k = 0; k < 3; ++k) {
        const TriangleVertex& v = vin[k];
        if (!std::isfinite(v.unit_s_over_w[u]) || !std::isfinite(v.unit_t_over_w[u])) return false;
        const double values[3] = {scaled(v.unit_s_over_w[u]), scaled(v.unit_t_over_w[u]), scaled(v.inv_w)};
        for (double value : values)
          if (std::fabs(value) > TEXCOORD_LIMIT) return false;
        s[k] = std::llround(std::ldexp(values[0], TEXCOORD_FRACTION_BITS));
        t[k] = std::llround(std::ldexp(values[1], TEXCOORD_FRACTION_BITS));
      }
      ts.unit_s[u] = plane(AttributeKind::texcoord, s);
      ts.unit_t[u] = plane(AttributeKind::texcoord, t);
    }
    ts.s = ts.unit_s[0];
    ts.t = ts.unit_t[0];
  }
  return true;
}

}  // namespace tessera::raster
