// One node of the cluster platform: an ARM922T host (either host model)
// with its own bus, memory and network interface, bound by the node's
// memory map (contract/cluster/node_memory_map.def), and its host link.
// The platform (cluster.h) builds p of them around one network.
#pragma once

#include <memory>
#include <vector>

#include <systemc>

#include "bus/ahb_bus.h"
#include "cluster/host_link.h"
#include "config/config.h"
#include "host/host.h"
#include "intc/interrupt_controller.h"
#include "mem/memory.h"
#include "network/network.h"
#include "network/network_interface.h"

namespace tessera {

class ClusterNode : public sc_core::sc_module {
 public:
  // Node `id` of the platform, joined to `network`.
  ClusterNode(sc_core::sc_module_name name, const Config& config, unsigned id, Network& network);
  ~ClusterNode() override;

  unsigned id() const { return m_id; }

  AhbBus bus;
  Memory memory;
  Host host;
  NetworkInterface ni;
  HostLink host_link;
  // Built only with host.model=iss, as on the SoC: the ISS's software waits
  // for the network interface's line through it.
  std::unique_ptr<InterruptController> intc;

  // The node's blocks, in the order of the statistics.
  const std::vector<Block*>& blocks() const { return m_blocks; }

 private:
  unsigned m_id;
  std::vector<Block*> m_blocks;
  std::vector<std::unique_ptr<sc_core::sc_signal<bool>>> m_irq_lines;
  sc_core::sc_signal<bool> m_host_link_irq{"host_link_irq", false};
  std::unique_ptr<sc_core::sc_signal<bool>> m_core_irq, m_core_fiq;
};

}  // namespace tessera
