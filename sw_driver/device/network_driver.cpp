#include "device/network_driver.h"

#include "cluster/node_memory_map.h"
#include "network/ni_regs.h"

namespace tessera {

namespace {

uint32_t ni_address(uint32_t offset) {
  return node_memory_map::ni_regs.base + offset;
}

}  // namespace

NetworkDriver::NetworkDriver(HostApi& host) : m_host(host) {
  m_id = reg(ni_regs::ID);
  m_nodes = reg(ni_regs::NODES);
}

uint32_t NetworkDriver::reg(uint32_t offset) {
  return m_host.read32(ni_address(offset));
}

void NetworkDriver::set_reg(uint32_t offset, uint32_t value) {
  m_host.write32(ni_address(offset), value);
}

void NetworkDriver::start(const Rings& rings) {
  m_rings = rings;
  set_reg(ni_regs::CTRL, 0);
  set_reg(ni_regs::TX_BASE, rings.tx_base);
  set_reg(ni_regs::TX_COUNT, rings.tx_count);
  set_reg(ni_regs::RX_BASE, rings.rx_base);
  set_reg(ni_regs::RX_COUNT, rings.rx_count);
  set_reg(ni_regs::RX_SLOT_BYTES, rings.rx_slot_bytes);
  set_reg(ni_regs::IRQ_ENABLE, ni_regs::IRQ_TX_DONE | ni_regs::IRQ_RX | ni_regs::IRQ_ERROR);
  set_reg(ni_regs::CTRL, ni_regs::CTRL_ENABLE);
  m_submitted = m_completed = 0;
  m_tx_head = m_rx_tail = m_rx_head = 0;
}

void NetworkDriver::check_error(uint32_t status) {
  if ((status & ni_regs::IRQ_ERROR) == 0) return;
  const uint32_t code = reg(ni_regs::ERROR_CODE);
  const uint32_t address = reg(ni_regs::ERROR_ADDR);
  throw NetworkError("network interface of node " + std::to_string(m_id) + ": error " + std::to_string(code) + " at " +
                         std::to_string(address),
                     code, address);
}

uint32_t NetworkDriver::completed() {
  const unsigned head = reg(ni_regs::TX_HEAD);
  m_completed += (head + m_rings.tx_count - m_tx_head) % m_rings.tx_count;
  m_tx_head = head;
  return m_completed;
}

void NetworkDriver::wait_sent(uint32_t ticket) {
  while (static_cast<int32_t>(completed() - ticket) <= 0) wait();
}

uint32_t NetworkDriver::send(unsigned destination, uint32_t payload, uint32_t bytes, uint32_t tag) {
  // One descriptor always stays free: head == tail means an empty ring.
  while (m_submitted - m_completed >= m_rings.tx_count - 1) {
    if (m_submitted - completed() < m_rings.tx_count - 1) break;
    wait();
  }
  const unsigned tail = m_submitted % m_rings.tx_count;
  const uint32_t words[4] = {destination, payload, bytes, tag};
  m_host.write_words(m_rings.tx_base + tail * DESCRIPTOR_BYTES, words, 4);
  set_reg(ni_regs::TX_TAIL, (tail + 1) % m_rings.tx_count);
  return m_submitted++;
}

bool NetworkDriver::peek(Message& message) {
  if (m_rx_tail == m_rx_head) {
    m_rx_head = reg(ni_regs::RX_HEAD);
    if (m_rx_tail == m_rx_head) return false;
  }
  const uint32_t slot = m_rings.rx_base + m_rx_tail * m_rings.rx_slot_bytes;
  uint32_t header[4];
  m_host.read_words(slot, header, 4);
  message.source = header[0];
  message.bytes = header[1];
  message.tag = header[2];
  message.sequence = header[3];
  message.payload = slot + HEADER_BYTES;
  return true;
}

void NetworkDriver::release() {
  m_rx_tail = (m_rx_tail + 1) % m_rings.rx_count;
  set_reg(ni_regs::RX_TAIL, m_rx_tail);
}

void NetworkDriver::wait() {
  // Clear what has been seen; what comes after keeps the line high.
  const uint32_t status = reg(ni_regs::IRQ_STATUS);
  check_error(status);
  if (status != 0) {
    set_reg(ni_regs::IRQ_STATUS, status);
    return;  // something happened since the caller looked: let it look again
  }
  m_host.wait_irq(node_irq::network_interface);
  check_error(reg(ni_regs::IRQ_STATUS));
}

}  // namespace tessera
