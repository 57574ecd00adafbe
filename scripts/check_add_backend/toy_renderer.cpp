#include "renderers/toy/toy_renderer.h"

#include <algorithm>
#include <cstring>

namespace tessera::toy {

ToyRenderer::ToyRenderer(AppEnvironment& env) : m_host(*env.host), m_display(env) {}

uint32_t ToyRenderer::pixel_address(int x, int y) const {
  const uint32_t row = m_display.height() - 1 - static_cast<uint32_t>(y);
  return m_display.back_buffer() + row * m_display.stride() + static_cast<uint32_t>(x) * m_display.bytes_per_pixel();
}

// Every pixel of the scissor box (the whole buffer without a scissor) gets
// the clear colour, one row of stores at a time; the colour mask is
// ignored (a toy). The stores are the host's only charge (no row of
// sw_driver/costs/host_costs.def: docs/how_to_add_a_backend.md, section 3).
void ToyRenderer::clear(const gl::ClearRequest& request) {
  if (!request.color) return;
  int x0 = 0, y0 = 0, x1 = static_cast<int>(width()), y1 = static_cast<int>(height());
  if (request.scissor_test) {
    x0 = std::max(x0, request.scissor_x);
    y0 = std::max(y0, request.scissor_y);
    x1 = static_cast<int>(std::min<int64_t>(x1, int64_t{request.scissor_x} + request.scissor_width));
    y1 = static_cast<int>(std::min<int64_t>(y1, int64_t{request.scissor_y} + request.scissor_height));
  }
  if (x0 >= x1 || y0 >= y1) return;
  const PixelFormat format = m_display.format();
  const unsigned bytes = m_display.bytes_per_pixel();
  const uint32_t rgba = uint32_t{request.rgba[0]} | uint32_t{request.rgba[1]} << 8 | uint32_t{request.rgba[2]} << 16 |
                        uint32_t{request.rgba[3]} << 24;
  const uint32_t packed = pack_pixel(format, rgba);
  const unsigned count = static_cast<unsigned>(x1 - x0);
  for (int y = y0; y < y1; ++y) {
    uint8_t* row = m_host.store_span(pixel_address(x0, y), bytes, count);
    for (unsigned i = 0; i < count; ++i) store_pixel(format, row + i * bytes, packed);
  }
}

// Pixels outside the buffer read as zeros.
void ToyRenderer::read_pixels(int x, int y, int width, int height, uint8_t* rgba) {
  if (width <= 0 || height <= 0 || rgba == nullptr) return;
  std::memset(rgba, 0, static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  const int x0 = std::max(x, 0);
  const int x1 = static_cast<int>(std::min<int64_t>(int64_t{x} + width, this->width()));
  if (x0 >= x1) return;
  const PixelFormat format = m_display.format();
  const unsigned bytes = m_display.bytes_per_pixel();
  for (int row = 0; row < height; ++row) {
    const int64_t gy = int64_t{y} + row;
    if (gy < 0 || gy >= int64_t{this->height()}) continue;
    const uint8_t* in =
        m_host.load_span(pixel_address(x0, static_cast<int>(gy)), bytes, static_cast<unsigned>(x1 - x0));
    uint8_t* out = rgba + (static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(x0 - x)) * 4;
    for (int i = 0; i < x1 - x0; ++i) {
      const uint32_t color = unpack_pixel(format, load_pixel(format, in + i * bytes));
      for (unsigned c = 0; c < 4; ++c) out[4 * i + c] = static_cast<uint8_t>(color >> (8 * c));
    }
  }
}

}  // namespace tessera::toy
