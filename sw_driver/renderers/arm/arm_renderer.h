// The `arm` back end: the study's sequential software rasterizer running on
// the ARM host. Colour buffers are the display's two frame buffers, depth
// (16 bits) and stencil (8 bits) buffers are allocated in system memory, and
// every access the rasterizer declares is charged through the host model
// (data cache, write buffer, bus). Presenting goes through the display
// driver (host copy or display DMA).
#pragma once

#include <memory>

#include "device/app_environment.h"
#include "device/display_driver.h"
#include "gl/renderer.h"
#include "renderers/arm/arm_rasterizer.h"
#include "renderers/arm/pixel_memory.h"
#include "renderers/backend_entry_points.h"

namespace tessera::arm {

// PixelMemory on the host model: spans become HostApi span accesses.
class HostPixelMemory : public PixelMemory {
 public:
  explicit HostPixelMemory(HostApi& host) : m_host(host) {}
  const uint8_t* load(uint32_t address, unsigned size, unsigned count) override {
    return m_host.load_span(address, size, count);
  }
  uint8_t* store(uint32_t address, unsigned size, unsigned count) override {
    return m_host.store_span(address, size, count);
  }
  void charge(HostCost cost, uint64_t units) override { costs::charge(m_host, cost, units); }

 private:
  HostApi& m_host;
};

class ArmRenderer : public gl::Renderer {
 public:
  explicit ArmRenderer(AppEnvironment& env);

  // Depth as uint16 and stencil as uint8 per pixel (arm_rasterizer.h).

  const char* name() const override { return "tessera arm (software, ARM922T)"; }
  gl::RendererCapabilities capabilities() const override { return backends::arm::CAPABILITIES; }
  unsigned width() const override { return m_display.width(); }
  unsigned height() const override { return m_display.height(); }
  PixelFormat color_format() const override { return m_display.format(); }
  void clear(const gl::ClearRequest& request) override { m_core->clear(request); }
  void draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) override {
    m_core->draw(state, triangles, count);
  }
  void read_pixels(int x, int y, int width, int height, uint8_t* rgba) override {
    m_core->read_pixels(x, y, width, height, rgba);
  }
  void finish() override {}
  void present() override;

 private:
  DisplayDriver m_display;
  HostPixelMemory m_memory;
  std::unique_ptr<ArmRasterizer> m_core;
};

}  // namespace tessera::arm
