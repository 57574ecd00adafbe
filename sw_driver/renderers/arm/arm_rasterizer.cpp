// Scan conversion, span shading and the per-fragment operations of the arm
// renderer; formats, rounding and the fill rule are stated in
// arm_rasterizer.h, instruction counts in README.md.
#include "renderers/arm/arm_rasterizer.h"

#include <algorithm>
#include <cstring>

#include "renderers/common/fixed_math.h"
#include "renderers/common/fog.h"
#include "renderers/common/fragment_ops.h"
#include "renderers/common/texturing.h"

namespace tessera::arm {

namespace {

using gl::BlendFactor;
using gl::CompareFunc;
using gl::LogicOp;
using gl::StencilOp;

// Ranges. The front end delivers 9.4 vertices in [0, 8191] (the 512-pixel
// screen, gl/geometry.h MAX_SCREEN_COORDINATE); the core takes any vertex
// with |x|, |y| <= MAX_COORDINATE = 2^14 - 1 (about +-1024 pixels) and skips
// a triangle with a vertex beyond. From that, in 9.4 units:
// - edge vectors: |dx|, |dy| <= 2^15 - 2;
// - twice the area, A = dx1 dy2 - dx2 dy1: |A| <= 2 (2^15 - 2)^2 < 2^31;
// - an edge DDA's numerator (xt - 8) d + (yt - yc) dx: |.| < 2^29 + 2^30,
//   as the walked row's centre yc lies between the edge's ends (|yt - yc|
//   <= d), and its divisor 16 d < 2^19: all int32, one 32-bit division each.
constexpr int32_t MAX_COORDINATE = (1 << 14) - 1;
// The window positions before snapping, for the attribute planes of a
// perspective textured triangle, are taken to 1/256 pixel while they lie
// within +-2^10 pixels (else the snapped vertices serve): |d| < 2^19 and
// |A| < 2^39 in those units, int64.
constexpr int UNSNAPPED_BITS = 8;
constexpr float MAX_UNSNAPPED = 1024.0f;
constexpr int COLOR_FRACTION_BITS = 16;
constexpr int DEPTH_FRACTION_BITS = 7;    // interpolant = z24 << 7 < 2^31
constexpr int Q_FRACTION_BITS = 30;       // normalised 1/w in (0, 1], as 1 .. 2^30
constexpr int ST_MAX_FRACTION_BITS = 24;  // s * width * q with F <= 24 fraction bits, |.| < 2^30
constexpr float MAX_TEXELS = 32768.0f;    // |s * width| is clamped to this
// Every plane's vertex values lie within [-2^30, 2^31) and differ by less
// than 2^31 (depth: [0, 2^31 - 128]; colour: < 2^24; q: [1, 2^30]; s q and
// t q: |.| < 2^30; fog: clamped to +-2^30), so that a difference times a
// barycentric weight (|w| < 2 in 2.30) is below 2^62.
constexpr int32_t MAX_FOG_VALUE = 1 << 30;

// One step of a span's interpolant, wrapping as the ARM's ADD does: the
// values the span's pixels use stay within their clamped range, but the
// step after its last pixel may leave int32 (a signed overflow, undefined
// in C++; the same bits on the ARM).
inline void advance(int32_t& value, int32_t delta) {
  value = int32_t(uint32_t(value) + uint32_t(delta));
}

int32_t floor_div(int32_t a, int32_t b) {  // b > 0: a 32-bit division
  int32_t q = a / b;
  if ((a % b) != 0 && a < 0) --q;
  return q;
}

int32_t ceil_div(int32_t a, int32_t b) {
  return -floor_div(-a, b);
}  // b > 0

bool finite(float f) {
  return f == f && f - f == 0.0f;  // not NaN, not infinite (no libm)
}

bool has_window_positions(const gl::Triangle& tri) {
  for (const gl::ScreenVertex& v : tri.v) {
    if (!finite(v.x_window) || !finite(v.y_window)) return false;
    if (v.x_window >= MAX_UNSNAPPED || v.x_window <= -MAX_UNSNAPPED || v.y_window >= MAX_UNSNAPPED ||
        v.y_window <= -MAX_UNSNAPPED)
      return false;
  }
  return true;
}

// Rounded to nearest, halves away from zero; |f| < 2^30.
int32_t round_to_int(float f) {
  return static_cast<int32_t>(f >= 0 ? f + 0.5f : f - 0.5f);
}

// llround(x / 2) for an integer x.
int64_t halve_rounded(int64_t x) {
  return x >= 0 ? (x + 1) >> 1 : -((-x + 1) >> 1);
}

// The frame the attribute planes are set up in: vertex 0 and the edge
// vectors to vertices 1 and 2, in units of 2^-bits pixel (bits = 4: the
// snapped 9.4 vertices; UNSNAPPED_BITS: the window positions), twice the
// area A (nonzero) and 1/|A|.
struct Basis {
  int bits = 4;
  int64_t x0 = 0, y0 = 0, dx1 = 0, dy1 = 0, dx2 = 0, dy2 = 0;
  int64_t area = 0;
  renderers::Reciprocal inverse;

  // False when the area is zero.
  bool init(int fraction_bits, const int64_t x[3], const int64_t y[3]) {
    bits = fraction_bits;
    x0 = x[0];
    y0 = y[0];
    dx1 = x[1] - x[0];
    dy1 = y[1] - y[0];
    dx2 = x[2] - x[0];
    dy2 = y[2] - y[0];
    area = dx1 * dy2 - dx2 * dy1;
    if (area == 0) return false;
    inverse = renderers::make_reciprocal(uint64_t(area < 0 ? -area : area));
    return true;
  }

  // N / A scaled by 2^k, for a numerator N (|N| < 2^62).
  int64_t over_area(int64_t n, int k) const { return renderers::scaled_quotient(area < 0 ? -n : n, inverse, k); }

