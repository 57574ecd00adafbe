// Typed view of node_memory_map.def (the same Region as the SoC's map).
#pragma once

#include "soc/memory_map.h"

namespace tessera::node_memory_map {

using memory_map::Region;

#define TESSERA_REGION(name, base, size, description) inline constexpr Region name{#name, base, size, description};
#include "cluster/node_memory_map.def"
#undef TESSERA_REGION

inline constexpr Region ALL_REGIONS[] = {
#define TESSERA_REGION(name, base, size, description) name,
#include "cluster/node_memory_map.def"
#undef TESSERA_REGION
};

// The bare-metal runtime waits for interrupts through the controller at the
// SoC's address (sw_driver/runtime/host_api_iss.cpp): a node puts its own there.
static_assert(node_intc.base == memory_map::intc.base && node_intc.size == memory_map::intc.size);

}  // namespace tessera::node_memory_map

namespace tessera::node_irq {

// The node's host interrupt line its network interface drives (the only
// interrupt source of a node).
inline constexpr unsigned network_interface = 0;

}  // namespace tessera::node_irq
