// A cluster node's network interface (README.md, "The network interface"):
// a peripheral whose send ring and receive ring live in the node's memory.
// It reads each send descriptor and its payload over its bus master and
// hands the message to the network at its time; it writes each arriving
// message, a 16-byte header and the payload, into the next free receive
// slot, holding arrivals in order while the ring is full. Errors set
// ERROR_CODE and ERROR_ADDR and raise ERROR; those that concern the rings
// stop the NI (CTRL.ENABLE cleared).
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include <systemc>

#include <nlohmann/json.hpp>

#include "common/bus_master.h"
#include "common/peripheral.h"
#include "config/config.h"
#include "network/network_message.h"
#include "network/ni_regs.h"

namespace tessera {

class Network;

struct NetworkInterfaceParams {
  unsigned burst_beats = 0;
  unsigned node = 0;              // set by the platform: this node's number
  unsigned nodes = 0;             // set by the platform: cluster.nodes
  unsigned burst_bytes = 0;       // set by the platform: burst_beats words of the node's bus
  sc_core::sc_time clock_period;  // set by the platform: the node's bus clock (one per register access)
  uint64_t memory_base = 0;       // set by the platform: the node's memory as the NI's bus master sees it
  uint64_t memory_bytes = 0;

  static ParamGroup parameters();
  static NetworkInterfaceParams from_config(const Config& config);
  static NetworkInterfaceParams defaults();
};

class NetworkInterface : public Peripheral, public NetworkEndpoint {
 public:
  SC_HAS_PROCESS(NetworkInterface);

  // Registers on `in`, the interrupt on `irq` (Peripheral).
  BusMaster out;  // into the node's memory: descriptors, payloads, receive slots

#define TESSERA_REGISTER_TABLE "network/ni_regs.def"
#include "common/register_members.inc"

  NetworkInterface(sc_core::sc_module_name name, const NetworkInterfaceParams& params);

  // Attaches this NI to the network as node params.node.
  void connect(Network& network);
  // The network's side: a message arrives (at the kernel's time).
  void deliver(NetworkMessage&& message) override;

  const NetworkInterfaceParams& params() const {
    return m_params;
  }
  // Notified whenever a send or a receive finishes or an error is raised.
  const sc_core::sc_event& progress_event() const {
    return m_progress;
  }
  size_t waiting_arrivals() const {
    return m_arrivals.size();
  }

  void trace_signals(sc_core::sc_trace_file* file) override;
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  const char* write_refusal(const tlm::tlm_generic_payload& gp) const override;
  void write_CTRL(uint32_t value);
  uint32_t read_STATUS() const;
  static void new_ring(Register& head, Register& tail);
  void write_TX_BASE(uint32_t value);
  void write_TX_COUNT(uint32_t value);
  void write_TX_TAIL(uint32_t value);
  void write_RX_BASE(uint32_t value);
  void write_RX_COUNT(uint32_t value);
  void write_RX_SLOT_BYTES(uint32_t value);
  void write_RX_TAIL(uint32_t value);

  void transmit();  // SC_THREAD: the send ring
  void receive();   // SC_THREAD: the receive ring
  void send_one();
  void receive_one();
  bool enabled() const {
    return (CTRL.get() & ni_regs::CTRL_ENABLE) != 0;
  }
  bool rx_slot_free() const;
  // The first bad ring register's value, if any.
  bool rings_valid(uint32_t& offending) const;
  bool in_memory(uint64_t address, uint64_t bytes) const;
  // A bus transfer at the kernel's time; returns when it has completed.
  bool transfer(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes);
  // Sets the error `delay` after the kernel's time: a register write's at
  // the access's time, the rings' at the kernel's (their threads wait for
  // every transfer).
  void fail(ni_regs::Error error, uint32_t address, const sc_core::sc_time& delay = sc_core::SC_ZERO_TIME);

  NetworkInterfaceParams m_params;
  Network* m_network = nullptr;
  std::vector<uint32_t> m_sequence;  // [destination]: the next sequence number
  std::deque<NetworkMessage> m_arrivals;
  // The times of the last software writes that let a ring go on (the
  // host may write ahead of the kernel's time).
  sc_core::sc_time m_tx_ready, m_rx_ready;
  sc_core::sc_event m_tx_wake, m_rx_wake, m_progress;
  bool m_tx_busy = false;
  bool m_rx_stalled = false;
  sc_core::sc_time m_rx_stall_start;
  sc_core::sc_time m_tx_busy_time, m_rx_stall_time;
  ActivityCounter& m_messages_sent;
  ActivityCounter& m_bytes_sent;
  ActivityCounter& m_messages_received;
  ActivityCounter& m_bytes_received;
  ActivityCounter& m_loopback;
  ActivityCounter& m_dropped;
  ActivityCounter& m_errors;
  ActivityCounter& m_rx_stalls;
};

}  // namespace tessera