  // The barycentric weights of vertices 1 and 2 at the centre of pixel (i,
  // j), in 2.30: w = E / A with E the edge function, both in [0, 1] for a
  // centre inside the triangle (every span's first pixel: the fill rule
  // puts its centre inside the snapped triangle, within 1/32 pixel of the
  // unsnapped one), clamped to +-2 otherwise. |E| < 2^38 (a centre within
  // 2^10 pixels of vertex 0, an edge shorter than 2^11 pixels).
  void weights(int i, int j, int32_t w[2]) const {
    const int64_t x = (2 * int64_t{i} + 1) * (int64_t{1} << (bits - 1)) - x0;
    const int64_t y = (2 * int64_t{j} + 1) * (int64_t{1} << (bits - 1)) - y0;
    const int64_t e[2] = {x * dy2 - y * dx2, y * dx1 - x * dy1};
    for (int k = 0; k < 2; ++k) {
      const int64_t v = over_area(e[k], 30);
      w[k] = int32_t(std::clamp<int64_t>(v, -(int64_t{1} << 31) + 1, (int64_t{1} << 31) - 1));
    }
  }

  // The numerators of an attribute's gradients: d/dx = nx 2^bits / A, d/dy
  // = ny 2^bits / A per pixel, for vertex differences |d1|, |d2| < 2^31:
  // |n| < 2^51.
  void numerators(int64_t d1, int64_t d2, int64_t* nx, int64_t* ny) const {
    *nx = d1 * dy2 - d2 * dy1;
    *ny = d2 * dx1 - d1 * dx2;
  }
};

// One attribute's plane in fixed point: the value at vertex 0 and the
// differences to vertices 1 and 2, evaluated at a span's first pixel from
// the barycentric weights there: v0 + floor((d1 w1 + d2 w2) / 2^30), each
// product below 2^62. Values inside the triangle are convex combinations of
// the vertex values, so every start value is clamped to [lo, hi] and nudged
// so that stepping to the span's end stays there. The step per pixel is the
// x gradient rounded to nearest (halves away from zero) and clamped to
// +-(hi - lo).
//
// The planes the perspective divide reads (q, s q, t q: |values| < 2^30)
// are also kept with FINE_BITS more fraction bits (start_fine, step_fine:
// value 2^29, below 2^59; the start is (v0 2^29 + d1 w1 / 2 + d2 w2 / 2),
// each term below 2^61), stepped by 64-bit adds (ADDS, ADC), so that a
// rounded step's error (half a unit per pixel, 256 units over a 512-pixel
// span) does not add up: where 1/w falls 1000 times across a triangle,
// 256 units of s q moved u by several texels.
constexpr int FINE_BITS = 29;

struct Plane {
  int32_t v0 = 0, d1 = 0, d2 = 0;
  int32_t lo = 0, hi = 0, step = 0;
  int64_t step_fine = 0;  // the x gradient in 2^-FINE_BITS units, for fine planes

  void setup(const int32_t v[3], const Basis& basis, bool fine = false) {
    v0 = v[0];
    d1 = v[1] - v[0];
    d2 = v[2] - v[0];
    lo = std::min({v[0], v[1], v[2]});
    hi = std::max({v[0], v[1], v[2]});
    int64_t nx, ny;
    basis.numerators(d1, d2, &nx, &ny);
    const int64_t range = int64_t{hi} - lo;
    step = int32_t(std::clamp<int64_t>(halve_rounded(basis.over_area(nx, basis.bits + 1)), -range, range));
    if (fine) {
      const int64_t fine_range = range << FINE_BITS;  // < 2^60
      step_fine =
          std::clamp<int64_t>(halve_rounded(basis.over_area(nx, basis.bits + FINE_BITS + 1)), -fine_range, fine_range);
    }
  }

  // Value at the first pixel of a span of n pixels, whose weights are w.
  int32_t start(const int32_t w[2], int n) const {
    const int64_t v = int64_t{v0} + ((int64_t{d1} * w[0] + int64_t{d2} * w[1]) >> 30);
    int64_t s = std::clamp<int64_t>(v, lo, hi);
    const int64_t end = s + int64_t{step} * (n - 1);
    if (end < lo) s += lo - end;
    if (end > hi) s -= end - hi;
    return int32_t(std::clamp<int64_t>(s, lo, hi));
  }

  // The same in 2^-FINE_BITS units, stepped by step_fine.
  int64_t start_fine(const int32_t w[2], int n) const {
    // Scaled by a multiply: lo, hi and v0 may be negative, and a left shift
    // of a negative value is undefined (the same bits on the ARM).
    constexpr int64_t FINE_UNIT = int64_t{1} << FINE_BITS;
    const int64_t low = int64_t{lo} * FINE_UNIT, high = int64_t{hi} * FINE_UNIT;
    const int64_t v = int64_t{v0} * FINE_UNIT + ((int64_t{d1} * w[0]) >> 1) + ((int64_t{d2} * w[1]) >> 1);
    int64_t s = std::clamp<int64_t>(v, low, high);
    // |step_fine| (n - 1) stays below 2^62 unless the step is far beyond
    // the span's reach (a sliver's): then the start is only clamped.
    const uint64_t magnitude = uint64_t(step_fine < 0 ? -step_fine : step_fine);
    if (n > 1 && renderers::bit_length64(magnitude) + renderers::bit_length(uint32_t(n - 1)) <= 62) {
      const int64_t end = s + step_fine * (n - 1);
      if (end < low) s += low - end;
      if (end > high) s -= end - high;
    }
    return std::clamp<int64_t>(s, low, high);
  }
};

// The gradients of a texture unit's s q, t q and of q, for its level of
// detail: g = gradient 2^-exponent, |g| < 2^30, one exponent for the six so
// that the pixel's derivatives of u = (s q) / q keep their ratio.
struct LodGradients {
  int32_t sx = 0, sy = 0, tx = 0, ty = 0, qx = 0, qy = 0;
  int exponent = 0;
  bool moves = false;  // a texture that does not move has lambda = -inf

