#include "cluster_run.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "common/activity_json.h"
#include "common/log.h"
#include "common/text_format.h"
#include "power/energy_model.h"
#include "soc/software_layout.h"

namespace tessera {

namespace {

// A node's energy from the SoC's energy model (the host, its bus and its
// memory are the SoC's blocks); units the model does not know (the network
// interface's) are left to the network's own estimate.
nlohmann::json node_energy(const EnergyModel& model, const ClusterNode& node, const sc_core::sc_time& elapsed) {
  EnergyActivity activity;
  for (const Block* block : node.blocks())
    for (UnitActivity& unit : block->energy_activity(elapsed)) {
      const bool known = std::any_of(model.units().begin(), model.units().end(),
                                     [&](const UnitEnergyParams& u) { return u.unit == unit.unit; });
      if (known) activity.push_back(std::move(unit));
    }
  nlohmann::json units = nlohmann::json::object();
  double total = 0;
  for (const UnitEnergy& unit : model.unit_energies(activity, elapsed.to_seconds())) {
    units[unit.unit] = {{"static_j", unit.static_joules}, {"dynamic_j", unit.dynamic_joules()}};
    total += unit.total_joules();
  }
  return {{"units", units}, {"total_j", total}};
}

}  // namespace

ClusterRun::ClusterRun(const Config& config, std::function<void(const Frame&)> on_frame)
    : m_config(config), m_cluster(std::make_unique<Cluster>("cluster", config)) {
  m_cluster->on_frame(std::move(on_frame));
}

ClusterRun::~ClusterRun() {
  close_trace();
}

void ClusterRun::start(const LaunchableApp& app, unsigned frames, bool iss_profile) {
  const unsigned nodes = m_cluster->nodes();
  m_envs.resize(nodes);
  m_counters.resize(nodes);
  m_node_frames.resize(nodes);
  for (unsigned i = 0; i < nodes; ++i) {
    AppEnvironment& env = m_envs[i];
    ClusterNode& node = m_cluster->node(i);
    node.host.set_profiling_program(iss_profile);
    env.frames = frames;
    env.memory_bytes = static_cast<uint32_t>(node.memory.size());
    env.heap_base = software_layout::HEAP_BASE;
    env.heap_end = env.memory_bytes;
    // No frame buffers: the stripes are gathered by the platform.
    env.frame_buffers[0] = env.frame_buffers[1] = env.memory_bytes;
    env.config = &m_config;
    env.counters = &m_counters[i];
    const std::string source = "node" + std::to_string(i);
    env.warn = [source](const std::string& from, const std::string& message) {
      log::warning(source + "." + from, message);
    };
    env.frame_statistics = [this, i](const std::vector<std::pair<std::string, double>>& figures) {
      nlohmann::json record = nlohmann::json::object();
      for (const auto& [name, value] : figures) record[name] = value;
      m_node_frames[i].push_back(std::move(record));
    };
  }
  m_cluster->set_programs([this, app](unsigned i) -> Host::Program {
    return [this, app, i](HostApi& host) {
      m_envs[i].host = &host;
      return app.main(m_envs[i], IssHost{m_cluster->node(i).host, nullptr});
    };
  });
}

void ClusterRun::trace_to(const std::string& systemc_base) {
  m_trace = sc_core::sc_create_vcd_trace_file(systemc_base.c_str());
  if (!m_trace) throw std::runtime_error("cannot create VCD file " + systemc_base + ".vcd");
  m_trace->set_time_unit(1, sc_core::SC_PS);
  m_cluster->network().trace_signals(m_trace);
  for (unsigned i = 0; i < m_cluster->nodes(); ++i)
    for (Block* block : m_cluster->node(i).blocks()) block->trace_signals(m_trace);
}

void ClusterRun::timeline_to(TimelineSink& sink) {
  m_cluster->network().timeline_to(sink);
  for (unsigned i = 0; i < m_cluster->nodes(); ++i)
    for (Block* block : m_cluster->node(i).blocks()) block->timeline_to(sink);
}

void ClusterRun::finish_timeline() {
  m_cluster->network().finish_timeline();
  for (unsigned i = 0; i < m_cluster->nodes(); ++i)
    for (Block* block : m_cluster->node(i).blocks()) block->finish_timeline();
}

void ClusterRun::close_trace() {
  if (!m_trace) return;
  sc_core::sc_close_vcd_trace_file(m_trace);
  m_trace = nullptr;
}

std::string ClusterRun::failure() const {
  for (unsigned i = 0; i < m_cluster->nodes(); ++i) {
    const Host& host = m_cluster->node(i).host;
    if (host.exit_code() != 0) return "node " + std::to_string(i) + ": " + host.failure();
  }
  return "";
}

// A gathered frame's record: its time and the energy since the previous
// frame, the nodes' and the network's (an estimate, as in the totals).
nlohmann::json ClusterRun::frame_record(const Frame& frame) {
  const sc_core::sc_time when(frame.time_seconds, sc_core::SC_SEC);
  const EnergyModel model = EnergyModel::from_config(m_config);
  double joules = 0;
  for (unsigned i = 0; i < m_cluster->nodes(); ++i)
    joules += node_energy(model, m_cluster->node(i), when)["total_j"].get<double>();
  const double nodes_joules = joules - m_energy_before;
  m_energy_before = joules;
  const double network = m_cluster->network().energy_estimate(when).total_j();
  const double network_joules = network - m_network_energy_before;
  m_network_energy_before = network;
  const double render = frame.time_seconds - m_previous_frame_seconds;
  m_previous_frame_seconds = frame.time_seconds;
  return {{"index", frame.index},
          {"time_ns", frame.time_seconds * 1e9},
          {"render_ns", render * 1e9},
          {"energy",
           {{"total_j", nodes_joules + network_joules},
            {"units", {{"nodes", {{"total_j", nodes_joules}}}, {"network", {{"total_j", network_joules}}}}}}}};
}

nlohmann::json ClusterRun::stats_json() const {
  const sc_core::sc_time elapsed = sc_core::sc_time_stamp();
  const EnergyModel energy = EnergyModel::from_config(m_config);
  nlohmann::json stats = {{"simulated_ns", elapsed.to_seconds() * 1e9}, {"platform", "cluster"}};
  const ClusterParams& p = m_cluster->params();
  stats["cluster"] = {{"nodes", p.nodes},
                      {"node_memory_bytes", p.node_memory_bytes},
                      {"scene", p.scene},
                      {"width", p.width},
                      {"height", p.height}};
  stats["network"] = m_cluster->network().stats_json(elapsed);
  nlohmann::json nodes = nlohmann::json::array();
  double nodes_energy = 0;
  unsigned busiest = 0, idlest = 0;
  double most = -1, least = 1e300;
  for (unsigned i = 0; i < m_cluster->nodes(); ++i) {
    const ClusterNode& node = m_cluster->node(i);
    nlohmann::json n = {{"node", i}};
    for (const Block* block : node.blocks()) n[block->basename()] = block->stats_json(elapsed);
    n["energy"] = node_energy(energy, node, elapsed);
    n["driver"] = to_json(m_counters[i]);
    n["frames"] = m_node_frames[i];
    nodes_energy += n["energy"]["total_j"].get<double>();
    const double busy = node.host.busy_time().to_seconds();
    if (busy > most) most = busy, busiest = i;
    if (busy < least) least = busy, idlest = i;
    nodes.push_back(std::move(n));
  }
  stats["nodes"] = std::move(nodes);
  const nlohmann::json& estimate = stats["network"]["energy_estimate"];
  const double network_energy = (estimate["dynamic_nj"].get<double>() + estimate["static_nj"].get<double>()) * 1e-9;
  stats["energy"] = {
      {"nodes_j", nodes_energy}, {"network_j", network_energy}, {"total_j", nodes_energy + network_energy}};
  stats["summary"] = {{"busiest_node", busiest}, {"idlest_node", idlest}};
  return stats;
}

void ClusterRun::print_summary(const nlohmann::json& stats, double wall_seconds,
                               const std::vector<std::string>& outputs) const {
  const sc_core::sc_time elapsed = sc_core::sc_time_stamp();
  const ClusterParams& p = m_cluster->params();
  std::printf("cluster: %u nodes (%s network), %s %ux%u, %u triangles\n", p.nodes,
              m_config.get_string("network.topology").c_str(), p.scene.c_str(), p.width, p.height, p.triangles);
  std::printf("simulated %s in %.2f s of wall time\n", format_duration(elapsed.to_seconds()).c_str(), wall_seconds);
  const std::vector<double>& times = m_cluster->frame_times();
  for (size_t f = 0; f < times.size(); ++f)
    std::printf("frame %zu: complete at %s (%s)\n", f, format_duration(times[f]).c_str(),
                format_duration(times[f] - (f ? times[f - 1] : 0.0)).c_str());
  const auto row = [&](const char* what, unsigned i) {
    const Host& host = m_cluster->node(i).host;
    std::printf("%s node %u: busy %s, stalled %s, waiting %s\n", what, i,
                format_percent(host.busy_time() / elapsed).c_str(), format_percent(host.stall_time() / elapsed).c_str(),
                format_percent(host.idle_time() / elapsed).c_str());
  };
  row("busiest", stats["summary"]["busiest_node"].get<unsigned>());
  row("idlest ", stats["summary"]["idlest_node"].get<unsigned>());
  std::printf("network: %s\n", m_cluster->network().summary_row(elapsed).notes.c_str());
  std::printf("energy: %s (nodes %s, network %s, estimate)\n",
              format_energy(stats["energy"]["total_j"].get<double>()).c_str(),
              format_energy(stats["energy"]["nodes_j"].get<double>()).c_str(),
              format_energy(stats["energy"]["network_j"].get<double>()).c_str());
  for (const std::string& output : outputs) std::printf("%s\n", output.c_str());
}

}  // namespace tessera
