#include "network/core/network_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "config/config.h"

namespace tessera::network {

namespace {

// A latency in ns as whole picoseconds; a negative or non-finite one is a
// ConfigError naming its key.
uint64_t latency_ps(double ns, const char* key) {
  if (!std::isfinite(ns) || ns < 0)
    throw ConfigError(std::string("configuration: '") + key + "' expects a latency of 0 ns or more, got " +
                      std::to_string(ns));
  return static_cast<uint64_t>(std::llround(ns * 1000.0));
}

}  // namespace

NetworkModel::NetworkModel(const NetworkConfig& config)
    : m_config(config),
      m_routing(config.topology, config.nodes),
      m_hop_ps(latency_ps(config.hop_latency_ns, "network.hop_latency_ns")),
      m_message_ps(latency_ps(config.message_latency_ns, "network.message_latency_ns")) {
  if (!std::isfinite(config.link_mb_per_s) || config.link_mb_per_s <= 0)
    throw ConfigError("configuration: 'network.link_mb_per_s' expects a bandwidth above 0 MB/s, got " +
                      std::to_string(config.link_mb_per_s));
  m_links.resize(m_routing.link_count());
  m_pairs.resize(size_t{config.nodes} * config.nodes);
  m_nodes.resize(config.nodes);
}

uint64_t NetworkModel::transfer_ps(uint64_t bytes) const {
  // bytes / (MB/s x 10^6) seconds = bytes x 10^6 / (MB/s) picoseconds.
  return static_cast<uint64_t>(std::ceil(static_cast<double>(bytes) * 1e6 / m_config.link_mb_per_s));
}

Delivery NetworkModel::send(unsigned src, unsigned dst, uint32_t payload_bytes, uint64_t inject_ps) {
  m_routing.route(src, dst, m_route);  // checks the nodes
  Delivery d;
  d.inject_ps = inject_ps;
  ++m_messages;
  m_payload_bytes += payload_bytes;
  m_nodes[src].messages_sent++;
  m_nodes[src].bytes_sent += payload_bytes;
  m_nodes[dst].messages_received++;
  m_nodes[dst].bytes_received += payload_bytes;
  if (src == dst) {
    ++m_self_messages;
    d.start_ps = d.arrival_ps = inject_ps;
    return d;
  }
  Pair& pair = m_pairs[size_t{src} * m_config.nodes + dst];
  const uint64_t wire = uint64_t{payload_bytes} + m_config.header_bytes;
  const uint64_t length = transfer_ps(wire);
  const uint64_t ready = inject_ps + m_message_ps;
  // The earliest common start at which link k is free over
  // [s + k h, s + k h + length) for every k; never before the previous
  // message of the pair started (it holds link 0 from then), so the pair
  // stays in order.
  uint64_t s = std::max(ready, pair.last_start);
  for (bool moved = true; moved;) {
    moved = false;
    for (size_t k = 0; k < m_route.size(); ++k) {
      const uint64_t at = s + k * m_hop_ps;
      const uint64_t free = m_links[m_route[k]].earliest_free(at, length);
      if (free > at) {
        s = free - k * m_hop_ps;
        moved = true;
        break;
      }
    }
  }
  for (size_t k = 0; k < m_route.size(); ++k) m_links[m_route[k]].reserve(s + k * m_hop_ps, length);
  d.hops = static_cast<unsigned>(m_route.size());
  d.start_ps = s;
  d.queue_ps = s - ready;
  d.arrival_ps = std::max(s + d.hops * m_hop_ps + length, pair.last_arrival);
  pair.last_start = s;
  pair.last_arrival = d.arrival_ps;
  m_wire_bytes += wire;
  m_link_bytes += wire * d.hops;
  m_total_hops += d.hops;
  m_total_queue_ps += d.queue_ps;
  m_max_queue_ps = std::max(m_max_queue_ps, d.queue_ps);
  m_last_arrival_ps = std::max(m_last_arrival_ps, d.arrival_ps);
  return d;
}

void NetworkModel::prune(uint64_t now_ps) {
  for (LinkTimeline& link : m_links) link.prune(now_ps);
}

double NetworkModel::mean_link_utilisation(uint64_t elapsed_ps) const {
  if (elapsed_ps == 0 || m_routing.existing_links() == 0) return 0.0;
  uint64_t busy = 0;
  for (const LinkTimeline& link : m_links) busy += link.busy_ps();
  return static_cast<double>(busy) / static_cast<double>(elapsed_ps) / m_routing.existing_links();
}

double NetworkModel::max_link_utilisation(uint64_t elapsed_ps) const {
  if (elapsed_ps == 0) return 0.0;
  uint64_t busy = 0;
  for (const LinkTimeline& link : m_links) busy = std::max(busy, link.busy_ps());
  return static_cast<double>(busy) / static_cast<double>(elapsed_ps);
}

}  // namespace tessera::network
