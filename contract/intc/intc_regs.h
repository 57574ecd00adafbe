// Register offsets of the interrupt controller, from intc_regs.def.
#pragma once

#include <cstdint>

namespace tessera::intc_regs {

#define TESSERA_INTC_REG(name, offset, reset, access) inline constexpr uint32_t name = offset;
#include "intc/intc_regs.def"
#undef TESSERA_INTC_REG

}  // namespace tessera::intc_regs
