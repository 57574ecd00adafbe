// Interrupt line numbers of the host, from irq_map.def.
#pragma once

namespace tessera::irq_map {
#define TESSERA_IRQ(source, line) inline constexpr unsigned source = line;
#include "soc/irq_map.def"
#undef TESSERA_IRQ
}  // namespace tessera::irq_map
