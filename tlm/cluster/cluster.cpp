#include "cluster/cluster.h"

#include <cstring>

#include "cluster/stripe_layout.h"
#include "common/log.h"

namespace tessera {

std::vector<ParamGroup> Cluster::parameter_groups() {
  return {ClusterParams::parameters(), NetworkParams::parameters(), NetworkInterfaceParams::parameters()};
}

Cluster::Cluster(sc_core::sc_module_name name, const Config& config)
    : sc_core::sc_module(name), m_params(ClusterParams::from_config(config)) {
  config.validate();
  tlm_utils::tlm_quantumkeeper::set_global_quantum(
      sc_core::sc_time(static_cast<double>(config.get_uint("sim.quantum_ns")), sc_core::SC_NS));
  NetworkParams network = NetworkParams::from_config(config);
  network.nodes = m_params.nodes;
  m_network = std::make_unique<Network>("network", network);
  m_nodes.reserve(m_params.nodes);
  for (unsigned i = 0; i < m_params.nodes; ++i) {
    m_nodes.push_back(std::make_unique<ClusterNode>(("node" + std::to_string(i)).c_str(), config, i, *m_network));
    m_nodes.back()->host.on_finish([this] {
      if (++m_finished == m_nodes.size()) m_all_finished.notify(sc_core::SC_ZERO_TIME);
    });
  }
  m_nodes.front()->host_link.on_frame_done(
      [this](unsigned frame, const sc_core::sc_time& when) { gather(frame, when); });
  SC_THREAD(finish);
}

Cluster::~Cluster() = default;

void Cluster::set_programs(const std::function<Host::Program(unsigned node)>& program) {
  for (auto& node : m_nodes) node->host.set_program(program(node->id()));
}

int Cluster::exit_code() const {
  for (const auto& node : m_nodes)
    if (node->host.exit_code() != 0) return node->host.exit_code();
  return 0;
}

// Every node has finished the frame when the program reports it (the
// paper's global completion), and none goes on to the next before node 0
// has sent its completion message, after this write: the stripes are read
// as they are, in no simulated time, as a debugger would.
void Cluster::gather(unsigned frame, const sc_core::sc_time& when) {
  Frame out;
  out.index = frame;
  out.time_seconds = out.requested_seconds = when.to_seconds();
  out.width = m_params.width;
  out.height = m_params.height;
  out.rgba.resize(size_t{out.width} * out.height * stripes::BYTES_PER_PIXEL);
  for (auto& node : m_nodes) {
    const unsigned s = node->id();
    const size_t row_bytes = size_t{out.width} * stripes::BYTES_PER_PIXEL;
    const size_t bytes = stripes::colour_bytes(s, out.width, out.height, m_params.nodes);
    const uint64_t address = node->host_link.STRIPE_ADDRESS.get();
    uint8_t* to = out.rgba.data() + stripes::first_row(s, out.height, m_params.nodes) * row_bytes;
    if (address + bytes <= node->memory.size())
      std::memcpy(to, node->memory.data() + address, bytes);
    else
      log::warning(name(), "node " + std::to_string(s) + "'s STRIPE_ADDRESS " +
                               log::hex(static_cast<uint32_t>(address)) +
                               " leaves its memory: its stripe is left black");
  }
  m_frame_times.push_back(out.time_seconds);
  if (m_on_frame) m_on_frame(out);
}

void Cluster::finish() {
  wait(m_all_finished);
  m_done = true;
  sc_core::sc_stop();
}

}  // namespace tessera
