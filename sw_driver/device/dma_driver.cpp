#include "device/dma_driver.h"

#include "dma/dma_regs.h"
#include "soc/irq_map.h"
#include "soc/memory_map.h"

namespace tessera {

namespace regs = dma_regs;

namespace {

constexpr uint32_t BASE = memory_map::dma_regs.base;

uint32_t channel_reg(unsigned channel, uint32_t offset) {
  return BASE + regs::channel_base(channel) + offset;
}

}  // namespace

DmaDriver::DmaDriver(AppEnvironment& env) : m_host(*env.host) {}

bool DmaDriver::present() {
  return m_host.read32(BASE + regs::ID) == regs::ID_VALUE;
}

unsigned DmaDriver::channels() {
  return m_host.read32(BASE + regs::CHANNELS);
}

dma::Descriptor DmaDriver::to_cmem(uint32_t src, uint32_t cmem, unsigned count, unsigned element_bytes) {
  dma::Descriptor d;
  d.ctrl = dma::Descriptor::make_ctrl(dma::Kind::mem_to_cmem, element_bytes);
  d.src = src;
  d.dst = cmem;
  d.length = count * element_bytes;
  return d;
}

dma::Descriptor DmaDriver::from_cmem(uint32_t cmem, uint32_t dst, unsigned count, unsigned element_bytes) {
  dma::Descriptor d;
  d.ctrl = dma::Descriptor::make_ctrl(dma::Kind::cmem_to_mem, element_bytes);
  d.src = cmem;
  d.dst = dst;
  d.length = count * element_bytes;
  return d;
}

dma::Descriptor DmaDriver::copy(uint32_t src, uint32_t dst, uint32_t bytes) {
  dma::Descriptor d;
  d.ctrl = dma::Descriptor::make_ctrl(dma::Kind::mem_to_mem);
  d.src = src;
  d.dst = dst;
  d.length = bytes;
  return d;
}

dma::Descriptor DmaDriver::broadcast(uint32_t src, uint32_t cmem, uint32_t bytes, uint32_t mask) {
  dma::Descriptor d;
  d.ctrl = dma::Descriptor::make_ctrl(dma::Kind::broadcast);
  d.src = src;
  d.dst = cmem;
  d.length = bytes;
  d.mask = mask;
  return d;
}

void DmaDriver::write_chain(uint32_t address, std::vector<dma::Descriptor> descriptors) {
  for (size_t i = 0; i < descriptors.size(); ++i) {
    descriptors[i].next =
        i + 1 < descriptors.size() ? address + static_cast<uint32_t>((i + 1) * dma::DESCRIPTOR_BYTES) : 0;
    const auto words = dma::encode(descriptors[i]);
    m_host.write_words(address + static_cast<uint32_t>(i * dma::DESCRIPTOR_BYTES), words.data(), dma::DESCRIPTOR_WORDS);
  }
}

void DmaDriver::enable_irq(unsigned channel) {
  const uint32_t bits = regs::irq_done(channel) | regs::irq_error(channel);
  m_latched &= ~bits;  // a new start: what was kept belonged to the previous one
  if ((m_enabled & bits) == bits) return;
  m_enabled |= bits;
  m_host.write32(BASE + regs::IRQ_ENABLE, m_enabled);
}

void DmaDriver::start(unsigned channel, const dma::Descriptor& descriptor) {
  enable_irq(channel);
  const auto words = dma::encode(descriptor);
  for (unsigned i = 0; i < dma::DESCRIPTOR_WORDS; ++i) m_host.write32(channel_reg(channel, 4 * i), words[i]);
  m_host.write32(channel_reg(channel, regs::CH_START), regs::START_GO);
}

void DmaDriver::start_chain(unsigned channel, uint32_t address) {
  enable_irq(channel);
  m_host.write32(channel_reg(channel, regs::CH_D_NEXT), address);
  m_host.write32(channel_reg(channel, regs::CH_START), regs::START_GO | regs::START_CHAIN_ONLY);
}

bool DmaDriver::busy(unsigned channel) {
  return (m_host.read32(channel_reg(channel, regs::CH_STATUS)) & regs::STATUS_BUSY) != 0;
}

void DmaDriver::finish(unsigned channel) {
  if ((m_host.read32(channel_reg(channel, regs::CH_STATUS)) & regs::STATUS_ERROR) == 0) return;
  const uint32_t code = m_host.read32(channel_reg(channel, regs::CH_ERROR_CODE));
  const uint32_t descriptor = m_host.read32(channel_reg(channel, regs::CH_ERROR_DESC));
  const uint64_t address = m_host.read32(channel_reg(channel, regs::CH_ERROR_ADDR)) |
                           uint64_t{m_host.read32(channel_reg(channel, regs::CH_ERROR_ADDR_HI))} << 32;
  throw DmaError("DMA channel " + std::to_string(channel) + " stopped: " +
                     dma::error_text(static_cast<dma::Error>(code)) + " (the simulator's log names the descriptor)",
                 code, descriptor, address);
}

void DmaDriver::wait(unsigned channel) {
  // The line is shared by the channels and level-sensitive: what is
  // pending is acknowledged at once and remembered, as an interrupt
  // handler would, so that another channel's pending interrupt does not
  // turn this wait into a poll of IRQ_STATUS.
  const uint32_t bits = regs::irq_done(channel) | regs::irq_error(channel);
  while ((m_latched & bits) == 0) {
    const uint32_t pending = m_host.read32(BASE + regs::IRQ_STATUS) & m_enabled;
    if (pending != 0) {
      m_host.write32(BASE + regs::IRQ_STATUS, pending);
      m_latched |= pending;
    } else {
      m_host.wait_irq(irq_map::dma);
    }
  }
  m_latched &= ~bits;
  finish(channel);
}

void DmaDriver::poll(unsigned channel) {
  while (busy(channel)) {
  }
  const uint32_t bits = regs::irq_done(channel) | regs::irq_error(channel);
  m_host.write32(BASE + regs::IRQ_STATUS, bits);
  m_latched &= ~bits;
  finish(channel);
}

}  // namespace tessera
