// The cluster platform (README.md): p nodes (cluster_node.h) joined by one
// network (tlm/network), every node running the same program. What the
// platform itself does beyond the assembly: it gathers the nodes' stripes
// into one frame when the program reports a frame complete (the host link's
// FRAME_DONE), and it ends the simulation when every node's program has
// returned.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <systemc>

#include "cluster/cluster_node.h"
#include "cluster/cluster_params.h"
#include "config/config.h"
#include "display/display_controller.h"
#include "network/network.h"

namespace tessera {

class Cluster : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Cluster);

  // The configuration must hold parameter_groups(); it is validated here.
  Cluster(sc_core::sc_module_name name, const Config& config);
  ~Cluster() override;

  // The platform's parameters beyond the SoC's (which give the nodes' host,
  // bus and memory timing and the simulation's quantum): cluster.* and the
  // network's.
  static std::vector<ParamGroup> parameter_groups();

  const ClusterParams& params() const { return m_params; }
  Network& network() { return *m_network; }
  const Network& network() const { return *m_network; }
  ClusterNode& node(unsigned i) { return *m_nodes.at(i); }
  const ClusterNode& node(unsigned i) const { return *m_nodes.at(i); }
  unsigned nodes() const { return static_cast<unsigned>(m_nodes.size()); }

  // Every node runs `program(node)`'s program.
  void set_programs(const std::function<Host::Program(unsigned node)>& program);

  // A frame gathered from the stripes, at the time the program reported it.
  void on_frame(std::function<void(const Frame&)> handler) { m_on_frame = std::move(handler); }
  const std::vector<double>& frame_times() const { return m_frame_times; }

  bool done() const { return m_done; }
  // The first non-zero exit status of a node's program (0 if none).
  int exit_code() const;

 private:
  void gather(unsigned frame, const sc_core::sc_time& when);
  void finish();  // SC_THREAD

  ClusterParams m_params;
  std::unique_ptr<Network> m_network;
  std::vector<std::unique_ptr<ClusterNode>> m_nodes;
  std::function<void(const Frame&)> m_on_frame;
  std::vector<double> m_frame_times;
  unsigned m_finished = 0;
  sc_core::sc_event m_all_finished;
  bool m_done = false;
};

}  // namespace tessera
