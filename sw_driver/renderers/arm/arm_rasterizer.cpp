// The arm renderer's functional core: clears, draws (per-draw decisions:
// draw_context; per-triangle set-up: triangle_setup; scan conversion here,
// with edge_walk; span shading: span_shading; the stores:
// fragment_operations.cpp) and read-back. Formats, rounding and the fill
// rule are stated in arm_rasterizer.h, instruction counts in README.md.
#include "renderers/arm/arm_rasterizer.h"

#include <algorithm>
#include <cstring>

#include "renderers/arm/draw_context.h"
#include "renderers/arm/edge_walk.h"
#include "renderers/arm/span_shading.h"
#include "renderers/arm/triangle_setup.h"

namespace tessera::arm {

namespace {

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

}  // namespace

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
  if (triangles == nullptr || !make_draw_context(state, m_buffers, c)) return;
  for (size_t i = 0; i < count; ++i) draw_triangle(c, triangles[i]);
}

void ArmRasterizer::draw_triangle(const DrawContext& c, const gl::Triangle& tri) {
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
  setup_triangle(c, tri, x, y, area2, m_memory, s);

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

void ArmRasterizer::shade_span(const DrawContext& c, const TriangleSetup& s, int j, int x_first, int x_last) {
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

  const SpanRows rows{m_depth_old.data(), m_depth_new.data(), m_stencil_new.data(), m_pass.data(), m_source.data()};
  SpanCounts counts;
  shade_pixels(c, s, j, x_first, n, rows, m_memory, counts);
  store_span(c, row_offset, x_first, n, counts.passed);
  charge_span(c, s, n, counts, m_memory);
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
