// The `toy` back end: the least a gl::Renderer does, written by
// scripts/check_add_backend.py into a copy of the tree to check
// docs/how_to_add_a_backend.md. It clears the colour buffer (the display's
// back buffer) through the host, ignores triangles and presents through
// the display driver, as the arm back end does. It has no depth or stencil
// buffer to clear: the table's depth bits are only what EGL reports.
#pragma once

#include <cstddef>
#include <cstdint>

#include "device/app_environment.h"
#include "device/display_driver.h"
#include "gl/renderer.h"
#include "renderers/backend_entry_points.h"

namespace tessera::toy {

class ToyRenderer : public gl::Renderer {
 public:
  explicit ToyRenderer(AppEnvironment& env);

  const char* name() const override { return "tessera toy (clears only)"; }
  gl::RendererCapabilities capabilities() const override { return backends::toy::CAPABILITIES; }
  unsigned width() const override { return m_display.width(); }
  unsigned height() const override { return m_display.height(); }
  PixelFormat color_format() const override { return m_display.format(); }
  void clear(const gl::ClearRequest& request) override;
  // The toy draws no triangle: its frames show the clear colour alone.
  void draw(const gl::RasterState&, const gl::Triangle*, size_t) override {}
  void read_pixels(int x, int y, int width, int height, uint8_t* rgba) override;
  void finish() override {}
  void present() override { m_display.present(); }

 private:
  // The address of pixel (x, y), y = 0 the bottom row (GL's), in the back
  // buffer, whose rows are in display order (top row first).
  uint32_t pixel_address(int x, int y) const;

  HostApi& m_host;
  DisplayDriver m_display;
};

}  // namespace tessera::toy
