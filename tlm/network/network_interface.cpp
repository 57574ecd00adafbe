#include "network/network_interface.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "common/log.h"
#include "network/network.h"

namespace tessera {

using sc_core::sc_time;
namespace regs = ni_regs;

namespace {

uint32_t word(const uint8_t* bytes, uint32_t offset) {
  return uint32_t{bytes[offset]} | uint32_t{bytes[offset + 1]} << 8 | uint32_t{bytes[offset + 2]} << 16 |
         uint32_t{bytes[offset + 3]} << 24;
}

void put_word(uint8_t* bytes, uint32_t offset, uint32_t value) {
  for (unsigned i = 0; i < 4; ++i) bytes[offset + i] = static_cast<uint8_t>(value >> (8 * i));
}

}  // namespace

NetworkInterface::NetworkInterface(sc_core::sc_module_name name, const NetworkInterfaceParams& params)
    : Peripheral(name, params.clock_period),
      out("out", activity()),
      m_params(params),
      m_sequence(params.nodes, 0),
      m_messages_sent(counter("messages_sent", "messages handed to the network or looped back")),
      m_bytes_sent(counter("bytes_sent", "payload bytes of the messages sent")),
      m_messages_received(counter("messages_received", "messages written into a receive slot")),
      m_bytes_received(counter("bytes_received", "payload bytes written into receive slots")),
      m_loopback(counter("loopback", "messages to this node, looped back without the network")),
      m_dropped(counter("dropped", "arriving messages longer than a receive slot holds, dropped")),
      m_errors(counter("errors", "errors raised (ERROR_CODE set)")),
      m_rx_stalls(counter("rx_stalls", "times an arrival found the receive ring full")) {
  if (params.nodes == 0 || params.node >= params.nodes)
    throw std::invalid_argument(std::string(this->name()) + ": node " + std::to_string(params.node) + " of " +
                                std::to_string(params.nodes) + " nodes");
  if (params.burst_bytes == 0) throw std::invalid_argument(std::string(this->name()) + ": zero burst length");
  out.configure(params.burst_bytes, BusMaster::OnError::stop);
  ID.set_reset(params.node);
  NODES.set_reset(params.nodes);
  bind_irq_registers(IRQ_STATUS, IRQ_ENABLE);
  CTRL.on_write(this, &NetworkInterface::write_CTRL);
  STATUS.on_read(this, &NetworkInterface::read_STATUS);
  TX_BASE.on_write(this, &NetworkInterface::write_TX_BASE);
  TX_COUNT.on_write(this, &NetworkInterface::write_TX_COUNT);
  TX_TAIL.on_write(this, &NetworkInterface::write_TX_TAIL);
  RX_BASE.on_write(this, &NetworkInterface::write_RX_BASE);
  RX_COUNT.on_write(this, &NetworkInterface::write_RX_COUNT);
  RX_SLOT_BYTES.on_write(this, &NetworkInterface::write_RX_SLOT_BYTES);
  RX_TAIL.on_write(this, &NetworkInterface::write_RX_TAIL);
  SC_THREAD(transmit);
  SC_THREAD(receive);
}

void NetworkInterface::connect(Network& network) {
  network.attach(m_params.node, *this);
  m_network = &network;
}

// --- Registers -------------------------------------------------------------

const char* NetworkInterface::write_refusal(const tlm::tlm_generic_payload& gp) const {
  if (!enabled()) return nullptr;
  switch (gp.get_address()) {
    case regs::TX_BASE:
    case regs::TX_COUNT:
    case regs::RX_BASE:
    case regs::RX_COUNT:
    case regs::RX_SLOT_BYTES: return "ring registers written while CTRL.ENABLE is set";
    default: return nullptr;
  }
}

bool NetworkInterface::rings_valid(uint32_t& offending) const {
  const std::pair<bool, uint32_t> checks[] = {
      {TX_COUNT.get() == 0, TX_COUNT.get()},
      {TX_BASE.get() % regs::TX_BASE_ALIGN != 0, TX_BASE.get()},
      {RX_COUNT.get() < regs::MIN_RX_COUNT, RX_COUNT.get()},
      {RX_BASE.get() % regs::RX_BASE_ALIGN != 0, RX_BASE.get()},
      {RX_SLOT_BYTES.get() < regs::HEADER_BYTES || RX_SLOT_BYTES.get() % 4 != 0, RX_SLOT_BYTES.get()},
  };
  for (const auto& [bad, value] : checks)
    if (bad) {
      offending = value;
      return false;
    }
  return true;
}

void NetworkInterface::write_CTRL(uint32_t value) {
  const bool enable = (value & regs::CTRL_ENABLE) != 0;
  uint32_t offending = 0;
  if (enable && !enabled() && !rings_valid(offending)) {
    CTRL.set(value & ~regs::CTRL_ENABLE);
    fail(regs::Error::bad_ring, offending, m_regs.access_delay());
    return;
  }
  CTRL.set(value);
  if (enable) {
    m_tx_ready = m_rx_ready = access_time();
    m_tx_wake.notify(m_regs.access_delay());
    m_rx_wake.notify(m_regs.access_delay());
  }
}

uint32_t NetworkInterface::read_STATUS() const {
  return (m_tx_busy ? regs::STATUS_TX_BUSY : 0u) | (m_arrivals.empty() ? 0u : regs::STATUS_RX_WAITING);
}

// A ring's base, count or slot size written: a new ring, empty.
void NetworkInterface::new_ring(Register& head, Register& tail) {
  head.set(0);
  tail.set(0);
}

void NetworkInterface::write_TX_BASE(uint32_t value) {
  TX_BASE.set(value);
  new_ring(TX_HEAD, TX_TAIL);
}

void NetworkInterface::write_TX_COUNT(uint32_t value) {
  TX_COUNT.set(value);
  new_ring(TX_HEAD, TX_TAIL);
}

void NetworkInterface::write_TX_TAIL(uint32_t value) {
  if (value >= TX_COUNT.get()) return fail(regs::Error::bad_ring, value, m_regs.access_delay());
  TX_TAIL.set(value);
  m_tx_ready = access_time();
  m_tx_wake.notify(m_regs.access_delay());
}

void NetworkInterface::write_RX_BASE(uint32_t value) {
  RX_BASE.set(value);
  new_ring(RX_HEAD, RX_TAIL);
}

void NetworkInterface::write_RX_COUNT(uint32_t value) {
  RX_COUNT.set(value);
  new_ring(RX_HEAD, RX_TAIL);
}

void NetworkInterface::write_RX_SLOT_BYTES(uint32_t value) {
  RX_SLOT_BYTES.set(value);
  new_ring(RX_HEAD, RX_TAIL);
}

void NetworkInterface::write_RX_TAIL(uint32_t value) {
  if (value >= RX_COUNT.get()) return fail(regs::Error::bad_ring, value, m_regs.access_delay());
  RX_TAIL.set(value);
  m_rx_ready = access_time();
  m_rx_wake.notify(m_regs.access_delay());
}

// --- Common ----------------------------------------------------------------

bool NetworkInterface::in_memory(uint64_t address, uint64_t bytes) const {
  return address >= m_params.memory_base && address + bytes <= m_params.memory_base + m_params.memory_bytes;
}

bool NetworkInterface::transfer(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes) {
  if (bytes == 0) return true;
  sc_time local = sc_core::SC_ZERO_TIME;
  const bool ok = out.transfer(command, address, data, bytes, local);
  sc_core::wait(local);
  return ok;
}

void NetworkInterface::fail(regs::Error error, uint32_t address, const sc_time& delay) {
  ERROR_CODE.set(static_cast<uint32_t>(error));
  ERROR_ADDR.set(address);
  const bool stops = regs::error_stops(error);
  if (stops) CTRL.set(CTRL.get() & ~regs::CTRL_ENABLE);
  ++m_errors;
  log::warning(name(), std::string(regs::error_text(error)) + " (" + log::hex(address) + ")" +
                           (stops ? "; interface stopped" : ""));
  raise_irq(regs::IRQ_ERROR, delay);
  m_progress.notify(sc_core::SC_ZERO_TIME);
}

// --- Send ------------------------------------------------------------------

void NetworkInterface::transmit() {
  for (;;) {
    if (!enabled() || TX_HEAD.get() == TX_TAIL.get()) {
      sc_core::wait(m_tx_wake);
      continue;
    }
    const sc_time now = sc_core::sc_time_stamp();
    if (m_tx_ready > now) {
      sc_core::wait(m_tx_ready - now);
      continue;
    }
    m_tx_busy = true;
    send_one();
    m_tx_busy_time += sc_core::sc_time_stamp() - now;
    m_tx_busy = false;
  }
}

void NetworkInterface::send_one() {
  const uint32_t head = TX_HEAD.get();
  // In 64 bits: a ring reaching past 4 GiB is outside memory, not wrapped into it.
  const uint64_t where = uint64_t{TX_BASE.get()} + uint64_t{head} * regs::DESCRIPTOR_BYTES;
  uint8_t descriptor[regs::DESCRIPTOR_BYTES] = {};
  if (!in_memory(where, regs::DESCRIPTOR_BYTES) ||
      !transfer(tlm::TLM_READ_COMMAND, where, descriptor, regs::DESCRIPTOR_BYTES))
    return fail(regs::Error::descriptor_fault, static_cast<uint32_t>(where));
  NetworkMessage message;
  message.source = m_params.node;
  message.destination = word(descriptor, regs::DESC_DESTINATION);
  const uint32_t payload = word(descriptor, regs::DESC_PAYLOAD);
  const uint32_t length = word(descriptor, regs::DESC_LENGTH);
  message.tag = word(descriptor, regs::DESC_TAG);
  if (message.destination >= m_params.nodes) return fail(regs::Error::bad_destination, message.destination);
  if (!in_memory(payload, length)) return fail(regs::Error::payload_fault, payload);
  message.payload.resize(length);
  if (!transfer(tlm::TLM_READ_COMMAND, payload, message.payload.data(), length))
    return fail(regs::Error::payload_fault, payload);
  message.sequence = m_sequence[message.destination]++;
  ++m_messages_sent;
  m_bytes_sent += length;
  if (message.destination == m_params.node) {
    ++m_loopback;
    deliver(std::move(message));
  } else if (m_network) {
    m_network->send(std::move(message));
  } else {
    log::error(name(), "message to node " + std::to_string(message.destination) +
                           " dropped: the interface is not connected to a network");
  }
  TX_HEAD.set((head + 1) % TX_COUNT.get());
  raise_irq(regs::IRQ_TX_DONE);
  m_progress.notify(sc_core::SC_ZERO_TIME);
}

// --- Receive ---------------------------------------------------------------

void NetworkInterface::deliver(NetworkMessage&& message) {
  m_arrivals.push_back(std::move(message));
  m_rx_wake.notify(sc_core::SC_ZERO_TIME);
}

bool NetworkInterface::rx_slot_free() const {
  const uint32_t count = RX_COUNT.get();
  return count != 0 && (RX_HEAD.get() + 1) % count != RX_TAIL.get();
}

void NetworkInterface::receive() {
  for (;;) {
    const sc_time now = sc_core::sc_time_stamp();
    if (m_arrivals.empty() || !enabled()) {
      sc_core::wait(m_rx_wake);
      continue;
    }
    if (!rx_slot_free()) {
      if (!m_rx_stalled) {
        m_rx_stalled = true;
        m_rx_stall_start = now;
        ++m_rx_stalls;
      }
      sc_core::wait(m_rx_wake);
      continue;
    }
    if (m_rx_ready > now) {
      sc_core::wait(m_rx_ready - now);
      continue;
    }
    if (m_rx_stalled) {
      m_rx_stalled = false;
      m_rx_stall_time += now - m_rx_stall_start;
    }
    receive_one();
  }
}

void NetworkInterface::receive_one() {
  const NetworkMessage& message = m_arrivals.front();
  const uint32_t length = static_cast<uint32_t>(message.payload.size());
  const uint32_t slot_bytes = RX_SLOT_BYTES.get();
  if (length > slot_bytes - regs::HEADER_BYTES) {
    log::warning(name(), "message from node " + std::to_string(message.source) + " with tag " + log::hex(message.tag) +
                             " dropped");
    m_arrivals.pop_front();
    ++m_dropped;
    return fail(regs::Error::message_too_long, length);
  }
  const uint32_t head = RX_HEAD.get();
  const uint64_t slot = uint64_t{RX_BASE.get()} + uint64_t{head} * slot_bytes;
  std::vector<uint8_t> bytes(regs::HEADER_BYTES + length);
  put_word(bytes.data(), regs::HDR_SOURCE, message.source);
  put_word(bytes.data(), regs::HDR_LENGTH, length);
  put_word(bytes.data(), regs::HDR_TAG, message.tag);
  put_word(bytes.data(), regs::HDR_SEQUENCE, message.sequence);
  std::copy(message.payload.begin(), message.payload.end(), bytes.begin() + regs::HEADER_BYTES);
  // A message whose slot fails stays first in line for when software has
  // fixed the ring and enabled the interface again.
  if (!in_memory(slot, bytes.size()) ||
      !transfer(tlm::TLM_WRITE_COMMAND, slot, bytes.data(), static_cast<unsigned>(bytes.size())))
    return fail(regs::Error::slot_fault, static_cast<uint32_t>(slot));
  ++m_messages_received;
  m_bytes_received += length;
  m_arrivals.pop_front();
  RX_HEAD.set((head + 1) % RX_COUNT.get());
  raise_irq(regs::IRQ_RX);
  m_progress.notify(sc_core::SC_ZERO_TIME);
}

// --- Hooks -----------------------------------------------------------------

void NetworkInterface::trace_signals(sc_core::sc_trace_file* file) {
  sc_core::sc_trace(file, irq, std::string(name()) + ".irq");
}

nlohmann::json NetworkInterface::stats_json(const sc_time& elapsed) const {
  nlohmann::json stats = Peripheral::stats_json(elapsed);
  const double elapsed_s = elapsed.to_seconds();
  stats["node"] = m_params.node;
  stats["tx_busy_ns"] = m_tx_busy_time.to_seconds() * 1e9;
  stats["rx_stall_ns"] = m_rx_stall_time.to_seconds() * 1e9;
  stats["utilisation"] = elapsed_s > 0 ? m_tx_busy_time.to_seconds() / elapsed_s : 0.0;
  stats["elapsed_ns"] = elapsed_s * 1e9;
  return stats;
}

SummaryRow NetworkInterface::summary_row(const sc_time& elapsed) const {
  return busy_row(m_tx_busy_time, elapsed,
                  std::to_string(m_messages_sent.value) + " sent, " + std::to_string(m_messages_received.value) +
                      " received, " + std::to_string(m_errors.value) + " errors");
}

EnergyActivity NetworkInterface::energy_activity(const sc_time& now) const {
  (void)now;
  return {{"network_interface",
           {{"bytes", static_cast<double>(m_bytes_sent.value + m_bytes_received.value)},
            {"messages", static_cast<double>(m_messages_sent.value + m_messages_received.value)}}}};
}

}  // namespace tessera
