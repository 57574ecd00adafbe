#include "renderers/arm/arm_renderer.h"

#include "gl/runtime.h"

namespace tessera::arm {

HostFrame::HostFrame(AppEnvironment& env) : display(env), memory(*env.host) {
  buffers.width = display.width();
  buffers.height = display.height();
  buffers.color_format = display.format();
  buffers.color_address = display.back_buffer();
  buffers.depth_address = gl::allocate(buffers.width * buffers.height * 2);
  buffers.stencil_address = gl::allocate(buffers.width * buffers.height);
  core = std::make_unique<ArmRasterizer>(memory, buffers);
}

void HostFrame::present() {
  display.present();
  buffers.color_address = display.back_buffer();
  core->set_color_address(buffers.color_address);
}

ArmRenderer::ArmRenderer(AppEnvironment& env) : m_frame(env) {}

}  // namespace tessera::arm
