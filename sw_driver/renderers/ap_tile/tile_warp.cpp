// Textures warped on the array (tile_warp.h, README.md "Textures warped on
// the array"). Single-precision floats only: the driver runs on an ARM922T
// without an FPU, and a plane is a few dozen operations per triangle.
#include "renderers/ap_tile/tile_warp.h"

#include <algorithm>
#include <cmath>

namespace tessera::ap_tile {

namespace ft = forward_texture;

namespace {

// A triangle's vertex on the texture's plane: texel and window coordinates
// and the clip w.
struct PlanePoint {
  float u, v, x, y, w;
};

// `value` to `bits` significant bits.
float to_bits(float value, int bits) {
  int exponent = 0;
  const float mantissa = std::frexp(value, &exponent);
  return std::ldexp(std::nearbyint(std::ldexp(mantissa, bits)), exponent - bits);
}

// The vertex's window position as the array fills it (9.4, snapped), and
// its w and texture coordinates to 16 bits: the host-compiled driver and
// the ARM's (newlib's sinf and cosf an ulp from glibc's) then find the same
// plane unless an ulp crosses a rounding step.
bool plane_point(const gl::ScreenVertex& vertex, const gl::Texture& texture, PlanePoint& point) {
  if (!(vertex.inv_w > 0.0f)) return false;
  point.u = to_bits(vertex.tex[0].s, 16) * static_cast<float>(texture.width);
  point.v = to_bits(vertex.tex[0].t, 16) * static_cast<float>(texture.height);
  point.x = static_cast<float>(vertex.x) / 16.0f;
  point.y = static_cast<float>(vertex.y) / 16.0f;
  point.w = to_bits(1.0f / vertex.inv_w, 16);
  return true;
}

// How far past the triangles' texels the region reaches, in base texels: a
// pixel on the primitive's edge filters F pixels around its centre, so its
// texels lie beyond the edge; those of a repeated or clamped texture exist
// (the wrap gives them), so the edge's pixels take them instead of the
// zeros beyond the region.
int region_margin(int filter_width) {
  return filter_width + 1;
}

// The largest pixels per warp texel over the region (its corners, edge
// midpoints and centre), in either pass of either order: the first pass's
// scale along a texture line, the second's along an intermediate line
// (d/dj at fixed x: dy/dj - dy/di (dx/dj / dx/di)).
float largest_scale(const ft::PerspectiveMatrix& fixed, int width, int height) {
  const float a = static_cast<float>(fixed.a) / 1048576.0f, b = static_cast<float>(fixed.b) / 1048576.0f;
  const float c = static_cast<float>(fixed.c) / 1048576.0f, d = static_cast<float>(fixed.d) / 1048576.0f;
  const float e = static_cast<float>(fixed.e) / 1048576.0f, f = static_cast<float>(fixed.f) / 1048576.0f;
  const float g = static_cast<float>(fixed.g) / 1073741824.0f, h = static_cast<float>(fixed.h) / 1073741824.0f;
  const float l = static_cast<float>(fixed.i) / 1073741824.0f;
  float largest = 0.0f;
  for (int pi = 0; pi <= 2; ++pi)
    for (int pj = 0; pj <= 2; ++pj) {
      const float i = static_cast<float>(width * pi) / 2.0f, j = static_cast<float>(height * pj) / 2.0f;
      const float w = g * i + h * j + l;
      const float x = (a * i + b * j + c) / w, y = (d * i + e * j + f) / w;
      const float xi = (a - x * g) / w, xj = (b - x * h) / w, yi = (d - y * g) / w, yj = (e - y * h) / w;
      largest = std::max({largest, std::fabs(xi), std::fabs(yj), std::fabs(xj), std::fabs(yi)});
      if (std::fabs(xi) > 1e-6f) largest = std::max(largest, std::fabs(yj - yi * xj / xi));
      if (std::fabs(yj) > 1e-6f) largest = std::max(largest, std::fabs(xi - xj * yi / yj));
    }
  return largest;
}

bool to_fixed(float value, int fraction_bits, float limit, int32_t& out) {
  if (!(std::fabs(value) < limit)) return false;
  out = static_cast<int32_t>(std::lround(std::ldexp(value, fraction_bits)));
  return true;
}

}  // namespace

bool TexturePlane::map(float u, float v, float& x, float& y) const {
  const float w = m[6] * u + m[7] * v + m[8];
  if (!(w > 0.0f)) return false;
  x = (m[0] * u + m[1] * v + m[2]) / w;
  y = (m[3] * u + m[4] * v + m[5]) / w;
  return true;
}

std::optional<TexturePlane> texture_plane(const gl::Triangle& triangle, const gl::Texture& texture) {
  PlanePoint p[3];
  for (int k = 0; k < 3; ++k)
    if (!plane_point(triangle.v[k], texture, p[k])) return std::nullopt;
  // Relative to vertex 0: row r of m is (P, Q, R) with value(u, v) = P (u -
  // u0) + Q (v - v0) + value0, P and Q from the other two vertices.
  const float du1 = p[1].u - p[0].u, dv1 = p[1].v - p[0].v, du2 = p[2].u - p[0].u, dv2 = p[2].v - p[0].v;
  const float det = du1 * dv2 - du2 * dv1;
  if (!(std::fabs(det) > 1e-6f)) return std::nullopt;
  TexturePlane plane;
  for (size_t r = 0; r < 3; ++r) {
    auto value = [r](const PlanePoint& q) { return r == 0 ? q.x * q.w : (r == 1 ? q.y * q.w : q.w); };
    const float base = value(p[0]), d1 = value(p[1]) - base, d2 = value(p[2]) - base;
    const float pu = (d1 * dv2 - d2 * dv1) / det, qv = (du1 * d2 - du2 * d1) / det;
    plane.m[3 * r] = pu;
    plane.m[3 * r + 1] = qv;
    plane.m[3 * r + 2] = base - pu * p[0].u - qv * p[0].v;
  }
  return plane;
}

bool on_plane(const TexturePlane& plane, const gl::Triangle& triangle, const gl::Texture& texture) {
  for (const gl::ScreenVertex& vertex : triangle.v) {
    PlanePoint p{};
    float x = 0, y = 0;
    if (!plane_point(vertex, texture, p) || !plane.map(p.u, p.v, x, y)) return false;
    if (std::fabs(x - p.x) > 0.25f || std::fabs(y - p.y) > 0.25f) return false;
  }
  return true;
}

int wrap_texel(int i, int size, gl::TexWrap wrap) {
  if (wrap == gl::TexWrap::clamp_to_edge) return std::clamp(i, 0, size - 1);
  const int r = i % size;
  return r < 0 ? r + size : r;
}

ft::FilterTable warp_filter(int width) {
  return ft::make_filter_table(ft::FilterKind::box, width);
}

void WarpedTexture::texel(int x, int y, uint8_t out[4]) const {
  for (int c = 0; c < 3; ++c) out[c] = channels[static_cast<size_t>(c)].at(x, y);
  out[3] = 255;
}

std::string WarpJob::prepare(const TexturePlane& plane, const gl::Texture& texture, float u_min, float u_max,
                             float v_min, float v_max, int frame_width, int frame_height, int max_texels) {
  m_plane = plane;
  m_frame_width = frame_width;
  m_frame_height = frame_height;
  m_max_texels = max_texels;
  m_bands.clear();
  m_region = WarpRegion{};
  // Levels down to one texel along the texture's shorter side.
  m_top_level = 0;
  while ((std::min(texture.width, texture.height) >> (m_top_level + 1)) > 0) ++m_top_level;
  const int margin = region_margin(m_table.width);
  const auto longest = static_cast<float>(max_texels << m_top_level);
  if (!(u_max - u_min <= longest) || !(v_max - v_min <= longest))
    return "its texels span " + std::to_string(std::lround(u_max - u_min)) + " x " +
           std::to_string(std::lround(v_max - v_min)) + " texels, beyond the array program's " +
           std::to_string(max_texels) + " texels a line at every level";
  m_region.u0 = static_cast<int>(std::floor(u_min)) - margin;
  m_region.v0 = static_cast<int>(std::floor(v_min)) - margin;
  m_region.width = static_cast<int>(std::ceil(u_max)) + margin - m_region.u0;
  m_region.height = static_cast<int>(std::ceil(v_max)) + margin - m_region.v0;
  // The whole region at the base level when it fits; else bands.
  WarpBand whole{m_region.u0, m_region.v0, m_region.width, m_region.height, 0, 1, {}};
  std::string error = fit_band(whole);
  if (error.empty()) {
    m_bands.push_back(whole);
  } else if (error.find("beyond the array program's") != std::string::npos) {
    error = cut_bands();
  }
  for (const WarpBand& band : m_bands) m_region.upscale = std::max(m_region.upscale, band.upscale);
  m_region.bands = static_cast<int>(m_bands.size());
  return error;
}

// The band's upscale (the smallest power of two that leaves every texel
// within a pixel by the scale at nine points; a warp still refused for
// magnification is retried at twice it: run) and its matrix.
std::string WarpJob::fit_band(WarpBand& band) const {
  band.upscale = 1;
  if (std::string error = band_matrix(band); !error.empty()) return error;
  const float scale = largest_scale(band.matrix, band.width, band.height);
  while (scale / static_cast<float>(band.upscale) > 1.0001f) band.upscale *= 2;
  return band_matrix(band);
}

// The region cut across its longer side into bands of whole chunks of
// 2^top_level base texels (the chunks' edges are texel edges at every
// level), each chunk at the level whose texels cover at most a pixel
// (level 0, upscaled, where the base texels cover more), consecutive
// chunks of one level and upscale one band while its lines fit.
std::string WarpJob::cut_bands() {
  const bool along_v = m_region.height >= m_region.width;
  const int chunk = 1 << m_top_level;
  const int first = along_v ? m_region.v0 : m_region.u0;
  const int end = first + (along_v ? m_region.height : m_region.width);
  auto floor_div = [](int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  auto ceil_div = [&](int a, int b) { return -floor_div(-a, b); };
  WarpBand current{};
  bool open = false;
  for (int c = floor_div(first, chunk) * chunk; c < end; c += chunk) {
    const int a = std::max(c, first), b = std::min(c + chunk, end);
    // The chunk's scale at level 0, then its level.
    WarpBand probe{along_v ? m_region.u0 : a,
                   along_v ? a : m_region.v0,
                   along_v ? m_region.width : b - a,
                   along_v ? b - a : m_region.height,
                   0,
                   1,
                   {}};
    if (std::string error = band_matrix(probe); !error.empty()) return error;
    const float scale = largest_scale(probe.matrix, probe.width, probe.height);
    int level = 0;
    while (level < m_top_level && scale * static_cast<float>(2 << level) <= 1.0f) ++level;
    const int size = 1 << level;
    // The band in level texels: its cross extent rounded outwards, its
    // ends at chunk edges (or the region's, rounded outwards).
    const int cross0 = floor_div(along_v ? m_region.u0 : m_region.v0, size);
    const int cross1 = ceil_div(along_v ? m_region.u0 + m_region.width : m_region.v0 + m_region.height, size);
    const int a_level = floor_div(a, size), b_level = ceil_div(b, size);
    const bool extends = open && current.level == level &&
                         (along_v ? current.v0 + current.height == a_level : current.u0 + current.width == a_level);
    WarpBand next = current;
    if (extends) {
      (along_v ? next.height : next.width) += b_level - a_level;
    } else {
      next = along_v ? WarpBand{cross0, a_level, cross1 - cross0, b_level - a_level, level, 1, {}}
                     : WarpBand{a_level, cross0, b_level - a_level, cross1 - cross0, level, 1, {}};
    }
    std::string error = fit_band(next);
    if (extends && !error.empty()) {
      // The band is full: this chunk starts the next.
      m_bands.push_back(current);
      next = along_v ? WarpBand{cross0, a_level, cross1 - cross0, b_level - a_level, level, 1, {}}
                     : WarpBand{a_level, cross0, b_level - a_level, cross1 - cross0, level, 1, {}};
      error = fit_band(next);
    } else if (!extends && open) {
      m_bands.push_back(current);
    }
    if (!error.empty()) return error;
    current = next;
    open = true;
  }
  if (open) m_bands.push_back(current);
  return {};
}

// The band's matrix: m times the band's texel-to-base map (level texels,
// upscaled), scaled so that the largest w at its corners is 1, in q12_20
// and q2_30.
std::string WarpJob::band_matrix(WarpBand& band) const {
  const int k = band.upscale;
  const int width = band.width * k, height = band.height * k;
  if (width > m_max_texels || height > m_max_texels)
    return "its texture region of " + std::to_string(band.width) + " x " + std::to_string(band.height) +
           " texels (level " + std::to_string(band.level) + ") upscaled " + std::to_string(k) +
           " times is beyond the array program's " + std::to_string(m_max_texels) + " texels a line";
  const std::array<float, 9>& m = m_plane.m;
  const auto size = static_cast<float>(1 << band.level);
  const float step = size / static_cast<float>(k);
  const float u0 = static_cast<float>(band.u0) * size, v0 = static_cast<float>(band.v0) * size;
  std::array<float, 9> r{};
  for (size_t row = 0; row < 3; ++row) {
    const size_t at = 3 * row;
    r[at] = m[at] * step;
    r[at + 1] = m[at + 1] * step;
    r[at + 2] = m[at] * u0 + m[at + 1] * v0 + m[at + 2];
  }
  float w_max = 0.0f, w_min = 0.0f;
  for (int corner = 0; corner < 4; ++corner) {
    const auto i = static_cast<float>(corner & 1 ? width : 0), j = static_cast<float>(corner & 2 ? height : 0);
    const float w = r[6] * i + r[7] * j + r[8];
    w_max = corner == 0 ? w : std::max(w_max, w);
    w_min = corner == 0 ? w : std::min(w_min, w);
  }
  if (!(w_min > 0.0f)) return "its plane passes behind the eye within the texture region";
  const float scale = 1.0f / w_max;
  bool fits = true;
  int32_t* fixed[9] = {&band.matrix.a, &band.matrix.b, &band.matrix.c, &band.matrix.d, &band.matrix.e,
                       &band.matrix.f, &band.matrix.g, &band.matrix.h, &band.matrix.i};
  for (size_t e = 0; e < 9; ++e) {
    const bool denominator = e >= 6;
    fits = fits && to_fixed(r[e] * scale, denominator ? ft::Q2_30_FRACTION_BITS : ft::Q12_20_FRACTION_BITS,
                            denominator ? 1.99f : 2047.0f, *fixed[e]);
  }
  if (!fits) return "its plane's matrix leaves the warp's fixed point";
  return ft::matrix_error(band.matrix, width, height);
}

// The band's texels at its level: the texture's own level when it has one
// (source), else the mean of the base texels under each (rounded).
std::vector<uint8_t> WarpJob::band_texels(const WarpBand& band, const TexelSource& source,
                                          uint64_t& texels_loaded) const {
  std::vector<uint8_t> texels(static_cast<size_t>(band.width) * band.height * 4);
  const int size = 1 << band.level;
  for (int j = 0; j < band.height; ++j)
    for (int i = 0; i < band.width; ++i) {
      uint8_t* out = &texels[(static_cast<size_t>(j) * band.width + i) * 4];
      ++texels_loaded;
      if (source(band.level, band.u0 + i, band.v0 + j, out)) continue;
      unsigned sum[4] = {};
      for (int b = 0; b < size; ++b)
        for (int a = 0; a < size; ++a) {
          uint8_t base[4];
          source(0, (band.u0 + i) * size + a, (band.v0 + j) * size + b, base);
          for (int c = 0; c < 4; ++c) sum[c] += base[c];
        }
      const auto count = static_cast<unsigned>(size * size);
      for (int c = 0; c < 4; ++c) out[c] = static_cast<uint8_t>((sum[c] + count / 2) / count);
      texels_loaded += count;
    }
  return texels;
}

std::string WarpJob::run(const TexelSource& source, ft::LineResampler* resampler, WarpedTexture& out,
                         uint64_t& texels_loaded) {
  const size_t pixels = static_cast<size_t>(m_frame_width) * m_frame_height;
  std::array<std::vector<uint16_t>, 3> sums;
  for (std::vector<uint16_t>& sum : sums) sum.assign(pixels, 0);
  for (WarpBand& band : m_bands) {
    const std::vector<uint8_t> texels = band_texels(band, source, texels_loaded);
    for (;;) {
      const int k = band.upscale, width = band.width * k, height = band.height * k;
      std::string error;
      std::array<ft::Image, 3> images;
      for (size_t c = 0; c < 3 && error.empty(); ++c) {
        ft::Image image{width, height, std::vector<uint8_t>(static_cast<size_t>(width) * height)};
        for (int j = 0; j < height; ++j)
          for (int i = 0; i < width; ++i)
            image.texels[static_cast<size_t>(j) * width + i] =
                texels[(static_cast<size_t>(j / k) * band.width + i / k) * 4 + c];
        ft::WarpResult result = ft::warp_texture(image, band.matrix, m_table, m_frame_width, m_frame_height, resampler);
        error = result.error;
        images[c] = std::move(result.image);
        out.order = result.pass_order.order;
        // The first pass's lines are the texture's rows (columns first:
        // its columns), the second's the output's columns (rows).
        const bool rows_first = out.order == ft::PassOrder::rows_first;
        const uint64_t first = rows_first ? height : width, texels_a_line = rows_first ? width : height;
        const uint64_t second = rows_first ? m_frame_width : m_frame_height;
        out.lines += first + second;
        out.borders += (first + second) * (texels_a_line + 1);
      }
      if (error.empty()) {
        // A band's image holds its texels' part of every pixel: the bands
        // add up.
        for (size_t c = 0; c < 3; ++c)
          for (size_t p = 0; p < pixels; ++p) sums[c][p] = static_cast<uint16_t>(sums[c][p] + images[c].texels[p]);
        break;
      }
      if (error.find("magnification") == std::string::npos) return error;
      band.upscale *= 2;
      m_region.upscale = std::max(m_region.upscale, band.upscale);
      if (std::string refused = band_matrix(band); !refused.empty()) return refused;
    }
  }
  for (size_t c = 0; c < 3; ++c) {
    out.channels[c] = ft::Image{m_frame_width, m_frame_height, std::vector<uint8_t>(pixels)};
    for (size_t p = 0; p < pixels; ++p)
      out.channels[c].texels[p] = static_cast<uint8_t>(std::min<unsigned>(sums[c][p], 255));
  }
  out.region = m_region;
  return {};
}

void WarpPlan::add(unsigned tid, const gl::Triangle& triangle, const gl::Texture& texture) {
  if (tid >= m_entries.size()) m_entries.resize(tid + 1);
  Entry& entry = m_entries[tid];
  if (!entry.refused.empty()) return;
  if (!entry.used) {
    const std::optional<TexturePlane> plane = texture_plane(triangle, texture);
    if (!plane) {
      entry.refused = "a triangle's texture coordinates are collinear or a vertex has no positive w";
      return;
    }
    entry.plane = *plane;
  } else if (!on_plane(entry.plane, triangle, texture)) {
    entry.refused = "its triangles do not share one texture plane";
    return;
  }
  for (int k = 0; k < 3; ++k) {
    const float u = triangle.v[k].tex[0].s * static_cast<float>(texture.width);
    const float v = triangle.v[k].tex[0].t * static_cast<float>(texture.height);
    const bool first = !entry.used && k == 0;
    entry.u_min = first ? u : std::min(entry.u_min, u);
    entry.u_max = first ? u : std::max(entry.u_max, u);
    entry.v_min = first ? v : std::min(entry.v_min, v);
    entry.v_max = first ? v : std::max(entry.v_max, v);
  }
  entry.used = true;
}

bool WarpPlan::warped(unsigned tid) const {
  return tid < m_entries.size() && m_entries[tid].used && m_entries[tid].refused.empty();
}

const std::string& WarpPlan::reason(unsigned tid) const {
  return tid < m_entries.size() ? m_entries[tid].refused : m_none;
}

void WarpPlan::refuse(unsigned tid, const std::string& why) {
  if (tid >= m_entries.size()) m_entries.resize(tid + 1);
  m_entries[tid].refused = why;
}

std::string WarpPlan::job(unsigned tid, const gl::Texture& texture, int frame_width, int frame_height, int max_texels,
                          WarpJob& job) {
  const Entry& entry = m_entries.at(tid);
  std::string error = job.prepare(entry.plane, texture, entry.u_min, entry.u_max, entry.v_min, entry.v_max, frame_width,
                                  frame_height, max_texels);
  if (!error.empty()) refuse(tid, error);
  return error;
}

}  // namespace tessera::ap_tile
