// The cluster network's topologies (README.md, "Topologies and routes"):
// each names its directed links by number and gives the route of a message,
// the links it crosses in order, under its deterministic routing (e-cube
// for the hypercube, XY for the mesh, shortest direction for the ring, in
// and out of the switch for the crossbar). Plain C++.
#pragma once

#include <string>
#include <vector>

namespace tessera::network {

enum class Topology { hypercube, mesh, ring, crossbar };

// "hypercube", ...; throws ConfigError naming network.topology otherwise.
Topology parse_topology(const std::string& name);
const char* topology_name(Topology topology);

inline constexpr unsigned MAX_NODES = 128;

class Routing {
 public:
  // Throws ConfigError naming cluster.nodes for a node count outside
  // 1..MAX_NODES or, on a hypercube, not a power of two.
  Routing(Topology topology, unsigned nodes);

  Topology topology() const { return m_topology; }
  unsigned nodes() const { return m_nodes; }
  // Directed links, numbered 0..link_count()-1 (some numbers of a mesh
  // with a short last row are never used: link_exists says which).
  unsigned link_count() const { return m_link_count; }
  bool link_exists(unsigned link) const { return m_exists.at(link); }
  // The links that exist (the static power is charged per link).
  unsigned existing_links() const { return m_existing_links; }
  // The links from src to dst in the order the message crosses them;
  // empty for src == dst. Nodes must be below nodes().
  void route(unsigned src, unsigned dst, std::vector<unsigned>& links) const;
  unsigned hops(unsigned src, unsigned dst) const;
  // "from->to" for a link (the switch of the crossbar is "x").
  std::string link_name(unsigned link) const;

  // The mesh's grid (0 for the other topologies).
  unsigned mesh_columns() const { return m_columns; }
  unsigned mesh_rows() const { return m_rows; }

 private:
  void route_mesh(unsigned src, unsigned dst, std::vector<unsigned>& links) const;
  unsigned dimensions() const { return m_dimensions; }

  Topology m_topology;
  unsigned m_nodes;
  unsigned m_dimensions = 0;  // hypercube
  unsigned m_columns = 0, m_rows = 0;
  unsigned m_link_count = 0;
  unsigned m_existing_links = 0;
  std::vector<bool> m_exists;
};

}  // namespace tessera::network
