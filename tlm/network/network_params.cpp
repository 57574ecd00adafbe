// The cluster network's parameters: network.* (README.md, "Parameters",
// gives the reasoning behind each default; all are estimates).
#include <string>

#include "network/network.h"

namespace tessera {

ParamGroup NetworkParams::parameters() {
  using param::integer;
  using param::real;
  return {"network",
          {
              param::choice("network.topology", "hypercube", {"hypercube", "mesh", "ring", "crossbar"},
                            "how the nodes are joined (hypercube: cluster.nodes a power of two)"),
              real("network.hop_latency_ns", 20.0, 0, 1e6, "ns", "latency of one link crossed: switch and wire"),
              real("network.link_mb_per_s", 200.0, 0.001, 1e6, "MB/s", "bandwidth of one directed link"),
              real("network.message_latency_ns", 100.0, 0, 1e6, "ns",
                   "router set-up once per message, before its head leaves the source"),
              integer("network.header_bytes", 8, 0, 1024, "bytes", "header on the wire before each payload"),
              real("network.energy_per_byte_pj", 10.0, 0, 1e6, "pJ", "energy per byte per link crossed (an estimate)"),
              real("network.static_mw_per_link", 0.5, 0, 1e4, "mW", "static power of one directed link (an estimate)"),
          },
          [](const Config& config) {
            if (!config.has("cluster.nodes") || config.get_string("network.topology") != "hypercube") return;
            const uint64_t nodes = config.get_uint("cluster.nodes");
            if (nodes == 0 || (nodes & (nodes - 1)) != 0)
              throw ConfigError(
                  "configuration: impossible combination: network.topology=hypercube needs "
                  "cluster.nodes to be a power of two, got cluster.nodes=" +
                  std::to_string(nodes));
          }};
}

NetworkParams NetworkParams::from_config(const Config& config) {
  NetworkParams p;
  p.topology = config.get_string("network.topology");
  p.hop_latency_ns = config.get_real("network.hop_latency_ns");
  p.link_mb_per_s = config.get_real("network.link_mb_per_s");
  p.message_latency_ns = config.get_real("network.message_latency_ns");
  p.header_bytes = static_cast<unsigned>(config.get_uint("network.header_bytes"));
  p.energy_per_byte_pj = config.get_real("network.energy_per_byte_pj");
  p.static_mw_per_link = config.get_real("network.static_mw_per_link");
  return p;
}

NetworkParams NetworkParams::defaults() {
  return from_config(Config({parameters()}));
}

network::NetworkConfig NetworkParams::core_config() const {
  network::NetworkConfig c;
  c.topology = network::parse_topology(topology);
  c.nodes = nodes;
  c.hop_latency_ns = hop_latency_ns;
  c.link_mb_per_s = link_mb_per_s;
  c.message_latency_ns = message_latency_ns;
  c.header_bytes = header_bytes;
  return c;
}

}  // namespace tessera
