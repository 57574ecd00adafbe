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

// The frame as the host draws it, shared by the back ends that draw into
// system memory (arm, ap-pixel, ap-object): the display's two colour
// buffers, a depth (16 bits) and a stencil (8 bits) buffer allocated in
// system memory, and the arm rasterizer on them (arm draws with it; the
// array back ends clear and read back with it).
struct HostFrame {
  explicit HostFrame(AppEnvironment& env);
  // Shows the back buffer (DisplayDriver::present) and draws into the next.
  void present();

  DisplayDriver display;
  HostPixelMemory memory;
  FrameBuffers buffers;
  std::unique_ptr<ArmRasterizer> core;
};

class ArmRenderer : public gl::Renderer {
 public:
  explicit ArmRenderer(AppEnvironment& env);

  // Depth as uint16 and stencil as uint8 per pixel (arm_rasterizer.h).

  const char* name() const override { return "tessera arm (software, ARM922T)"; }
  gl::RendererCapabilities capabilities() const override { return backends::arm::CAPABILITIES; }
  unsigned width() const override { return m_frame.buffers.width; }
  unsigned height() const override { return m_frame.buffers.height; }
  PixelFormat color_format() const override { return m_frame.buffers.color_format; }
  void clear(const gl::ClearRequest& request) override { m_frame.core->clear(request); }
  void draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) override {
    m_frame.core->draw(state, triangles, count);
  }
  void read_pixels(int x, int y, int width, int height, uint8_t* rgba) override {
    m_frame.core->read_pixels(x, y, width, height, rgba);
  }
  void finish() override {}
  void present() override { m_frame.present(); }

 private:
  HostFrame m_frame;
};

}  // namespace tessera::arm
