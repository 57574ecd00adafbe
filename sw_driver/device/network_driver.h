// Driver of a cluster node's network interface (tlm/network/README.md):
// the send ring and the receive ring in the node's memory, messages out by
// descriptor, messages in from the slots, and the wait for either. Every
// register access is a bus transaction of the node's host model; the
// rings' words are the host's loads and stores. On the SoC there is no
// network interface: only the cluster platform's nodes have one.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "host/host_api.h"

namespace tessera {

// The interface stopped with an error (ni_errors.def): its code and address.
class NetworkError : public std::runtime_error {
 public:
  NetworkError(const std::string& what, uint32_t code, uint32_t address)
      : std::runtime_error(what), m_code(code), m_address(address) {}
  uint32_t code() const { return m_code; }
  uint32_t address() const { return m_address; }

 private:
  uint32_t m_code, m_address;
};

class NetworkDriver {
 public:
  // Where the rings live: `tx_count` send descriptors at `tx_base`
  // (16-byte aligned), `rx_count` slots of `rx_slot_bytes` at `rx_base`.
  struct Rings {
    uint32_t tx_base = 0;
    unsigned tx_count = 0;
    uint32_t rx_base = 0;
    unsigned rx_count = 0;
    unsigned rx_slot_bytes = 0;
  };
  static constexpr unsigned DESCRIPTOR_BYTES = 16;
  static constexpr unsigned HEADER_BYTES = 16;  // a slot's header before the payload

  // A message in the slot at the ring's tail.
  struct Message {
    unsigned source = 0;
    uint32_t bytes = 0;
    uint32_t tag = 0;
    uint32_t sequence = 0;
    uint32_t payload = 0;  // its payload's address in the slot
  };

  // Reads the node's number and the number of nodes.
  explicit NetworkDriver(HostApi& host);

  unsigned id() const { return m_id; }
  unsigned nodes() const { return m_nodes; }
  // The rings' bytes in memory.
  static uint32_t tx_ring_bytes(unsigned count) { return count * DESCRIPTOR_BYTES; }
  static uint32_t rx_ring_bytes(unsigned count, unsigned slot_bytes) { return count * slot_bytes; }

  // Programs the rings and enables the interface, its interrupt on
  // arrivals, send completions and errors.
  void start(const Rings& rings);

  // Submits a message of `bytes` at `payload` to node `destination`, after
  // waiting for a free descriptor if the ring is full; returns its ticket:
  // the message's payload may be reused once completed() has passed it.
  uint32_t send(unsigned destination, uint32_t payload, uint32_t bytes, uint32_t tag);
  // Messages whose payload the interface has read: tickets below this.
  uint32_t completed();
  // Waits until completed() passes `ticket`.
  void wait_sent(uint32_t ticket);

  // The message at the receive ring's tail, if one has arrived.
  bool peek(Message& message);
  // Frees the slot at the tail (the message peek() returned).
  void release();
  // Sleeps until an interrupt of the interface: a message, a completed
  // send or an error (then NetworkError). The caller checks what it waits
  // for before calling, so no event is missed: the status bit of one that
  // came in between keeps the line high.
  void wait();

  // Tickets handed out so far.
  uint32_t submitted() const { return m_submitted; }

 private:
  uint32_t reg(uint32_t offset);
  void set_reg(uint32_t offset, uint32_t value);
  void check_error(uint32_t status);

  HostApi& m_host;
  unsigned m_id = 0, m_nodes = 0;
  Rings m_rings;
  uint32_t m_submitted = 0;  // descriptors written
  uint32_t m_completed = 0;  // descriptors the interface has taken
  unsigned m_tx_head = 0;    // the interface's TX_HEAD as last read
  unsigned m_rx_tail = 0;
  unsigned m_rx_head = 0;  // the interface's RX_HEAD as last read
};

}  // namespace tessera
