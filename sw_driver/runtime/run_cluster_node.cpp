// tessera_runtime_run for the cluster platform's node program
// (tessera_cluster_node.elf, sw_driver/cluster_node/README.md): every node
// of soc_sim --platform cluster with host.model=iss runs it. ARM only.
#include "cluster_node/sort_middle_node.h"
#include "runtime/runtime.h"

int tessera_runtime_run(tessera::AppEnvironment& env, const tessera::boot_info::BootInfo& /*boot*/) {
  return tessera::cluster_node_app(env);
}