  void setup(const Plane& sq, const Plane& tq, const Plane& q, const Basis& basis) {
    int64_t n[6];
    basis.numerators(sq.d1, sq.d2, &n[0], &n[1]);
    basis.numerators(tq.d1, tq.d2, &n[2], &n[3]);
    basis.numerators(q.d1, q.d2, &n[4], &n[5]);
    unsigned longest = 0;
    for (int64_t v : n) longest = std::max(longest, renderers::bit_length64(uint64_t(v < 0 ? -v : v)));
    moves = longest != 0;
    if (!moves) return;
    // |n 2^(bits + k) / A| < 2^(longest + bits + k - length(A) + 1) = 2^29.
    const int area_length = int(renderers::bit_length64(uint64_t(basis.area < 0 ? -basis.area : basis.area)));
    const int k = 28 - int(longest) - basis.bits + area_length;
    exponent = k;
    int32_t* out[6] = {&sx, &sy, &tx, &ty, &qx, &qy};
    for (int i = 0; i < 6; ++i) {
      const int64_t g = basis.over_area(n[i], basis.bits + k);
      *out[i] = int32_t(std::clamp<int64_t>(g, -(int64_t{1} << 30), int64_t{1} << 30));
    }
  }
};

// Exact round(x / 255) for 0 <= x <= 65025.

// Depth (16 bits) and colour words of a clear, little-endian, 2 or 4 bytes.
inline uint32_t load_le(const uint8_t* p, unsigned bytes) {
  return bytes == 2 ? uint32_t(p[0]) | uint32_t(p[1]) << 8
                    : uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

inline void store_le(uint8_t* p, unsigned bytes, uint32_t value) {
  p[0] = uint8_t(value);
  p[1] = uint8_t(value >> 8);
  if (bytes == 4) {
    p[2] = uint8_t(value >> 16);
    p[3] = uint8_t(value >> 24);
  }
}

using renderers::blend;
using renderers::factor_reads_destination;
using renderers::logic_op;
using renderers::logic_op_reads_destination;

// A wrap code without an entry acts as repeat (fixed_function.def).
inline int wrap(int i, unsigned size, gl::TexWrap mode) {
  return renderers::wrap_texel(i, size, mode);
}

// How many arguments a GL_COMBINE function reads (ES 1.1 table 3.18).
unsigned combine_arguments(gl::CombineFunc func) {
  switch (func) {
    case gl::CombineFunc::replace: return 1;
    case gl::CombineFunc::interpolate: return 3;
    default: return 2;
  }
}

}  // namespace

struct ArmRasterizer::TriangleSetup {
  // Depth follows the snapped vertices; colour, q, the texture coordinates
  // and fog follow `attributes`, the unsnapped positions of a perspective
  // textured triangle (draw_triangle), else the same snapped frame.
  Basis snapped, unsnapped;
  bool use_unsnapped = false;
  Plane z, color[4], q, fog;
  Plane sq[gl::MAX_TEXTURE_UNITS], tq[gl::MAX_TEXTURE_UNITS];  // per unit of DrawContext::units
  int st_bits[gl::MAX_TEXTURE_UNITS] = {};                     // F: s q and t q are s W q 2^F, t H q 2^F
  LodGradients lod_gradients[gl::MAX_TEXTURE_UNITS];
  uint32_t flat_rgba = 0;
  bool perspective = false;        // the vertices' 1/w differ
  bool perspective_color = false;  // Gouraud colours divided by q per pixel, as GL interpolates them
  bool linear_filter[gl::MAX_TEXTURE_UNITS] = {};
  // Per unit: the level of detail chooses filter and levels (texturing.h).
  bool lod[gl::MAX_TEXTURE_UNITS] = {};
};

struct ArmRasterizer::DrawContext {
  const gl::RasterState* state = nullptr;
  int clip_x0 = 0, clip_x1 = -1, clip_y0 = 0, clip_y1 = -1;  // inclusive, GL coordinates
  bool depth_test = false, depth_write = false;
  bool stencil_test = false, stencil_writes = false;
  bool alpha_test = false, texture = false, gouraud = false;
  // The texture units drawn, in order (enabled, with a usable texture).
  unsigned units[gl::MAX_TEXTURE_UNITS] = {};
  unsigned unit_count = 0;
  bool fog = false;
  renderers::FogCoefficientsF fog_coefficients;
  uint32_t fog_rgba = 0;
  bool late_tests = false;  // alpha test first, then stencil and depth
  bool color_write = false, needs_destination = false, blend = false, logic_op = false;
  uint32_t color_write_mask = 0;  // packed bits that are written
  // What the host is charged for (sw_driver/costs): attributes set up and
  // stepped, texture environments applied per shaded pixel (GL_COMBINE
  // apart), whether a written pixel reads the destination back.
  unsigned attributes = 0;
  unsigned environments = 0, combines = 0, combine_arguments = 0;
  bool reads_destination = false;
};

ArmRasterizer::ArmRasterizer(PixelMemory& memory, const FrameBuffers& buffers)
    : m_memory(memory),
      m_buffers(buffers),
      m_depth_old(buffers.width),
      m_depth_new(buffers.width),
      m_stencil_old(buffers.width),
      m_stencil_new(buffers.width),
      m_pass(buffers.width),
      m_source(buffers.width) {}

void ArmRasterizer::clear(const gl::ClearRequest& request) {
  const int w = int(m_buffers.width), h = int(m_buffers.height);
  int x0 = 0, x1 = w - 1, y0 = 0, y1 = h - 1;
  if (request.scissor_test) {
    x0 = std::max(x0, request.scissor_x);
    y0 = std::max(y0, request.scissor_y);
    x1 = std::min<int64_t>(x1, int64_t(request.scissor_x) + request.scissor_width - 1);
    y1 = std::min<int64_t>(y1, int64_t(request.scissor_y) + request.scissor_height - 1);
  }
  if (x0 > x1 || y0 > y1) return;
  const unsigned n = unsigned(x1 - x0 + 1);
  // Rows y1 .. y0 are consecutive in memory (display order), so full-width
  // rows are cleared as one block; a masked clear reads and merges row by
  // row through the scratch row.
  const bool whole_rows = x0 == 0 && x1 == w - 1;
  auto fill = [&](uint32_t base, unsigned size, uint32_t value, uint32_t mask, uint32_t all_bits) {
    if ((mask & all_bits) == 0) return;
    const bool masked = (mask & all_bits) != all_bits;
    const bool one_block = whole_rows && !masked;
    const unsigned elements = one_block ? n * unsigned(y1 - y0 + 1) : n;
    for (int y = y1; y >= (one_block ? y1 : y0); --y) {
      const uint32_t address = base + (uint32_t(h - 1 - y) * m_buffers.width + uint32_t(x0)) * size;
      if (masked) {
        const uint8_t* old = m_memory.load(address, size, elements);
        for (unsigned k = 0; k < elements; ++k)
          m_source[k] = ((size == 1 ? old[k] : load_le(old + k * size, size)) & ~mask) | (value & mask);
        uint8_t* out = m_memory.store(address, size, elements);
        for (unsigned k = 0; k < elements; ++k) {
          if (size == 1)
            out[k] = uint8_t(m_source[k]);
          else
            store_le(out + k * size, size, m_source[k]);
        }
        m_memory.charge(HostCost::arm_clear_masked_pixel, elements);
      } else {
        uint8_t* out = m_memory.store(address, size, elements);
        if (size == 1) {
          std::memset(out, int(value & 0xff), elements);
        } else {
          for (unsigned k = 0; k < elements; ++k) store_le(out + k * size, size, value);
        }
        m_memory.charge(HostCost::arm_clear_block, (uint64_t(elements) * size + 31) / 32);
      }
      m_memory.charge(HostCost::arm_clear_row);
    }
  };

  const PixelFormat format = m_buffers.color_format;
  const unsigned bpp = bytes_per_pixel(format);
  const uint32_t all_color = channel_bits(format, 0xf);
  if (request.color) {
    uint32_t rgba = 0;
    unsigned color_mask = 0;
    for (unsigned ch = 0; ch < 4; ++ch) {
      rgba |= uint32_t(request.rgba[ch]) << (8 * ch);
      color_mask |= request.color_mask[ch] ? 1u << ch : 0u;
    }
    fill(m_buffers.color_address, bpp, pack_pixel(format, rgba), channel_bits(format, color_mask), all_color);
  }
  if (request.depth && request.depth_write) {
    const uint32_t z16 = std::min<uint32_t>(request.depth_value, 0xffffff) >> 8;
    fill(m_buffers.depth_address, 2, z16, 0xffff, 0xffff);
  }
  if (request.stencil) {
    fill(m_buffers.stencil_address, 1, request.stencil_value, request.stencil_write_mask, 0xff);
  }
}

void ArmRasterizer::draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) {
  DrawContext c;
  c.state = &state;
  c.clip_x0 = 0;
  c.clip_y0 = 0;
  c.clip_x1 = int(m_buffers.width) - 1;
  c.clip_y1 = int(m_buffers.height) - 1;
  if (state.scissor_test) {
    c.clip_x0 = std::max(c.clip_x0, state.scissor_x);
    c.clip_y0 = std::max(c.clip_y0, state.scissor_y);
    c.clip_x1 = int(std::min<int64_t>(c.clip_x1, int64_t(state.scissor_x) + state.scissor_width - 1));
    c.clip_y1 = int(std::min<int64_t>(c.clip_y1, int64_t(state.scissor_y) + state.scissor_height - 1));
  }
  if (c.clip_x0 > c.clip_x1 || c.clip_y0 > c.clip_y1 || triangles == nullptr) return;

  const PixelFormat format = m_buffers.color_format;
  c.depth_test = state.depth_test;
  c.depth_write = state.depth_test && state.depth_write;
  c.stencil_test = state.stencil_test;
  c.stencil_writes = state.stencil_test && state.stencil_write_mask != 0 &&
                     (state.stencil_fail != StencilOp::keep || state.depth_fail != StencilOp::keep ||
                      state.depth_pass != StencilOp::keep);
  c.alpha_test = state.alpha_test;
  c.late_tests = state.alpha_test;
  c.gouraud = !state.flat_shading;
  c.fog = state.fog;
  if (c.fog) {
    c.fog_coefficients = renderers::fog_coefficients_f(state);
    c.fog_rgba = renderers::fog_rgba(state);
  }
  for (unsigned u = 0; u < gl::MAX_TEXTURE_UNITS; ++u) {
    const gl::TextureUnit& unit = state.unit[u];
    const gl::Texture& tex = unit.tex;
    if (unit.enabled && tex.width > 0 && tex.height > 0 && (tex.width & (tex.width - 1)) == 0 &&
        (tex.height & (tex.height - 1)) == 0)
      c.units[c.unit_count++] = u;
  }
  c.texture = c.unit_count != 0;
  unsigned color_mask = 0;
  for (unsigned ch = 0; ch < 4; ++ch) color_mask |= state.color_mask[ch] ? 1u << ch : 0u;
  c.color_write_mask = channel_bits(format, color_mask);
  const uint32_t all_color = channel_bits(format, 0xf);
  c.color_write = c.color_write_mask != 0;
  c.logic_op = state.logic_op;
  c.blend =
      state.blend && !state.logic_op && !(state.blend_src == BlendFactor::one && state.blend_dst == BlendFactor::zero);
  c.needs_destination =
      c.color_write &&
      ((c.blend && (state.blend_dst != BlendFactor::zero || factor_reads_destination(state.blend_src))) ||
       (c.logic_op && logic_op_reads_destination(state.logic_op_mode)) || c.color_write_mask != all_color);

  // A texture takes s/w, t/w and 1/w; each further unit its own s/w, t/w.
  c.attributes =
      (c.depth_test ? 1 : 0) + (c.gouraud ? 4 : 0) + (c.texture ? 1 + 2 * c.unit_count : 0) + (c.fog ? 1 : 0);
  for (unsigned i = 0; i < c.unit_count; ++i) {
    const gl::TextureUnit& unit = state.unit[c.units[i]];
    const gl::TexEnvMode env = unit.env;
    if (env == gl::TexEnvMode::combine) {
      ++c.combines;
      c.combine_arguments += combine_arguments(unit.combine_rgb.func);
      if (unit.combine_rgb.func != gl::CombineFunc::dot3_rgba)
        c.combine_arguments += combine_arguments(unit.combine_alpha.func);
    } else if (env != gl::TexEnvMode::replace) {
      ++c.environments;
    }
  }
  c.reads_destination = c.color_write && (c.needs_destination || c.blend || c.logic_op);

  for (size_t i = 0; i < count; ++i) draw_triangle(c, triangles[i]);
}

namespace {

// Exact DDA of one edge's crossing with the scanlines: f is the first pixel
// whose centre is at or right of the crossing, ceil((x - 8) / 16) in 9.4
// units, kept as quotient and remainder while stepping down one row.
struct EdgeWalk {
  int32_t f = 0, e = 0, q = 0, r = 0, m = 1;
  int row = 0;

