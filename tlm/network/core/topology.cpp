#include "network/core/topology.h"

#include <cmath>
#include <stdexcept>

#include "config/config.h"

namespace tessera::network {

namespace {

// Mesh link numbers: node * 4 + direction.
enum MeshDirection : unsigned { east = 0, west = 1, north = 2, south = 3 };
// Ring link numbers: node * 2 + direction.
enum RingDirection : unsigned { clockwise = 0, counter_clockwise = 1 };

}  // namespace

Topology parse_topology(const std::string& name) {
  if (name == "hypercube") return Topology::hypercube;
  if (name == "mesh") return Topology::mesh;
  if (name == "ring") return Topology::ring;
  if (name == "crossbar") return Topology::crossbar;
  throw ConfigError("configuration: 'network.topology' expects one of hypercube, mesh, ring, crossbar, got \"" + name +
                    "\"");
}

const char* topology_name(Topology topology) {
  switch (topology) {
    case Topology::hypercube: return "hypercube";
    case Topology::mesh: return "mesh";
    case Topology::ring: return "ring";
    case Topology::crossbar: return "crossbar";
  }
  return "?";
}

Routing::Routing(Topology topology, unsigned nodes) : m_topology(topology), m_nodes(nodes) {
  if (nodes < 1 || nodes > MAX_NODES)
    throw ConfigError("configuration: 'cluster.nodes' expects an integer in [1, " + std::to_string(MAX_NODES) +
                      "], got " + std::to_string(nodes));
  switch (topology) {
    case Topology::hypercube:
      if ((nodes & (nodes - 1)) != 0)
        throw ConfigError(
            "configuration: impossible combination: network.topology=hypercube needs cluster.nodes to "
            "be a power of two, got " +
            std::to_string(nodes));
      while ((1u << m_dimensions) < nodes) ++m_dimensions;
      m_link_count = nodes * m_dimensions;
      m_exists.assign(m_link_count, true);
      break;
    case Topology::mesh: {
      m_columns = static_cast<unsigned>(std::ceil(std::sqrt(static_cast<double>(nodes))));
      m_rows = (nodes + m_columns - 1) / m_columns;
      m_link_count = 4 * nodes;
      m_exists.assign(m_link_count, false);
      for (unsigned n = 0; n < nodes; ++n) {
        const unsigned x = n % m_columns, y = n / m_columns;
        m_exists[4 * n + east] = x + 1 < m_columns && n + 1 < nodes;
        m_exists[4 * n + west] = x > 0;
        m_exists[4 * n + north] = y > 0;
        m_exists[4 * n + south] = n + m_columns < nodes;
      }
      break;
    }
    case Topology::ring:
      // A ring of one node has no link; of two, the clockwise and the
      // counter-clockwise link between the two nodes are two cables.
      m_link_count = nodes > 1 ? 2 * nodes : 0;
      m_exists.assign(m_link_count, true);
      break;
    case Topology::crossbar:
      m_link_count = 2 * nodes;  // [n]: n into the switch; [nodes + n]: the switch out to n
      m_exists.assign(m_link_count, nodes > 1);
      break;
  }
  for (bool e : m_exists) m_existing_links += e ? 1 : 0;
}

void Routing::route(unsigned src, unsigned dst, std::vector<unsigned>& links) const {
  links.clear();
  if (src >= m_nodes || dst >= m_nodes)
    throw std::out_of_range("network: route from node " + std::to_string(src) + " to node " + std::to_string(dst) +
                            " of " + std::to_string(m_nodes));
  if (src == dst) return;
  switch (m_topology) {
    case Topology::hypercube: {
      unsigned at = src;
      for (unsigned d = 0; d < m_dimensions; ++d)
        if (((at ^ dst) >> d) & 1u) {
          links.push_back(at * m_dimensions + d);
          at ^= 1u << d;
        }
      break;
    }
    case Topology::mesh: route_mesh(src, dst, links); break;
    case Topology::ring: {
      const unsigned forward = (dst + m_nodes - src) % m_nodes;
      const bool cw = forward <= m_nodes - forward;
      const unsigned steps = cw ? forward : m_nodes - forward;
      unsigned at = src;
      for (unsigned i = 0; i < steps; ++i) {
        links.push_back(2 * at + (cw ? clockwise : counter_clockwise));
        at = cw ? (at + 1) % m_nodes : (at + m_nodes - 1) % m_nodes;
      }
      break;
    }
    case Topology::crossbar:
      links.push_back(src);
      links.push_back(m_nodes + dst);
      break;
  }
}

void Routing::route_mesh(unsigned src, unsigned dst, std::vector<unsigned>& links) const {
  unsigned x = src % m_columns, y = src / m_columns;
  const unsigned tx = dst % m_columns, ty = dst / m_columns;
  const auto move_x = [&] {
    while (x != tx) {
      const unsigned at = y * m_columns + x;
      links.push_back(4 * at + (tx > x ? east : west));
      x = tx > x ? x + 1 : x - 1;
    }
  };
  const auto move_y = [&] {
    while (y != ty) {
      const unsigned at = y * m_columns + x;
      links.push_back(4 * at + (ty > y ? south : north));
      y = ty > y ? y + 1 : y - 1;
    }
  };
  // XY, except from a short last row to another row, where a move along
  // the last row could leave the grid: there YX (every row above is full).
  const bool short_last_row = m_rows * m_columns != m_nodes;
  if (short_last_row && y == m_rows - 1 && ty != y) {
    move_y();
    move_x();
  } else {
    move_x();
    move_y();
  }
}

unsigned Routing::hops(unsigned src, unsigned dst) const {
  std::vector<unsigned> links;
  route(src, dst, links);
  return static_cast<unsigned>(links.size());
}

std::string Routing::link_name(unsigned link) const {
  const auto pair = [](unsigned from, unsigned to) { return std::to_string(from) + "->" + std::to_string(to); };
  switch (m_topology) {
    case Topology::hypercube: {
      const unsigned n = link / m_dimensions, d = link % m_dimensions;
      return pair(n, n ^ (1u << d));
    }
    case Topology::mesh: {
      const unsigned n = link / 4;
      switch (link % 4) {
        case east: return pair(n, n + 1);
        case west: return pair(n, n - 1);
        case north: return pair(n, n - m_columns);
        default: return pair(n, n + m_columns);
      }
    }
    case Topology::ring: {
      const unsigned n = link / 2;
      return pair(n, link % 2 == clockwise ? (n + 1) % m_nodes : (n + m_nodes - 1) % m_nodes);
    }
    case Topology::crossbar:
      return link < m_nodes ? std::to_string(link) + "->x" : "x->" + std::to_string(link - m_nodes);
  }
  return "?";
}

}  // namespace tessera::network
