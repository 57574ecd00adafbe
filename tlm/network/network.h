// The cluster's network as a SystemC block (README.md, "The SystemC
// wrapper"): the plain C++ NetworkModel (core/) times each message from
// the NI's local time to its arrival; the message waits in one heap for
// the whole network and one method process hands it to the destination's
// endpoint at its arrival time.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <systemc>

#include <nlohmann/json.hpp>

#include "common/block.h"
#include "config/config.h"
#include "network/core/network_model.h"
#include "network/network_message.h"

namespace tessera {

struct NetworkParams {
  std::string topology;
  double hop_latency_ns = 0;
  double link_mb_per_s = 0;
  double message_latency_ns = 0;
  unsigned header_bytes = 0;
  double energy_per_byte_pj = 0;  // an estimate: per byte per link crossed
  double static_mw_per_link = 0;  // an estimate: per directed link
  unsigned nodes = 0;             // set by the platform: cluster.nodes

  static ParamGroup parameters();
  static NetworkParams from_config(const Config& config);
  static NetworkParams defaults();
  // The core's configuration; ConfigError naming a bad key.
  network::NetworkConfig core_config() const;
};

class Network : public Block {
 public:
  SC_HAS_PROCESS(Network);

  // Throws ConfigError naming a bad parameter.
  Network(sc_core::sc_module_name name, const NetworkParams& params);

  // Node `node`'s NI; each node once. A message to a node without one is
  // dropped with a warning (counted: undeliverable).
  void attach(unsigned node, NetworkEndpoint& endpoint);

  // Sends `message` (source and destination in it) at the sender's local
  // time, sc_time_stamp() + `offset`; delivers it to the destination's
  // endpoint at the arrival time. Returns the core's timing. Nodes out of
  // range: std::out_of_range (the NI checks first).
  network::Delivery send(NetworkMessage message, const sc_core::sc_time& offset = sc_core::SC_ZERO_TIME);

  const network::NetworkModel& model() const { return m_model; }
  const NetworkParams& params() const { return m_params; }
  unsigned in_flight() const { return static_cast<unsigned>(m_pending.size()); }

  void trace_signals(sc_core::sc_trace_file* file) override;
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;
  // The network's energy up to `elapsed`, an estimate (network.energy_per_byte_pj per byte per link crossed,
  // network.static_mw_per_link per link): dynamic and static, in pJ.
  struct EnergyEstimate {
    double dynamic_pj = 0, static_pj = 0;
    double total_j() const { return (dynamic_pj + static_pj) * 1e-12; }
  };
  EnergyEstimate energy_estimate(const sc_core::sc_time& elapsed) const;

  static uint64_t to_ps(const sc_core::sc_time& t);
  static sc_core::sc_time from_ps(uint64_t ps);

 private:
  struct Pending {
    uint64_t arrival_ps;
    uint64_t order;  // sending order: ties in arrival keep it
    NetworkMessage message;
  };
  // The heap's order: the earliest arrival on top, ties in sending order.
  struct Later {
    bool operator()(const Pending& a, const Pending& b) const {
      return a.arrival_ps != b.arrival_ps ? a.arrival_ps > b.arrival_ps : a.order > b.order;
    }
  };
  void deliver_due();  // SC_METHOD, sensitive to m_next_arrival
  void schedule_next();

  NetworkParams m_params;
  network::NetworkModel m_model;
  std::vector<NetworkEndpoint*> m_endpoints;
  std::vector<Pending> m_pending;  // a heap (Later)
  uint64_t m_sent = 0;
  uint64_t m_prune_countdown = PRUNE_EVERY;
  static constexpr uint64_t PRUNE_EVERY = 1024;
  sc_core::sc_event m_next_arrival;
  // Written by the senders' threads and the delivery method, possibly in one
  // delta cycle: the last write holds the latest count.
  sc_core::sc_signal<unsigned, sc_core::SC_UNCHECKED_WRITERS> m_in_flight_signal;
  bool m_tracing = false;
  ActivityCounter& m_messages;
  ActivityCounter& m_link_bytes;
  ActivityCounter& m_undeliverable;
};

}  // namespace tessera