  // Edge from (xt, yt) down to (xb, yb), yt > yb, at scanline j (yb < 16 j + 8
  // <= yt); the bounds are MAX_COORDINATE's.
  void init(int32_t xt, int32_t yt, int32_t xb, int32_t yb, int j) {
    const int32_t d = yt - yb, dx = xb - xt, yc = j * 16 + 8;
    m = 16 * d;
    const int32_t n = (xt - 8) * d + (yt - yc) * dx;
    f = ceil_div(n, m);
    e = f * m - n;
    q = floor_div(16 * dx, m);
    r = 16 * dx - q * m;
    row = j;
  }

  void step() {
    f += q;
    e -= r;
    if (e < 0) {
      ++f;
      e += m;
    }
    --row;
  }
};

}  // namespace

void ArmRasterizer::draw_triangle(const DrawContext& c, const gl::Triangle& tri) {
  const gl::RasterState& state = *c.state;
  for (const gl::ScreenVertex& v : tri.v) {
    if (v.x > MAX_COORDINATE || v.x < -MAX_COORDINATE || v.y > MAX_COORDINATE || v.y < -MAX_COORDINATE) return;
  }
  m_memory.charge(HostCost::arm_triangle);

  const int32_t x[3] = {tri.v[0].x, tri.v[1].x, tri.v[2].x};
  const int32_t y[3] = {tri.v[0].y, tri.v[1].y, tri.v[2].y};
  const int32_t area2 = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  if (area2 == 0) return;

  // Top, middle, bottom by GL y (top = largest y = first display row).
  int t = 0, mid = 1, b = 2;
  if (y[t] < y[mid]) std::swap(t, mid);
  if (y[mid] < y[b]) std::swap(mid, b);
  if (y[t] < y[mid]) std::swap(t, mid);

  // floor((y - 8) / 16) as an arithmetic shift.
  const int32_t j_top = (y[t] - 8) >> 4;
  const int32_t j_mid = (y[mid] - 8) >> 4;
  const int32_t j_bottom = ((y[b] - 8) >> 4) + 1;
  const int32_t first_row = std::min<int32_t>(j_top, c.clip_y1);
  const int32_t last_row = std::max<int32_t>(j_bottom, c.clip_y0);
  if (first_row < last_row) return;

  m_memory.charge(HostCost::arm_triangle_setup);
  m_memory.charge(HostCost::arm_triangle_attribute, c.attributes);

  TriangleSetup s;
  {
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
        if (!s.perspective) m_memory.charge(HostCost::arm_lod);
      }
      m_memory.charge(HostCost::arm_triangle_texture_unit);
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
      m_memory.charge(HostCost::arm_triangle_fog);
    }
  }

  // Is the middle vertex left of the long edge (top -> bottom)?
  const int32_t cross = (x[t] - x[b]) * (y[mid] - y[b]) - (y[t] - y[b]) * (x[mid] - x[b]);
  const bool short_is_left = cross > 0;

  EdgeWalk long_edge, short_edge;
  uint64_t rows = 0;
  auto walk = [&](int32_t from, int32_t to, int short_top, int short_bottom) {
    for (int32_t j = from; j >= to; --j) {
      if (long_edge.row != j || rows == 0) long_edge.init(x[t], y[t], x[b], y[b], j);
      if (j == from) short_edge.init(x[short_top], y[short_top], x[short_bottom], y[short_bottom], j);
      const EdgeWalk& left = short_is_left ? short_edge : long_edge;
      const EdgeWalk& right = short_is_left ? long_edge : short_edge;
      const int32_t x_first = std::max<int32_t>(left.f, c.clip_x0);
      const int32_t x_last = std::min<int32_t>(right.f - 1, c.clip_x1);
      if (x_first <= x_last) shade_span(c, s, j, x_first, x_last);
      long_edge.step();
      short_edge.step();
      ++rows;
    }
  };
  // Upper part: y_mid < yc <= y_top; lower part: y_bottom < yc <= y_mid.
  walk(first_row, std::max<int32_t>(j_mid + 1, last_row), t, mid);
  walk(std::min<int32_t>(j_mid, first_row), last_row, mid, b);
  m_memory.charge(HostCost::arm_row, rows);
}

