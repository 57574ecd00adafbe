#include "renderers/arm/arm_renderer.h"

#include "gl/runtime.h"

namespace tessera::arm {

ArmRenderer::ArmRenderer(AppEnvironment& env) : m_display(env), m_memory(*env.host) {
  FrameBuffers buffers;
  buffers.width = m_display.width();
  buffers.height = m_display.height();
  buffers.color_format = m_display.format();
  buffers.color_address = m_display.back_buffer();
  buffers.depth_address = gl::allocate(buffers.width * buffers.height * 2);
  buffers.stencil_address = gl::allocate(buffers.width * buffers.height);
  m_core = std::make_unique<ArmRasterizer>(m_memory, buffers);
}

void ArmRenderer::present() {
  m_display.present();
  m_core->set_color_address(m_display.back_buffer());
}

}  // namespace tessera::arm
