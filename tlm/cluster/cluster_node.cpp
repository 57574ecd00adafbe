#include "cluster/cluster_node.h"

#include "cluster/cluster_params.h"
#include "cluster/node_memory_map.h"
#include "soc/platform_params.h"
#include "soc/soc.h"

namespace tessera {

namespace {

MemoryParams node_memory_params(const Config& config) {
  return platform_memory_params(config, ClusterParams::from_config(config).node_memory_bytes);
}

NetworkInterfaceParams network_interface_params(const Config& config, unsigned id) {
  NetworkInterfaceParams p = NetworkInterfaceParams::from_config(config);
  const BusParams bus = BusParams::from_config(config);
  const ClusterParams cluster = ClusterParams::from_config(config);
  p.node = id;
  p.nodes = cluster.nodes;
  p.burst_bytes = p.burst_beats * bus.width_bytes;
  p.clock_period = bus.clock_period;
  p.memory_base = node_memory_map::node_memory.base;
  p.memory_bytes = cluster.node_memory_bytes;
  return p;
}

HostParams node_host_params(const Config& config) {
  return platform_host_params(config, node_memory_map::node_memory.base,
                              ClusterParams::from_config(config).node_memory_bytes);
}

}  // namespace

ClusterNode::ClusterNode(sc_core::sc_module_name name, const Config& config, unsigned id, Network& network)
    : sc_core::sc_module(name),
      bus("bus", BusParams::from_config(config)),
      memory("memory", node_memory_params(config)),
      host("host", node_host_params(config)),
      ni("ni", network_interface_params(config, id)),
      host_link("host_link", BusParams::from_config(config).clock_period),
      m_id(id) {
  ni.connect(network);
  // The network interface serves the network before the host: the host
  // waits for its messages anyway (as the SoC's DMAs come before its host).
  bus.attach(host.out, "host", BusPriority::HOST);
  bus.attach(ni.out, "ni", BusPriority::DMA);

  bus.map(memory.in, node_memory_map::node_memory.base, node_memory_map::node_memory.size,
          node_memory_map::node_memory.name);
  bus.map(ni.in, node_memory_map::ni_regs.base, node_memory_map::ni_regs.size, node_memory_map::ni_regs.name);
  bus.map(host_link.in, node_memory_map::host_link.base, node_memory_map::host_link.size,
          node_memory_map::host_link.name);

  for (unsigned i = 0; i < host.irq.size(); ++i) {
    m_irq_lines.push_back(std::make_unique<sc_core::sc_signal<bool>>(("irq_line_" + std::to_string(i)).c_str(), false));
    host.irq[i].bind(*m_irq_lines.back());
  }
  ni.irq.bind(*m_irq_lines[node_irq::network_interface]);
  host_link.irq.bind(m_host_link_irq);

  m_blocks = {&host, &bus, &memory, &ni, &host_link};
  if (host.params().iss) {
    intc = std::make_unique<InterruptController>("intc", bus.params().clock_period, host.irq.size());
    bus.map(intc->in, node_memory_map::node_intc.base, node_memory_map::node_intc.size,
            node_memory_map::node_intc.name);
    for (unsigned i = 0; i < host.irq.size(); ++i) intc->lines[i].bind(*m_irq_lines[i]);
    m_core_irq = std::make_unique<sc_core::sc_signal<bool>>("core_irq", false);
    m_core_fiq = std::make_unique<sc_core::sc_signal<bool>>("core_fiq", false);
    intc->irq.bind(*m_core_irq);
    intc->fiq.bind(*m_core_fiq);
    host.core_irq.bind(*m_core_irq);
    host.core_fiq.bind(*m_core_fiq);
    m_blocks.push_back(intc.get());
  }
}

ClusterNode::~ClusterNode() = default;

}  // namespace tessera
