// The cluster platform's parameters: cluster.*.
#include "cluster/cluster_params.h"

#include <cctype>

#include "cluster/stripe_layout.h"
#include "common/screen_size.h"

namespace tessera {

namespace {

constexpr unsigned MAX_NODES = 128;
constexpr unsigned MAX_BUFFER_DEPTH = 65535;

void validate(const Config& config) {
  // With soc_sim's sim.platform, only a cluster run is checked: a SoC run
  // ignores cluster.* (and may set mem.size_mib).
  if (config.has("sim.platform") && config.get_string("sim.platform") != "cluster") return;
  const ClusterParams p = ClusterParams::from_config(config);
  if (p.nodes > p.height)
    throw ConfigError("configuration: impossible combination: cluster.nodes=" + std::to_string(p.nodes) +
                      " nodes need a stripe of at least one row each, and cluster.height=" + std::to_string(p.height) +
                      " has fewer rows");
  if (config.is_set("mem.size_mib"))
    throw ConfigError(
        "configuration: mem.size_mib is the SoC's memory; a cluster node's memory is "
        "cluster.node_memory_kib");
  // The node program's heap starts at 4 MiB (the runtime's layout), on the
  // ISS after the program's own C heap (host.iss_heap_mib), and must hold
  // the highest stripe's colour and depth buffers at least; the rest of its
  // needs are checked by the program, which knows them.
  const unsigned most_rows = (p.height + p.nodes - 1) / p.nodes;
  const uint64_t stripe_bytes = 2ull * most_rows * p.width * stripes::BYTES_PER_PIXEL;
  const bool iss = config.has("host.model") && config.get_string("host.model") == "iss";
  const uint64_t heap_base = (4ull << 20) + (iss ? config.get_uint("host.iss_heap_mib") << 20 : 0);
  if (heap_base + stripe_bytes > p.node_memory_bytes)
    throw ConfigError("configuration: impossible combination: a stripe of " + std::to_string(most_rows) +
                      " rows of cluster.width=" + std::to_string(p.width) + " pixels (colour and depth, " +
                      std::to_string(stripe_bytes) + " bytes) does not fit a node's memory above the program's " +
                      std::to_string(heap_base >> 20) +
                      " MiB: cluster.node_memory_kib=" + std::to_string(p.node_memory_bytes >> 10) + " is too small");
}

}  // namespace

unsigned parse_buffer_depth(const std::string& text) {
  if (text == "auto") return 0;
  bool digits = !text.empty() && text.size() <= 6;
  for (const char c : text) digits = digits && std::isdigit(static_cast<unsigned char>(c));
  const unsigned long value = digits ? std::stoul(text) : 0;
  if (!digits || value < 1 || value > MAX_BUFFER_DEPTH)
    throw ConfigError("cluster.buffer_depth: expected \"auto\" or a whole number of trapezoids from 1 to " +
                      std::to_string(MAX_BUFFER_DEPTH) + ", got \"" + text + "\"");
  return static_cast<unsigned>(value);
}

ParamGroup ClusterParams::parameters() {
  return {
      "cluster",
      {
          param::integer("cluster.nodes", 8, 1, MAX_NODES, "nodes",
                         "processors of the cluster platform (soc_sim --platform cluster), each an ARM922T host "
                         "with its own bus, memory and network interface"),
          param::integer("cluster.node_memory_kib", 16384, 4096, 262144, "KiB",
                         "each node's memory (the SoC's mem.size_mib default: 16 MiB)"),
          param::text("cluster.buffer_depth", "auto",
                      "trapezoids a node collects for one destination before it sends them, d; \"auto\": the "
                      "paper's Eq. 11 from the previous frame's counts (docs/cluster.md)"),
          param::choice("cluster.scene", "random_triangles", {"random_triangles", "teapot"}, "what every frame draws"),
          param::integer("cluster.triangles", 10000, 1, 1000000, "triangles",
                         "random_triangles: triangles in the scene, n"),
          param::integer("cluster.triangle_pixels", 10, 1, 256, "pixels",
                         "random_triangles: each triangle's size (its 3-D triangle spans this many pixels "
                         "before projection, as the paper's 10 x 10 pixel triangles)"),
          param::integer("cluster.seed", 1, 0, 4294967295.0, "", "random_triangles: the scene's seed"),
          param::integer("cluster.width", 512, 1, MAX_SCREEN_SIZE, "pixels", "frame width"),
          param::integer("cluster.height", 512, 1, MAX_SCREEN_SIZE, "pixels",
                         "frame height: node s of p draws rows [floor(s h / p), floor((s + 1) h / p))"),
      },
      validate};
}

ClusterParams ClusterParams::from_config(const Config& config) {
  ClusterParams p;
  p.nodes = static_cast<unsigned>(config.get_uint("cluster.nodes"));
  p.node_memory_bytes = config.get_uint("cluster.node_memory_kib") << 10;
  p.buffer_depth = parse_buffer_depth(config.get_string("cluster.buffer_depth"));
  p.scene = config.get_string("cluster.scene");
  p.triangles = static_cast<unsigned>(config.get_uint("cluster.triangles"));
  p.triangle_pixels = static_cast<unsigned>(config.get_uint("cluster.triangle_pixels"));
  p.seed = static_cast<unsigned>(config.get_uint("cluster.seed"));
  p.width = static_cast<unsigned>(config.get_uint("cluster.width"));
  p.height = static_cast<unsigned>(config.get_uint("cluster.height"));
  return p;
}

ClusterParams ClusterParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