void ArmRasterizer::fetch_texel(const gl::Texture& tex, unsigned level, int u8, int v8, bool linear, uint8_t out[4]) {
  const gl::TextureLevel image = renderers::texture_level(tex, level);
  const unsigned w = image.width, h = image.height;
  auto address = [&](int i, int j) { return image.address + (uint32_t(j) * w + uint32_t(i)) * 4; };
  if (!linear) {
    const int i = wrap(u8 >> 8, w, tex.wrap_s), j = wrap(v8 >> 8, h, tex.wrap_t);
    std::memcpy(out, m_memory.load(address(i, j), 4, 1), 4);
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
      std::memcpy(texel[2 * r], m_memory.load(address(i0, rows[r]), 4, 2), 8);
    } else {
      std::memcpy(texel[2 * r], m_memory.load(address(i0, rows[r]), 4, 1), 4);
      std::memcpy(texel[2 * r + 1], m_memory.load(address(i1, rows[r]), 4, 1), 4);
    }
  }
  renderers::bilinear(texel, fu, fv, out);
}

void ArmRasterizer::shade_span(const DrawContext& c, const TriangleSetup& s, int j, int x_first, int x_last) {
  const gl::RasterState& state = *c.state;
  const int n = x_last - x_first + 1;
  const uint32_t row_offset = uint32_t(int(m_buffers.height) - 1 - j) * m_buffers.width;
  const uint32_t first = row_offset + uint32_t(x_first);

  if (c.depth_test) {
    const uint8_t* p = m_memory.load(m_buffers.depth_address + first * 2, 2, unsigned(n));
    for (int i = 0; i < n; ++i) m_depth_old[i] = uint16_t(p[2 * i] | p[2 * i + 1] << 8);
  }
  if (c.stencil_test) {
    const uint8_t* p = m_memory.load(m_buffers.stencil_address + first, 1, unsigned(n));
    std::memcpy(m_stencil_old.data(), p, size_t(n));
    std::memcpy(m_stencil_new.data(), p, size_t(n));
  }

  // The barycentric weights of the span's first pixel, once per frame of planes.
  int32_t w_snapped[2], w_attributes[2];
  s.snapped.weights(x_first, j, w_snapped);
  if (s.use_unsnapped) {
    s.unsnapped.weights(x_first, j, w_attributes);
  } else {
    w_attributes[0] = w_snapped[0];
    w_attributes[1] = w_snapped[1];
  }
  int32_t z = 0, dz = 0;
  if (c.depth_test) {
    z = s.z.start(w_snapped, n);
    dz = s.z.step;
  }
  int32_t color[4] = {0, 0, 0, 0}, dcolor[4] = {0, 0, 0, 0};
  if (c.gouraud) {
    for (int ch = 0; ch < 4; ++ch) {
      color[ch] = s.color[ch].start(w_attributes, n);
      dcolor[ch] = s.color[ch].step;
    }
  }
  // q, s q and t q in 2^-FINE_BITS units (Plane::start_fine); the pixel's
  // values are their integer parts.
  int64_t sq_fine[gl::MAX_TEXTURE_UNITS] = {}, tq_fine[gl::MAX_TEXTURE_UNITS] = {};
  int64_t q_fine = int64_t{1} << FINE_BITS, dq = 0;
  int64_t dsq[gl::MAX_TEXTURE_UNITS] = {}, dtq[gl::MAX_TEXTURE_UNITS] = {};
  for (unsigned u = 0; u < c.unit_count; ++u) {
    sq_fine[u] = s.sq[u].start_fine(w_attributes, n);
    tq_fine[u] = s.tq[u].start_fine(w_attributes, n);
    dsq[u] = s.sq[u].step_fine;
    dtq[u] = s.tq[u].step_fine;
  }
  if (c.texture || s.perspective_color || (c.fog && s.perspective)) {
    q_fine = s.q.start_fine(w_attributes, n);
    dq = s.q.step_fine;
  }
  int32_t fog = 0, dfog = 0;
  if (c.fog) {
    fog = s.fog.start(w_attributes, n);
    dfog = s.fog.step;
  }

  // The scratch rows as plain pointers: nothing the loop stores can move them.
  const uint16_t* const depth_old = m_depth_old.data();
  uint16_t* const depth_new = m_depth_new.data();
  uint8_t* const stencil_new = m_stencil_new.data();
  uint8_t* const pass = m_pass.data();
  uint32_t* const source = m_source.data();
  const uint8_t stencil_ref = state.stencil_ref, stencil_mask = state.stencil_value_mask;
  const uint8_t stencil_write_mask = state.stencil_write_mask;
  // Stencil and depth tests of pixel i; updates the stencil value.
  auto fragment_tests = [&](int i, uint16_t z16) {
    if (c.stencil_test) {
      const uint8_t old = stencil_new[i];
      if (!compare_passes<uint8_t>(state.stencil_func, stencil_ref & stencil_mask, old & stencil_mask)) {
        stencil_new[i] = stencil_op_result(state.stencil_fail, old, stencil_ref, stencil_write_mask);
        return false;
      }
      if (c.depth_test && !compare_passes(state.depth_func, z16, depth_old[i])) {
        stencil_new[i] = stencil_op_result(state.depth_fail, old, stencil_ref, stencil_write_mask);
        return false;
      }
      stencil_new[i] = stencil_op_result(state.depth_pass, old, stencil_ref, stencil_write_mask);
      return true;
    }
    return !c.depth_test || compare_passes(state.depth_func, z16, depth_old[i]);
  };
  const bool early_depth_only = !c.late_tests && !c.stencil_test;
  const CompareFunc depth_func = c.depth_test ? state.depth_func : CompareFunc::always;
  const bool step_q = c.texture || s.perspective_color || (c.fog && s.perspective);

  // Per span: at most 512 pixels, so 32-bit counts.
  uint32_t shaded = 0, texel_calls = 0, passed = 0, color_divisions = 0, fog_divisions = 0;
  // Where the level of detail chooses per pixel: its computations, the
  // texels it samples, the blends of two levels.
  uint32_t lods = 0, lod_nearest = 0, lod_linear = 0, mipmap_blends = 0;
  // lambda (16.16) at a pixel from unit i's stepped (s q), (t q), q and its
  // planes' gradients: du/dx = (gx(sq) q - sq gx(q)) / q^2 2^(30 - F) in
  // level 0's texels, the gradients g 2^-e (LodGradients). Each product is
  // below 2^59 (|g| <= 2^30, q <= 2^30, |sq| < 2^30), each difference below
  // 2^60; lambda = log2(max) - 2 log2(q) + 30 - F - e.
  auto pixel_lod = [&](unsigned i, int32_t sq_value, int32_t tq_value, int32_t q_value) -> int32_t {
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
  };
  // The spans most scenes draw (no texture, fog, stencil or alpha test:
  // depth and colour only) take a loop of their own, specialised on the
  // depth function, with few live values: the general loop below keeps
  // every stage's state and spilled it (about 180 ARM instructions per
  // pixel for a Gouraud, depth-tested pixel). Same arithmetic, same
  // charges.
  const bool plain = early_depth_only && !c.texture && !c.fog;
  auto plain_loop = [&](auto passes) {
    int32_t depth = z, r = color[0], g = color[1], b = color[2], a = color[3];
    const int32_t dr = dcolor[0], dg = dcolor[1], db = dcolor[2], da = dcolor[3];
    int64_t q_value = q_fine;
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
    shaded = passed = count;
    if (divide) color_divisions = count;
  };
  if (plain) {
    switch (depth_func) {
      case CompareFunc::less: plain_loop([](uint16_t in, uint16_t old) { return in < old; }); break;
      case CompareFunc::lequal: plain_loop([](uint16_t in, uint16_t old) { return in <= old; }); break;
      case CompareFunc::always: plain_loop([](uint16_t, uint16_t) { return true; }); break;
      default: plain_loop([depth_func](uint16_t in, uint16_t old) { return compare_passes(depth_func, in, old); });
    }
  }
  int32_t sq[gl::MAX_TEXTURE_UNITS] = {}, tq[gl::MAX_TEXTURE_UNITS] = {};
  for (int i = 0; !plain && i < n; ++i) {
    const uint16_t z16 = uint16_t(uint32_t(z) >> (8 + DEPTH_FRACTION_BITS));
    bool alive =
        early_depth_only ? compare_passes(depth_func, z16, depth_old[i]) : (c.late_tests || fragment_tests(i, z16));
    if (alive) {
      ++shaded;
      const int32_t q = step_q ? int32_t(q_fine >> FINE_BITS) : int32_t{1} << Q_FRACTION_BITS;
      for (unsigned u = 0; u < c.unit_count; ++u) {
        sq[u] = int32_t(sq_fine[u] >> FINE_BITS);
        tq[u] = int32_t(tq_fine[u] >> FINE_BITS);
      }
      // The pixel's 1/q, when anything divides: q in [1, 2^30] is
      // normalised to m in [2^29, 2^30), 1/q ~ r / 2^shift with r =
      // floor(2^59 / m) (one 32-bit division, a Newton step, a correction;
      // renderers/common/fixed_math.h), shift = 29 + length(q). A value x
      // times 2^k / q is then (x r) >> (shift - k), x r below 2^61,
      // truncated toward zero; within 2^-29 of the exact quotient.
      renderers::Reciprocal inverse_q;
      if (s.perspective) inverse_q = renderers::make_reciprocal(uint32_t(q));
      auto divide = [&](int32_t value, int scale_bits) {
        int64_t product = int64_t{value} * inverse_q.r;
        const int shift = inverse_q.shift - scale_bits;  // >= 0 for every scale below
        if (product < 0) product += (int64_t{1} << shift) - 1;
        return product >> shift;
      };
      uint32_t rgba;
      if (s.perspective_color) {
        // c/w over 1/w: one reciprocal of q per pixel (shared with the
        // texture coordinates), then a multiply per channel.
        rgba = 0;
        for (int ch = 0; ch < 4; ++ch) {
          const int64_t value =
              (divide(color[ch], Q_FRACTION_BITS) + (1 << (COLOR_FRACTION_BITS - 1))) >> COLOR_FRACTION_BITS;
          rgba |= uint32_t(std::clamp<int64_t>(value, 0, 255)) << (8 * ch);
        }
        if (!c.texture) ++color_divisions;
      } else if (c.gouraud) {
        rgba = uint32_t(color[0] >> COLOR_FRACTION_BITS) | uint32_t(color[1] >> COLOR_FRACTION_BITS) << 8 |
               uint32_t(color[2] >> COLOR_FRACTION_BITS) << 16 | uint32_t(color[3] >> COLOR_FRACTION_BITS) << 24;
      } else {
        rgba = s.flat_rgba;
      }
      if (c.texture) {
        // One reciprocal of q per pixel serves every unit (texel_calls).
        if (s.perspective) ++texel_calls;
        const uint32_t primary = rgba;
        for (unsigned u = 0; u < c.unit_count; ++u) {
          // Texel coordinates with 8 fraction bits: (s q 2^F) 2^(38 - F) / q,
          // |.| < 2^23 inside the triangle (|s W| <= 2^15), clamped to 2^30.
          const int bits = s.st_bits[u];
          int64_t u8, v8;
          if (s.perspective) {
            u8 = divide(sq[u], 8 + Q_FRACTION_BITS - bits);
            v8 = divide(tq[u], 8 + Q_FRACTION_BITS - bits);
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
              fetch_texel(unit.tex, level, fu, fv, linear, filtered);
            };
            const renderers::LodChoice choice = renderers::sample_texture_lod_q16(
                unit.tex, int(u8), int(v8), pixel_lod(u, sq[u], tq[u], q), filter_level, texel);
            if (s.perspective) ++lods;
            (choice.linear ? lod_linear : lod_nearest) += choice.count;
            mipmap_blends += choice.count - 1;
          } else {
            fetch_texel(unit.tex, 0, int(u8), int(v8), s.linear_filter[u], texel);
          }
          // The unit's base format rules (fill_missing_components) apply
          // before its environment, inside apply_texture_unit.
          rgba = renderers::apply_texture_unit(unit, rgba, primary, texel);
        }
      }
      if (c.fog) {
        // After texturing, before the fragment operations (ES 1.1, 3.8).
        int64_t argument = fog;
        if (s.perspective) {
          argument = divide(fog, Q_FRACTION_BITS);
          // The reciprocal of q is shared with the texture coordinates or
          // the colours when they divide too.
          if (!c.texture && !s.perspective_color) ++fog_divisions;
        }
        const auto a = int32_t(std::clamp<int64_t>(argument, INT32_MIN, INT32_MAX));
        rgba = fog_blend(fog_factor(state.fog_mode, a), rgba, c.fog_rgba);
      }
      if (c.alpha_test && !compare_passes<uint32_t>(state.alpha_func, rgba >> 24, state.alpha_ref)) {
        alive = false;
      } else if (c.late_tests) {
        alive = fragment_tests(i, z16);
      }
      source[i] = rgba;
    }
    pass[i] = alive;
    depth_new[i] = z16;
    passed += alive;
    advance(z, dz);
    for (int ch = 0; ch < 4; ++ch) advance(color[ch], dcolor[ch]);
    for (unsigned u = 0; u < c.unit_count; ++u) {
      sq_fine[u] += dsq[u];
      tq_fine[u] += dtq[u];
    }
    if (step_q) q_fine += dq;
    advance(fog, dfog);
  }

  // Stores, as runs of consecutive pixels; a span whose every pixel passed
  // is one run without a scan. The rows are reached through the local
  // pointers (the stores' calls cannot move them).
  const uint8_t* const stencil_old = m_stencil_old.data();
  auto for_each_run = [n](auto&& is_set, auto&& emit) {
    int i = 0;
    while (i < n) {
      while (i < n && !is_set(i)) ++i;
      const int begin = i;
      while (i < n && is_set(i)) ++i;
      if (begin < i) emit(begin, i);
    }
  };
  auto for_each_passing_run = [&](auto&& emit) {
    if (passed == uint32_t(n)) {
      emit(0, n);
    } else {
      for_each_run([pass](int i) { return pass[i] != 0; }, emit);
    }
  };
  if (c.stencil_writes) {
    for_each_run([stencil_new, stencil_old](int i) { return stencil_new[i] != stencil_old[i]; },
                 [&](int begin, int end) {
                   uint8_t* p =
                       m_memory.store(m_buffers.stencil_address + first + uint32_t(begin), 1, unsigned(end - begin));
                   std::memcpy(p, stencil_new + begin, size_t(end - begin));
                 });
  }
  if (passed != 0) {
    if (c.depth_write) {
      for_each_passing_run([&](int begin, int end) {
        uint8_t* p = m_memory.store(m_buffers.depth_address + (first + uint32_t(begin)) * 2, 2, unsigned(end - begin));
        const uint16_t* from = depth_new + begin;
        for (int e = 0; e < end - begin; ++e) {
          p[2 * e] = uint8_t(from[e]);
          p[2 * e + 1] = uint8_t(from[e] >> 8);
        }
      });
    }
    if (c.color_write) {
      for_each_passing_run([&](int begin, int end) { write_color_run(c, row_offset, x_first, begin, end); });
    }
  }

  // The span's host time (sw_driver/costs): per span, per pixel walked,
  // per pixel shaded and its texels, divisions and environments, per pixel
  // written.
  uint32_t nearest_units = 0, linear_units = 0;
  for (unsigned u = 0; u < c.unit_count; ++u) {
    if (!s.lod[u]) ++(s.linear_filter[u] ? linear_units : nearest_units);
  }
  m_memory.charge(HostCost::arm_span);
  m_memory.charge(HostCost::arm_span_attribute, c.attributes);
  m_memory.charge(HostCost::arm_pixel, uint64_t(n));
  if (c.depth_test) m_memory.charge(HostCost::arm_pixel_depth, uint64_t(n));
  if (c.stencil_test) m_memory.charge(HostCost::arm_pixel_stencil, uint64_t(n));
  if (c.gouraud) m_memory.charge(HostCost::arm_pixel_color, uint64_t(n));
  if (c.texture) m_memory.charge(HostCost::arm_pixel_texcoord, uint64_t(n) * c.unit_count);
  if (c.fog) m_memory.charge(HostCost::arm_pixel_fog, uint64_t(n));
  m_memory.charge(HostCost::arm_shaded_pixel, shaded);
  m_memory.charge(HostCost::arm_texel_nearest, uint64_t(shaded) * nearest_units + lod_nearest);
  m_memory.charge(HostCost::arm_texel_linear, uint64_t(shaded) * linear_units + lod_linear);
  m_memory.charge(HostCost::arm_mipmap_blend, mipmap_blends);
  m_memory.charge(HostCost::arm_lod, lods);
  m_memory.charge(HostCost::arm_division, uint64_t(texel_calls) + color_divisions + fog_divisions);
  if (s.perspective_color) m_memory.charge(HostCost::arm_perspective_color, shaded);
  m_memory.charge(HostCost::arm_texture_environment, uint64_t(shaded) * c.environments);
  m_memory.charge(HostCost::arm_texture_combine, uint64_t(shaded) * c.combines);
  m_memory.charge(HostCost::arm_texture_combine_argument, uint64_t(shaded) * c.combine_arguments);
  if (c.fog) m_memory.charge(HostCost::arm_fog, shaded);
  if (c.alpha_test) m_memory.charge(HostCost::arm_alpha_test, shaded);
  if (c.color_write) m_memory.charge(HostCost::arm_color_write, passed);
  if (c.reads_destination) m_memory.charge(HostCost::arm_color_read_back, passed);
  if (c.depth_write) m_memory.charge(HostCost::arm_depth_write, passed);
}

