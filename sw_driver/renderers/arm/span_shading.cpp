// The arm renderer's span shading (span_shading.h).
#include "renderers/arm/span_shading.h"

#include <algorithm>

#include "common/little_endian.h"
#include "renderers/common/fixed_math.h"
#include "renderers/common/fog.h"
#include "renderers/common/fragment_ops.h"
#include "renderers/common/texturing.h"

namespace tessera::arm {

namespace {

using gl::CompareFunc;

// A wrap code without an entry acts as repeat (fixed_function.def).
inline int wrap(int i, unsigned size, gl::TexWrap mode) {
  return renderers::wrap_texel(i, size, mode);
}

// Nearest or bilinear texel of `tex`'s mipmap level `level` at that level's texel coordinates (u8, v8).
void fetch_texel(PixelMemory& memory, const gl::Texture& tex, unsigned level, int u8, int v8, bool linear,
                 uint8_t out[4]) {
  const gl::TextureLevel image = renderers::texture_level(tex, level);
  const unsigned w = image.width, h = image.height;
  auto address = [&](int i, int j) { return image.address + (uint32_t(j) * w + uint32_t(i)) * 4; };
  if (!linear) {
    const int i = wrap(u8 >> 8, w, tex.wrap_s), j = wrap(v8 >> 8, h, tex.wrap_t);
    copy_word(memory.load(address(i, j), 4, 1), out);
    return;
  }
  const int um = u8 - 128, vm = v8 - 128;
  const uint32_t fu = uint32_t(um) & 255, fv = uint32_t(vm) & 255;
  const int i0 = wrap(um >> 8, w, tex.wrap_s), i1 = wrap((um >> 8) + 1, w, tex.wrap_s);
  const int j0 = wrap(vm >> 8, h, tex.wrap_t), j1 = wrap((vm >> 8) + 1, h, tex.wrap_t);
  uint8_t texel[4][4];  // (i0, j0), (i1, j0), (i0, j1), (i1, j1)
  const int rows[2] = {j0, j1};
  for (int r = 0; r < 2; ++r) {
    if (i1 == i0 + 1) {
      const uint8_t* pair = memory.load(address(i0, rows[r]), 4, 2);
      copy_word(pair, texel[2 * r]);
      copy_word(pair + 4, texel[2 * r + 1]);
    } else {
      copy_word(memory.load(address(i0, rows[r]), 4, 1), texel[2 * r]);
      copy_word(memory.load(address(i1, rows[r]), 4, 1), texel[2 * r + 1]);
    }
  }
  renderers::bilinear(texel, fu, fv, out);
}

// The interpolants at the span's first pixel and their steps per pixel.
struct Interpolants {
  int32_t z = 0, dz = 0;
  int32_t color[4] = {0, 0, 0, 0}, dcolor[4] = {0, 0, 0, 0};
  // q, s q and t q in 2^-FINE_BITS units (Plane::start_fine); the pixel's
  // values are their integer parts.
  int64_t sq_fine[gl::MAX_TEXTURE_UNITS] = {}, tq_fine[gl::MAX_TEXTURE_UNITS] = {};
  int64_t q_fine = int64_t{1} << FINE_BITS, dq = 0;
  int64_t dsq[gl::MAX_TEXTURE_UNITS] = {}, dtq[gl::MAX_TEXTURE_UNITS] = {};
  int32_t fog = 0, dfog = 0;
};

Interpolants start_interpolants(const DrawContext& c, const TriangleSetup& s, int j, int x_first, int n) {
  Interpolants v;
  // The barycentric weights of the span's first pixel, once per frame of planes.
  int32_t w_snapped[2], w_attributes[2];
  s.snapped.weights(x_first, j, w_snapped);
  if (s.use_unsnapped) {
    s.unsnapped.weights(x_first, j, w_attributes);
  } else {
    w_attributes[0] = w_snapped[0];
    w_attributes[1] = w_snapped[1];
  }
  if (c.depth_test) {
    v.z = s.z.start(w_snapped, n);
    v.dz = s.z.step;
  }
  if (c.gouraud) {
    for (int ch = 0; ch < 4; ++ch) {
      v.color[ch] = s.color[ch].start(w_attributes, n);
      v.dcolor[ch] = s.color[ch].step;
    }
  }
  for (unsigned u = 0; u < c.unit_count; ++u) {
    v.sq_fine[u] = s.sq[u].start_fine(w_attributes, n);
    v.tq_fine[u] = s.tq[u].start_fine(w_attributes, n);
    v.dsq[u] = s.sq[u].step_fine;
    v.dtq[u] = s.tq[u].step_fine;
  }
  if (c.texture || s.perspective_color || (c.fog && s.perspective)) {
    v.q_fine = s.q.start_fine(w_attributes, n);
    v.dq = s.q.step_fine;
  }
  if (c.fog) {
    v.fog = s.fog.start(w_attributes, n);
    v.dfog = s.fog.step;
  }
  return v;
}

// Stencil and depth tests of pixel i; updates the stencil value.
inline bool fragment_tests(const DrawContext& c, const SpanRows& rows, int i, uint16_t z16) {
  const gl::RasterState& state = *c.state;
  if (c.stencil_test) {
    const uint8_t stencil_ref = state.stencil_ref, stencil_mask = state.stencil_value_mask;
    const uint8_t stencil_write_mask = state.stencil_write_mask;
    const uint8_t old = rows.stencil_new[i];
    if (!compare_passes<uint8_t>(state.stencil_func, stencil_ref & stencil_mask, old & stencil_mask)) {
      rows.stencil_new[i] = stencil_op_result(state.stencil_fail, old, stencil_ref, stencil_write_mask);
      return false;
    }
    if (c.depth_test && !compare_passes(state.depth_func, z16, rows.depth_old[i])) {
      rows.stencil_new[i] = stencil_op_result(state.depth_fail, old, stencil_ref, stencil_write_mask);
      return false;
    }
    rows.stencil_new[i] = stencil_op_result(state.depth_pass, old, stencil_ref, stencil_write_mask);
    return true;
  }
  return !c.depth_test || compare_passes(state.depth_func, z16, rows.depth_old[i]);
}

// lambda (16.16) at a pixel from unit i's stepped (s q), (t q), q and its
// planes' gradients: du/dx = (gx(sq) q - sq gx(q)) / q^2 2^(30 - F) in
// level 0's texels, the gradients g 2^-e (LodGradients). Each product is
// below 2^59 (|g| <= 2^30, q <= 2^30, |sq| < 2^30), each difference below
// 2^60; lambda = log2(max) - 2 log2(q) + 30 - F - e.
inline int32_t pixel_lod(const TriangleSetup& s, unsigned i, int32_t sq_value, int32_t tq_value, int32_t q_value) {
  const LodGradients& g = s.lod_gradients[i];
  if (!g.moves) return renderers::LOD_MAGNIFIED;
  auto magnitude = [](int64_t v) { return uint64_t(v < 0 ? -v : v); };
  const uint64_t ux = magnitude(int64_t{g.sx} * q_value - int64_t{sq_value} * g.qx);
  const uint64_t uy = magnitude(int64_t{g.sy} * q_value - int64_t{sq_value} * g.qy);
  const uint64_t vx = magnitude(int64_t{g.tx} * q_value - int64_t{tq_value} * g.qx);
  const uint64_t vy = magnitude(int64_t{g.ty} * q_value - int64_t{tq_value} * g.qy);
  const int32_t scale =
      (Q_FRACTION_BITS - s.st_bits[i] - g.exponent) * renderers::LOD_ONE - 2 * renderers::log2_q16(uint64_t(q_value));
  return renderers::texture_lod_q16(ux, vx, uy, vy, scale);
}

// value 2^k / q from the pixel's 1/q (see shade_general).
inline int64_t divide(const renderers::Reciprocal& inverse_q, int32_t value, int scale_bits) {
  int64_t product = int64_t{value} * inverse_q.r;
  const int shift = inverse_q.shift - scale_bits;  // >= 0 for every scale below
  if (product < 0) product += (int64_t{1} << shift) - 1;
  return product >> shift;
}

// The pixel's colour after its texture units, from its primary colour rgba.
inline uint32_t texture_pixel(const DrawContext& c, const TriangleSetup& s, const int32_t sq[], const int32_t tq[],
                              int32_t q, const renderers::Reciprocal& inverse_q, uint32_t rgba, PixelMemory& memory,
                              SpanCounts& counts) {
  const gl::RasterState& state = *c.state;
  // One reciprocal of q per pixel serves every unit (texel_calls).
  if (s.perspective) ++counts.texel_calls;
  const uint32_t primary = rgba;
  for (unsigned u = 0; u < c.unit_count; ++u) {
    // Texel coordinates with 8 fraction bits: (s q 2^F) 2^(38 - F) / q,
    // |.| < 2^23 inside the triangle (|s W| <= 2^15), clamped to 2^30.
    const int bits = s.st_bits[u];
    int64_t u8, v8;
    if (s.perspective) {
      u8 = divide(inverse_q, sq[u], 8 + Q_FRACTION_BITS - bits);
      v8 = divide(inverse_q, tq[u], 8 + Q_FRACTION_BITS - bits);
    } else {
      u8 = sq[u] >> (bits - 8);
      v8 = tq[u] >> (bits - 8);
    }
    u8 = std::clamp<int64_t>(u8, -(int64_t{1} << 30), int64_t{1} << 30);
    v8 = std::clamp<int64_t>(v8, -(int64_t{1} << 30), int64_t{1} << 30);
    const gl::TextureUnit& unit = state.unit[c.units[u]];
    uint8_t texel[4];
    if (s.lod[u]) {
      // The unit's own level of detail, from its coordinates' gradients.
      auto filter_level = [&](unsigned level, int fu, int fv, bool linear, uint8_t filtered[4]) {
        fetch_texel(memory, unit.tex, level, fu, fv, linear, filtered);
      };
      const renderers::LodChoice choice = renderers::sample_texture_lod_q16(
          unit.tex, int(u8), int(v8), pixel_lod(s, u, sq[u], tq[u], q), filter_level, texel);
      if (s.perspective) ++counts.lods;
      (choice.linear ? counts.lod_linear : counts.lod_nearest) += choice.count;
      counts.mipmap_blends += choice.count - 1;
    } else {
      fetch_texel(memory, unit.tex, 0, int(u8), int(v8), s.linear_filter[u], texel);
    }
    // The unit's base format rules (fill_missing_components) apply
    // before its environment, inside apply_texture_unit.
    rgba = renderers::apply_texture_unit(unit, rgba, primary, texel);
  }
  return rgba;
}

// The spans most scenes draw (no texture, fog, stencil or alpha test:
// depth and colour only) take a loop of their own, specialised on the
// depth function, with few live values: the general loop below keeps
// every stage's state and spilled it (about 180 ARM instructions per
// pixel for a Gouraud, depth-tested pixel). Same arithmetic, same
// charges.
template <typename Passes>
void shade_plain(const DrawContext& c, const TriangleSetup& s, const Interpolants& v, int n, const SpanRows& rows,
                 SpanCounts& counts, Passes passes) {
  const uint16_t* const depth_old = rows.depth_old;
  uint16_t* const depth_new = rows.depth_new;
  uint8_t* const pass = rows.pass;
  uint32_t* const source = rows.source;
  const int32_t dz = v.dz;
  int32_t depth = v.z, r = v.color[0], g = v.color[1], b = v.color[2], a = v.color[3];
  const int32_t dr = v.dcolor[0], dg = v.dcolor[1], db = v.dcolor[2], da = v.dcolor[3];
  int64_t q_value = v.q_fine;
  const int64_t dq = v.dq;
  const bool divide = s.perspective_color, gouraud = c.gouraud;
  const uint32_t flat = s.flat_rgba;
  uint32_t count = 0;
  for (int i = 0; i < n; ++i) {
    const uint16_t z16 = uint16_t(uint32_t(depth) >> (8 + DEPTH_FRACTION_BITS));
    const bool alive = passes(z16, depth_old[i]);
    if (alive) {
      uint32_t rgba;
      if (divide) {
        // As the general loop: c/w times the pixel's reciprocal of q.
        const renderers::Reciprocal inverse = renderers::make_reciprocal(uint32_t(q_value >> FINE_BITS));
        const int shift = inverse.shift - Q_FRACTION_BITS;  // >= 0
        const int64_t round = (int64_t{1} << shift) - 1;
        const int32_t channels[4] = {r, g, b, a};
        rgba = 0;
        for (int ch = 0; ch < 4; ++ch) {
          int64_t product = int64_t{channels[ch]} * inverse.r;
          if (product < 0) product += round;
          const int64_t value = ((product >> shift) + (1 << (COLOR_FRACTION_BITS - 1))) >> COLOR_FRACTION_BITS;
          rgba |= uint32_t(std::clamp<int64_t>(value, 0, 255)) << (8 * ch);
        }
      } else if (gouraud) {
        rgba = uint32_t(r >> COLOR_FRACTION_BITS) | uint32_t(g >> COLOR_FRACTION_BITS) << 8 |
               uint32_t(b >> COLOR_FRACTION_BITS) << 16 | uint32_t(a >> COLOR_FRACTION_BITS) << 24;
      } else {
        rgba = flat;
      }
      source[i] = rgba;
    }
    pass[i] = alive;
    depth_new[i] = z16;
    count += alive;
    advance(depth, dz);
    advance(r, dr);
    advance(g, dg);
    advance(b, db);
    advance(a, da);
    q_value += dq;
  }
  counts.shaded = counts.passed = count;
  if (divide) counts.color_divisions = count;
}

// Every other span: each stage in turn, with the tests where the state puts
// them (early depth, or alpha first and then stencil and depth).
void shade_general(const DrawContext& c, const TriangleSetup& s, Interpolants& v, int n, const SpanRows& rows,
                   PixelMemory& memory, SpanCounts& counts) {
  const gl::RasterState& state = *c.state;
  const bool early_depth_only = !c.late_tests && !c.stencil_test;
  const CompareFunc depth_func = c.depth_test ? state.depth_func : CompareFunc::always;
  const bool step_q = c.texture || s.perspective_color || (c.fog && s.perspective);
  int32_t sq[gl::MAX_TEXTURE_UNITS] = {}, tq[gl::MAX_TEXTURE_UNITS] = {};
  for (int i = 0; i < n; ++i) {
    const uint16_t z16 = uint16_t(uint32_t(v.z) >> (8 + DEPTH_FRACTION_BITS));
    bool alive = early_depth_only ? compare_passes(depth_func, z16, rows.depth_old[i])
                                  : (c.late_tests || fragment_tests(c, rows, i, z16));
    if (alive) {
      ++counts.shaded;
      const int32_t q = step_q ? int32_t(v.q_fine >> FINE_BITS) : int32_t{1} << Q_FRACTION_BITS;
      for (unsigned u = 0; u < c.unit_count; ++u) {
        sq[u] = int32_t(v.sq_fine[u] >> FINE_BITS);
        tq[u] = int32_t(v.tq_fine[u] >> FINE_BITS);
      }
      // The pixel's 1/q, when anything divides: q in [1, 2^30] is
      // normalised to m in [2^29, 2^30), 1/q ~ r / 2^shift with r =
      // floor(2^59 / m) (one 32-bit division, a Newton step, a correction;
      // renderers/common/fixed_math.h), shift = 29 + length(q). A value x
      // times 2^k / q is then (x r) >> (shift - k), x r below 2^61,
      // truncated toward zero; within 2^-29 of the exact quotient.
      renderers::Reciprocal inverse_q;
      if (s.perspective) inverse_q = renderers::make_reciprocal(uint32_t(q));
      uint32_t rgba;
      if (s.perspective_color) {
        // c/w over 1/w: one reciprocal of q per pixel (shared with the
        // texture coordinates), then a multiply per channel.
        rgba = 0;
        for (int ch = 0; ch < 4; ++ch) {
          const int64_t value = (divide(inverse_q, v.color[ch], Q_FRACTION_BITS) + (1 << (COLOR_FRACTION_BITS - 1))) >>
                                COLOR_FRACTION_BITS;
          rgba |= uint32_t(std::clamp<int64_t>(value, 0, 255)) << (8 * ch);
        }
        if (!c.texture) ++counts.color_divisions;
      } else if (c.gouraud) {
        rgba = uint32_t(v.color[0] >> COLOR_FRACTION_BITS) | uint32_t(v.color[1] >> COLOR_FRACTION_BITS) << 8 |
               uint32_t(v.color[2] >> COLOR_FRACTION_BITS) << 16 | uint32_t(v.color[3] >> COLOR_FRACTION_BITS) << 24;
      } else {
        rgba = s.flat_rgba;
      }
      if (c.texture) rgba = texture_pixel(c, s, sq, tq, q, inverse_q, rgba, memory, counts);
      if (c.fog) {
        // After texturing, before the fragment operations (ES 1.1, 3.8).
        int64_t argument = v.fog;
        if (s.perspective) {
          argument = divide(inverse_q, v.fog, Q_FRACTION_BITS);
          // The reciprocal of q is shared with the texture coordinates or
          // the colours when they divide too.
          if (!c.texture && !s.perspective_color) ++counts.fog_divisions;
        }
        const auto a = int32_t(std::clamp<int64_t>(argument, INT32_MIN, INT32_MAX));
        rgba = fog_blend(fog_factor(state.fog_mode, a), rgba, c.fog_rgba);
      }
      if (c.alpha_test && !compare_passes<uint32_t>(state.alpha_func, rgba >> 24, state.alpha_ref)) {
        alive = false;
      } else if (c.late_tests) {
        alive = fragment_tests(c, rows, i, z16);
      }
      rows.source[i] = rgba;
    }
    rows.pass[i] = alive;
    rows.depth_new[i] = z16;
    counts.passed += alive;
    advance(v.z, v.dz);
    for (int ch = 0; ch < 4; ++ch) advance(v.color[ch], v.dcolor[ch]);
    for (unsigned u = 0; u < c.unit_count; ++u) {
      v.sq_fine[u] += v.dsq[u];
      v.tq_fine[u] += v.dtq[u];
    }
    if (step_q) v.q_fine += v.dq;
    advance(v.fog, v.dfog);
  }
}

}  // namespace

void shade_pixels(const DrawContext& c, const TriangleSetup& s, int j, int x_first, int n, const SpanRows& rows,
                  PixelMemory& memory, SpanCounts& counts) {
  Interpolants v = start_interpolants(c, s, j, x_first, n);
  const bool early_depth_only = !c.late_tests && !c.stencil_test;
  if (!early_depth_only || c.texture || c.fog) {
    shade_general(c, s, v, n, rows, memory, counts);
    return;
  }
  switch (c.depth_test ? c.state->depth_func : CompareFunc::always) {
    case CompareFunc::less:
      shade_plain(c, s, v, n, rows, counts, [](uint16_t in, uint16_t old) { return in < old; });
      break;
    case CompareFunc::lequal:
      shade_plain(c, s, v, n, rows, counts, [](uint16_t in, uint16_t old) { return in <= old; });
      break;
    case CompareFunc::always: shade_plain(c, s, v, n, rows, counts, [](uint16_t, uint16_t) { return true; }); break;
    default: {
      const CompareFunc depth_func = c.state->depth_func;
      shade_plain(c, s, v, n, rows, counts,
                  [depth_func](uint16_t in, uint16_t old) { return compare_passes(depth_func, in, old); });
    }
  }
}

void charge_span(const DrawContext& c, const TriangleSetup& s, int n, const SpanCounts& counts, PixelMemory& memory) {
  uint32_t nearest_units = 0, linear_units = 0;
  for (unsigned u = 0; u < c.unit_count; ++u) {
    if (!s.lod[u]) ++(s.linear_filter[u] ? linear_units : nearest_units);
  }
  memory.charge(HostCost::arm_span);
  memory.charge(HostCost::arm_span_attribute, c.attributes);
  memory.charge(HostCost::arm_pixel, uint64_t(n));
  if (c.depth_test) memory.charge(HostCost::arm_pixel_depth, uint64_t(n));
  if (c.stencil_test) memory.charge(HostCost::arm_pixel_stencil, uint64_t(n));
  if (c.gouraud) memory.charge(HostCost::arm_pixel_color, uint64_t(n));
  if (c.texture) memory.charge(HostCost::arm_pixel_texcoord, uint64_t(n) * c.unit_count);
  if (c.fog) memory.charge(HostCost::arm_pixel_fog, uint64_t(n));
  memory.charge(HostCost::arm_shaded_pixel, counts.shaded);
  memory.charge(HostCost::arm_texel_nearest, uint64_t(counts.shaded) * nearest_units + counts.lod_nearest);
  memory.charge(HostCost::arm_texel_linear, uint64_t(counts.shaded) * linear_units + counts.lod_linear);
  memory.charge(HostCost::arm_mipmap_blend, counts.mipmap_blends);
  memory.charge(HostCost::arm_lod, counts.lods);
  memory.charge(HostCost::arm_division, uint64_t(counts.texel_calls) + counts.color_divisions + counts.fog_divisions);
  if (s.perspective_color) memory.charge(HostCost::arm_perspective_color, counts.shaded);
  memory.charge(HostCost::arm_texture_environment, uint64_t(counts.shaded) * c.environments);
  memory.charge(HostCost::arm_texture_combine, uint64_t(counts.shaded) * c.combines);
  memory.charge(HostCost::arm_texture_combine_argument, uint64_t(counts.shaded) * c.combine_arguments);
  if (c.fog) memory.charge(HostCost::arm_fog, counts.shaded);
  if (c.alpha_test) memory.charge(HostCost::arm_alpha_test, counts.shaded);
  if (c.color_write) memory.charge(HostCost::arm_color_write, counts.passed);
  if (c.reads_destination) memory.charge(HostCost::arm_color_read_back, counts.passed);
  if (c.depth_write) memory.charge(HostCost::arm_depth_write, counts.passed);
}

}  // namespace tessera::arm
