// The network interface's parameter: ni.burst_beats (README.md,
// "Parameters"). Its node number, the node count, its clock and its node's
// memory are set by the platform.
#include "network/network_interface.h"

namespace tessera {

ParamGroup NetworkInterfaceParams::parameters() {
  return {"ni",
          {param::integer("ni.burst_beats", 16, 1, 256, "beats",
                          "longest burst of the network interface's accesses to its node's memory")},
          {}};
}

NetworkInterfaceParams NetworkInterfaceParams::from_config(const Config& config) {
  NetworkInterfaceParams p;
  p.burst_beats = static_cast<unsigned>(config.get_uint("ni.burst_beats"));
  return p;
}

NetworkInterfaceParams NetworkInterfaceParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