void ArmRasterizer::write_color_run(const DrawContext& c, uint32_t row_offset, int x_begin, int begin, int end) {
  const gl::RasterState& state = *c.state;
  const PixelFormat format = m_buffers.color_format;
  const unsigned bpp = bytes_per_pixel(format);
  const unsigned count = unsigned(end - begin);
  const uint32_t address = m_buffers.color_address + (row_offset + uint32_t(x_begin + begin)) * bpp;
  const uint32_t all = channel_bits(format, 0xf);
  if (c.needs_destination) {
    const uint8_t* d = m_memory.load(address, bpp, count);
    for (unsigned i = 0; i < count; ++i) {
      const uint32_t dst = load_pixel(format, d + i * bpp);
      uint32_t src = m_source[begin + int(i)];
      if (c.blend) src = blend(state.blend_src, state.blend_dst, src, unpack_pixel(format, dst));
      uint32_t out = pack_pixel(format, src);
      if (c.logic_op) out = logic_op(state.logic_op_mode, out, dst) & all;
      m_source[begin + int(i)] = (out & c.color_write_mask) | (dst & ~c.color_write_mask);
    }
  } else {
    for (int i = begin; i < end; ++i) {
      uint32_t out = pack_pixel(format, m_source[i]);
      if (c.logic_op) out = logic_op(state.logic_op_mode, out, 0) & all;
      m_source[i] = out;
    }
  }
  uint8_t* p = m_memory.store(address, bpp, count);
  for (unsigned i = 0; i < count; ++i) store_pixel(format, p + i * bpp, m_source[begin + int(i)]);
}

