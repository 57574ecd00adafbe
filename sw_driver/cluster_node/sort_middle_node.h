// The sort-middle renderer's SPMD program (README.md): what every node of
// the cluster platform runs, on either host model. Node k of p deals itself
// the triangles i = k, k + p, ...; transforms, culls and splits each into
// trapezoids (sw_driver/cluster); draws the pieces of its own stripe and
// collects the others per destination, sending a buffer when it holds d
// trapezoids, two buffers per destination so that one fills while the
// other is sent; draws what it receives; and ends each frame with the
// paper's termination protocol.
#pragma once

#include "device/app_environment.h"

namespace tessera {

// The built-in application `cluster_node` (apps.h): the node program, on
// the cluster platform only (soc_sim --platform cluster).
int cluster_node_app(AppEnvironment& env);

}  // namespace tessera
