// soc_sim --platform cluster: the cluster platform (tlm/cluster) built from
// the run's configuration, every node running the run's program (the
// built-in cluster_node, on the host model host.model names) with an
// environment of its own, and what is reported of it: the gathered frames,
// stats.json's sections (the platform, the network, every node's blocks,
// the nodes' figures per frame) and the summary. RunSession owns the run
// (outputs, watch, judgement) and asks this for what differs from the SoC.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <systemc>

#include "cluster/cluster.h"
#include "common/activity_counters.h"
#include "device/app_environment.h"
#include "launch/app_loading.h"

namespace tessera {

class ClusterRun {
 public:
  // Builds the platform; `on_frame` gets each gathered frame.
  ClusterRun(const Config& config, std::function<void(const Frame&)> on_frame);
  ~ClusterRun();

  // Every node runs `app` (natively, or its ARM build on the ISS, profiled
  // per function with `iss_profile`).
  void start(const LaunchableApp& app, unsigned frames, bool iss_profile);
  void trace_to(const std::string& systemc_base);
  void close_trace();
  // Every node's blocks on `sink` (common/timeline.h), each node's under
  // its own names; finish_timeline at the end of the run.
  void timeline_to(TimelineSink& sink);
  void finish_timeline();

  bool done() const { return m_cluster->done(); }
  int exit_code() const { return m_cluster->exit_code(); }
  // The first failing node's failure, naming the node.
  std::string failure() const;

  // stats.json's platform sections; the per-frame records of the gathered
  // frames are `frame_record(i)`'s.
  nlohmann::json stats_json() const;
  nlohmann::json frame_record(const Frame& frame);
  void print_summary(const nlohmann::json& stats, double wall_seconds, const std::vector<std::string>& outputs) const;

  Cluster& cluster() { return *m_cluster; }

 private:
  const Config& m_config;
  std::unique_ptr<Cluster> m_cluster;
  std::vector<AppEnvironment> m_envs;
  std::vector<ActivityCounters> m_counters;
  // Each node's figures, frame by frame (AppEnvironment::frame_statistics).
  std::vector<std::vector<nlohmann::json>> m_node_frames;
  sc_core::sc_trace_file* m_trace = nullptr;
  double m_previous_frame_seconds = 0;
  double m_energy_before = 0;          // the nodes' energy at the last frame, J
  double m_network_energy_before = 0;  // the network's estimate at the last frame, J
};

}  // namespace tessera
