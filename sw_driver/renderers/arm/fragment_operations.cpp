// The arm renderer's fragment operations after shading: a span's stores
// (stencil, depth, colour with blending, the logic op and the colour mask),
// as runs of consecutive pixels.
#include <cstring>

#include "renderers/arm/arm_rasterizer.h"
#include "renderers/arm/draw_context.h"
#include "renderers/common/fragment_ops.h"

namespace tessera::arm {

using renderers::blend;
using renderers::logic_op;

void ArmRasterizer::store_span(const DrawContext& c, uint32_t row_offset, int x_first, int n, uint32_t passed) {
  const uint32_t first = row_offset + uint32_t(x_first);
  uint8_t* const pass = m_pass.data();
  uint8_t* const stencil_new = m_stencil_new.data();
  const uint16_t* const depth_new = m_depth_new.data();
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

}  // namespace tessera::arm
