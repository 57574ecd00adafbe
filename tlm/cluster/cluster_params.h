// The cluster platform's own parameters (cluster.*): how many nodes, how
// much memory each has, and the job every node runs (the scene and the
// sort-middle renderer's buffer depth). The nodes' host, bus and memory
// timing are the SoC's groups (host.*, bus.*, mem.* but mem.size_mib), the
// network's are network.* (tlm/network).
#pragma once

#include <cstdint>
#include <string>

#include "config/config.h"

namespace tessera {

struct ClusterParams {
  unsigned nodes = 0;
  uint64_t node_memory_bytes = 0;
  // cluster.buffer_depth: trapezoids per message; 0 for "auto" (the paper's
  // Eq. 11 from the previous frame's counts).
  unsigned buffer_depth = 0;
  std::string scene;
  unsigned triangles = 0;
  unsigned triangle_pixels = 0;
  unsigned seed = 0;
  unsigned width = 0;
  unsigned height = 0;

  static ParamGroup parameters();
  static ClusterParams from_config(const Config& config);
  static ClusterParams defaults();
};

// "auto" -> 0, a whole number >= 1 -> itself; anything else is a
// ConfigError naming cluster.buffer_depth.
unsigned parse_buffer_depth(const std::string& text);

}  // namespace tessera
