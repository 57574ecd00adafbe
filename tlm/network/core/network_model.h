// The cluster network's functional and timing model (README.md, "The
// network model"): given a message's source, destination, size and inject
// time, when it arrives, with contention on every directed link through
// per-link timelines of reservations, deterministic routes, and in-order
// delivery per (source, destination) pair. Time is integer picoseconds.
// Plain C++, no SystemC: the SystemC wrapper (network/network.h) calls
// send() at the NI's local time and delivers at the arrival.
#pragma once

#include <cstdint>
#include <vector>

#include "network/core/link_timeline.h"
#include "network/core/topology.h"

namespace tessera::network {

struct NetworkConfig {
  Topology topology = Topology::hypercube;
  unsigned nodes = 0;             // cluster.nodes
  double hop_latency_ns = 0;      // network.hop_latency_ns: per link crossed
  double link_mb_per_s = 0;       // network.link_mb_per_s: 10^6 bytes per second
  double message_latency_ns = 0;  // network.message_latency_ns: router set-up, once per message
  unsigned header_bytes = 0;      // network.header_bytes: on the wire before the payload
};

// When a message went and came, in picoseconds.
struct Delivery {
  uint64_t inject_ps = 0;   // handed to the network
  uint64_t start_ps = 0;    // its head left the source (inject + set-up + queueing)
  uint64_t arrival_ps = 0;  // its last byte arrived at the destination
  uint64_t queue_ps = 0;    // waiting for links: start - (inject + set-up)
  unsigned hops = 0;
};

struct NodeTraffic {
  uint64_t messages_sent = 0, bytes_sent = 0;
  uint64_t messages_received = 0, bytes_received = 0;
};

class NetworkModel {
 public:
  // Throws ConfigError naming the key of a bad parameter (README.md, "Bad
  // configuration").
  explicit NetworkModel(const NetworkConfig& config);

  // A message of `payload_bytes` from src to dst handed to the network at
  // `inject_ps`. Nodes out of range: std::out_of_range. src == dst costs
  // nothing (arrival = inject).
  Delivery send(unsigned src, unsigned dst, uint32_t payload_bytes, uint64_t inject_ps);
  // Drops the link reservations that ended by `now_ps`; send() must not be
  // called with an earlier inject time afterwards.
  void prune(uint64_t now_ps);

  const NetworkConfig& config() const { return m_config; }
  const Routing& routing() const { return m_routing; }
  uint64_t hop_latency_ps() const { return m_hop_ps; }
  uint64_t message_latency_ps() const { return m_message_ps; }
  // Time a link needs for `bytes` (rounded up to a picosecond).
  uint64_t transfer_ps(uint64_t bytes) const;

  // Statistics since construction.
  uint64_t messages() const { return m_messages; }  // self messages included
  uint64_t self_messages() const { return m_self_messages; }
  uint64_t payload_bytes() const { return m_payload_bytes; }
  uint64_t wire_bytes() const { return m_wire_bytes; }  // payload and header, once per message
  uint64_t link_bytes() const { return m_link_bytes; }  // wire bytes times hops: what the links carried
  uint64_t total_queue_ps() const { return m_total_queue_ps; }
  uint64_t max_queue_ps() const { return m_max_queue_ps; }
  uint64_t total_hops() const { return m_total_hops; }
  // The last arrival of any message (0 if none).
  uint64_t last_arrival_ps() const { return m_last_arrival_ps; }
  uint64_t link_busy_ps(unsigned link) const { return m_links.at(link).busy_ps(); }
  // Busy time over `elapsed_ps`, averaged over the links that exist, and
  // the busiest link's.
  double mean_link_utilisation(uint64_t elapsed_ps) const;
  double max_link_utilisation(uint64_t elapsed_ps) const;
  const NodeTraffic& node(unsigned n) const { return m_nodes.at(n); }

 private:
  struct Pair {
    uint64_t last_start = 0;
    uint64_t last_arrival = 0;
  };

  NetworkConfig m_config;
  Routing m_routing;
  uint64_t m_hop_ps;
  uint64_t m_message_ps;
  std::vector<LinkTimeline> m_links;
  std::vector<Pair> m_pairs;  // [src * nodes + dst]
  std::vector<NodeTraffic> m_nodes;
  std::vector<unsigned> m_route;  // scratch
  uint64_t m_messages = 0, m_self_messages = 0;
  uint64_t m_payload_bytes = 0, m_wire_bytes = 0, m_link_bytes = 0;
  uint64_t m_total_queue_ps = 0, m_max_queue_ps = 0, m_total_hops = 0;
  uint64_t m_last_arrival_ps = 0;
};

}  // namespace tessera::network
