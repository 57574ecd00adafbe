#include "cluster_node/host_charges.h"

#include "costs/host_cost.h"

namespace tessera {

void CostMeter::charge(HostApi& host, const cluster::WorkCounters& now) {
  using costs::HostCost;
  const cluster::WorkCounters& was = m_charged;
  costs::charge(host, HostCost::sort_middle_triangle, now.triangles_in - was.triangles_in);
  costs::charge(host, HostCost::sort_middle_split, now.triangles_split - was.triangles_split);
  costs::charge(host, HostCost::sort_middle_piece, now.trapezoids_out - was.trapezoids_out);
  costs::charge(host, HostCost::sort_middle_trapezoid, now.trapezoids_in - was.trapezoids_in);
  costs::charge(host, HostCost::sort_middle_row, now.rows - was.rows);
  costs::charge(host, HostCost::sort_middle_pixel, now.pixels - was.pixels);
  m_charged = now;
}

}  // namespace tessera
