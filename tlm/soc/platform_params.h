// The parameters a platform derives for the blocks it builds from other
// groups' keys, shared by the SoC (soc.cpp) and the cluster platform
// (tlm/cluster): a memory on the bus's clock and width, a host whose
// cacheable range is that memory and whose run-ahead follows the
// simulation's timing (sim.quantum_ns, sim.run_ahead_us).
#pragma once

#include <cstdint>

#include "bus/ahb_bus.h"
#include "config/config.h"
#include "host/host.h"
#include "mem/memory.h"

namespace tessera {

// mem.* with `size_bytes` populated (the SoC's mem.size_mib, a node's
// cluster.node_memory_kib).
MemoryParams platform_memory_params(const Config& config, uint64_t size_bytes);

// host.* with the cacheable range [base, base + size_bytes).
HostParams platform_host_params(const Config& config, uint32_t cacheable_base, uint64_t size_bytes);

}  // namespace tessera
