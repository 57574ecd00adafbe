#include "device/display_driver.h"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

#include "costs/host_cost.h"
#include "display/display_regs.h"
#include "soc/irq_map.h"
#include "soc/memory_map.h"

namespace tessera {

namespace regs = display_regs;

namespace {
constexpr uint32_t reg(uint32_t offset) {
  return memory_map::display_regs.base + offset;
}
}  // namespace

DisplayDriver::DisplayDriver(AppEnvironment& env)
    : m_host(*env.host), m_buffers{env.frame_buffers[0], env.frame_buffers[1]} {
  m_width = m_host.read32(reg(regs::WIDTH));
  m_height = m_host.read32(reg(regs::HEIGHT));
  const uint32_t format = m_host.read32(reg(regs::FORMAT));
  const std::optional<PixelFormat> known = pixel_format_from_code(format);
  if (!known)
    throw std::runtime_error("display driver: the display reports pixel format code " + std::to_string(format) +
                             ", which this driver does not know (" + pixel_format_names() + ")");
  m_format = *known;
  m_dma = m_host.read32(reg(regs::MODE)) == 1;
  if (m_dma) {
    m_host.write32(reg(regs::IRQ_ENABLE), regs::IRQ_SWAP_DONE);
    m_host.write32(reg(regs::CTRL), regs::CTRL_ENABLE);
  }
}

void DisplayDriver::present() {
  const uint32_t buffer = m_buffers[m_back];
  if (!m_dma) {
    // Copy loop of LDM/STM with eight registers, as hand-written ARM code
    // does: the LDM reads the frame where it is (through the cache), the STM
    // writes the registers to the port.
    const uint32_t bytes = m_width * m_height * bytes_per_pixel();
#if defined(TESSERA_HOST_ISS)
    uint32_t offset = 0;
    while (bytes - offset >= 4) {
      const unsigned count = std::min<uint32_t>(8, (bytes - offset) / 4);
      const auto* words = reinterpret_cast<const uint32_t*>(m_host.load_span(buffer + offset, 4, count));
      m_host.write_words(memory_map::display_port.base + offset, words, count);
      costs::charge(m_host, costs::HostCost::display_copy_block);
      offset += 4 * count;
    }
#else
    // The same blocks as one call (HostApi::copy_words), each block's
    // charge metered in order beforehand: the loop charges nothing else.
    const uint32_t words = bytes / 4, blocks = (words + 7) / 8;
    m_copy_cycles.resize(blocks);
    costs::meter_cycles_each(costs::HostCost::display_copy_block, m_copy_cycles.data(), blocks);
    m_host.copy_words(memory_map::display_port.base, buffer, words, m_copy_cycles.data());
    const uint32_t offset = 4 * words;
#endif
    if (offset < bytes) m_host.write16(memory_map::display_port.base + offset, m_host.read16(buffer + offset));
    m_host.write32(reg(regs::PRESENT), 1);
    return;
  }
  m_host.write32(reg(regs::BACK_BASE), buffer);
  m_host.write32(reg(regs::SWAP), 1);
  for (;;) {
    m_host.wait_irq(irq_map::display);
    const uint32_t status = m_host.read32(reg(regs::IRQ_STATUS));
    m_host.write32(reg(regs::IRQ_STATUS), status);
    if (status & regs::IRQ_SWAP_DONE) break;
  }
  m_back ^= 1;
}

}  // namespace tessera
