#include "network/network.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/log.h"

namespace tessera {

using sc_core::sc_time;

uint64_t Network::to_ps(const sc_time& t) {
  return static_cast<uint64_t>(std::llround(t.to_seconds() * 1e12));
}

sc_time Network::from_ps(uint64_t ps) {
  return sc_time(static_cast<double>(ps), sc_core::SC_PS);
}

Network::Network(sc_core::sc_module_name name, const NetworkParams& params)
    : Block(name),
      m_params(params),
      m_model(params.core_config()),
      m_endpoints(params.nodes, nullptr),
      m_in_flight_signal("in_flight"),
      m_messages(counter("messages", "messages handed to the network, self messages included")),
      m_link_bytes(counter("link_bytes", "bytes carried by links, header included, once per link crossed")),
      m_undeliverable(counter("undeliverable", "messages to a node without an attached endpoint, dropped")) {
  SC_METHOD(deliver_due);
  sensitive << m_next_arrival;
  dont_initialize();
}

void Network::attach(unsigned node, NetworkEndpoint& endpoint) {
  if (node >= m_endpoints.size())
    throw std::out_of_range(std::string(name()) + ": attach of node " + std::to_string(node) + " to a network of " +
                            std::to_string(m_endpoints.size()) + " nodes");
  if (m_endpoints[node])
    throw std::logic_error(std::string(name()) + ": node " + std::to_string(node) + " attached twice");
  m_endpoints[node] = &endpoint;
}

network::Delivery Network::send(NetworkMessage message, const sc_time& offset) {
  const sc_time now = sc_core::sc_time_stamp();
  if (--m_prune_countdown == 0) {
    m_model.prune(to_ps(now));
    m_prune_countdown = PRUNE_EVERY;
  }
  const uint64_t link_bytes_before = m_model.link_bytes();
  const network::Delivery d = m_model.send(message.source, message.destination,
                                           static_cast<uint32_t>(message.payload.size()), to_ps(now + offset));
  ++m_messages;
  m_link_bytes += m_model.link_bytes() - link_bytes_before;
  if (log::enabled(log::Level::debug))
    log::debug(name(), "message " + std::to_string(message.source) + " -> " + std::to_string(message.destination) +
                           ", " + std::to_string(message.payload.size()) + " bytes, tag " + log::hex(message.tag) +
                           ": " + std::to_string(d.hops) + " hops, arrives at " + from_ps(d.arrival_ps).to_string());
  m_pending.push_back({d.arrival_ps, m_sent++, std::move(message)});
  std::push_heap(m_pending.begin(), m_pending.end(), Later{});
  // An event keeps its earliest notification: a later one is ignored.
  m_next_arrival.notify(from_ps(d.arrival_ps) - now);
  if (m_tracing) m_in_flight_signal.write(in_flight());
  return d;
}

void Network::deliver_due() {
  const uint64_t now = to_ps(sc_core::sc_time_stamp());
  while (!m_pending.empty() && m_pending.front().arrival_ps <= now) {
    std::pop_heap(m_pending.begin(), m_pending.end(), Later{});
    NetworkMessage message = std::move(m_pending.back().message);
    m_pending.pop_back();
    NetworkEndpoint* endpoint = m_endpoints[message.destination];
    if (!endpoint) {
      ++m_undeliverable;
      log::warning(name(), "message from node " + std::to_string(message.source) + " to node " +
                               std::to_string(message.destination) + ", which has no network interface, dropped");
      continue;
    }
    endpoint->deliver(std::move(message));
  }
  schedule_next();
  if (m_tracing) m_in_flight_signal.write(in_flight());
}

void Network::schedule_next() {
  if (m_pending.empty()) return;
  const sc_time now = sc_core::sc_time_stamp();
  const sc_time next = from_ps(m_pending.front().arrival_ps);
  m_next_arrival.notify(next > now ? next - now : sc_core::SC_ZERO_TIME);
}

void Network::trace_signals(sc_core::sc_trace_file* file) {
  m_tracing = true;
  sc_core::sc_trace(file, m_in_flight_signal, std::string(name()) + ".in_flight");
}

nlohmann::json Network::stats_json(const sc_time& elapsed) const {
  nlohmann::json stats = Block::stats_json(elapsed);
  const network::Routing& routing = m_model.routing();
  // Utilisation over the run, or up to the last arrival if that is later.
  const uint64_t span = std::max(to_ps(elapsed), m_model.last_arrival_ps());
  const uint64_t routed = m_model.messages() - m_model.self_messages();
  stats["topology"] = network::topology_name(routing.topology());
  stats["nodes"] = routing.nodes();
  stats["links"] = routing.existing_links();
  if (routing.topology() == network::Topology::mesh) {
    stats["mesh_columns"] = routing.mesh_columns();
    stats["mesh_rows"] = routing.mesh_rows();
  }
  stats["hop_latency_ns"] = m_params.hop_latency_ns;
  stats["link_mb_per_s"] = m_params.link_mb_per_s;
  stats["message_latency_ns"] = m_params.message_latency_ns;
  stats["header_bytes"] = m_params.header_bytes;
  stats["self_messages"] = m_model.self_messages();
  stats["payload_bytes"] = m_model.payload_bytes();
  stats["wire_bytes"] = m_model.wire_bytes();
  stats["mean_hops"] = routed ? static_cast<double>(m_model.total_hops()) / static_cast<double>(routed) : 0.0;
  stats["total_queue_ns"] = static_cast<double>(m_model.total_queue_ps()) / 1e3;
  stats["max_queue_ns"] = static_cast<double>(m_model.max_queue_ps()) / 1e3;
  stats["mean_queue_ns"] =
      routed ? static_cast<double>(m_model.total_queue_ps()) / 1e3 / static_cast<double>(routed) : 0.0;
  stats["mean_link_utilisation"] = m_model.mean_link_utilisation(span);
  stats["max_link_utilisation"] = m_model.max_link_utilisation(span);
  nlohmann::json links = nlohmann::json::object();
  for (unsigned l = 0; l < routing.link_count(); ++l)
    if (routing.link_exists(l) && m_model.link_busy_ps(l) > 0)
      links[routing.link_name(l)] = static_cast<double>(m_model.link_busy_ps(l)) / 1e3;
  stats["link_busy_ns"] = links;
  nlohmann::json nodes = nlohmann::json::array();
  for (unsigned n = 0; n < routing.nodes(); ++n) {
    const network::NodeTraffic& t = m_model.node(n);
    nodes.push_back({{"messages_sent", t.messages_sent},
                     {"bytes_sent", t.bytes_sent},
                     {"messages_received", t.messages_received},
                     {"bytes_received", t.bytes_received}});
  }
  stats["per_node"] = nodes;
  const EnergyEstimate energy = energy_estimate(elapsed);
  stats["energy_estimate"] = {{"dynamic_nj", energy.dynamic_pj / 1e3}, {"static_nj", energy.static_pj / 1e3}};
  stats["elapsed_ns"] = elapsed.to_seconds() * 1e9;
  return stats;
}

SummaryRow Network::summary_row(const sc_time& elapsed) const {
  const uint64_t span = std::max(to_ps(elapsed), m_model.last_arrival_ps());
  return {std::nullopt, std::nullopt,
          std::to_string(m_model.messages()) + " messages, " + std::to_string(m_model.payload_bytes()) +
              " bytes, max queueing " + format_duration(static_cast<double>(m_model.max_queue_ps()) * 1e-12) +
              ", busiest link " + format_percent(m_model.max_link_utilisation(span))};
}

Network::EnergyEstimate Network::energy_estimate(const sc_time& elapsed) const {
  const network::Routing& routing = m_model.routing();
  return {static_cast<double>(m_model.link_bytes()) * m_params.energy_per_byte_pj,
          routing.existing_links() * m_params.static_mw_per_link * 1e-3 * elapsed.to_seconds() * 1e12};
}

EnergyActivity Network::energy_activity(const sc_time& now) const {
  (void)now;
  return {{"network",
           {{"link_bytes", static_cast<double>(m_model.link_bytes())},
            {"messages", static_cast<double>(m_model.messages() - m_model.self_messages())}}}};
}

}  // namespace tessera