void ArmRasterizer::read_pixels(int x, int y, int width, int height, uint8_t* rgba) {
  if (width <= 0 || height <= 0 || rgba == nullptr) return;
  std::memset(rgba, 0, size_t(width) * size_t(height) * 4);
  const PixelFormat format = m_buffers.color_format;
  const unsigned bpp = bytes_per_pixel(format);
  const int x0 = std::max(x, 0);
  const int x1 = int(std::min<int64_t>(int64_t(x) + width, m_buffers.width));
  if (x0 >= x1) return;
  for (int row = 0; row < height; ++row) {
    const int64_t gy = int64_t(y) + row;
    if (gy < 0 || gy >= int64_t(m_buffers.height)) continue;
    const uint32_t offset = uint32_t(int64_t(m_buffers.height) - 1 - gy) * m_buffers.width + uint32_t(x0);
    const uint8_t* p = m_memory.load(m_buffers.color_address + offset * bpp, bpp, unsigned(x1 - x0));
    uint8_t* out = rgba + (size_t(row) * size_t(width) + size_t(x0 - x)) * 4;
    for (int i = 0; i < x1 - x0; ++i) {
      const uint32_t v = unpack_pixel(format, load_pixel(format, p + i * bpp));
      out[4 * i] = uint8_t(v);
      out[4 * i + 1] = uint8_t(v >> 8);
      out[4 * i + 2] = uint8_t(v >> 16);
      out[4 * i + 3] = uint8_t(v >> 24);
    }
    m_memory.charge(HostCost::arm_read_pixel, uint64_t(x1 - x0));
  }
}

}  // namespace tessera::arm
