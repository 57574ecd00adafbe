// Register offsets of the interrupt controller, from intc_regs.def.
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::intc_regs {

#define TESSERA_REGISTER_TABLE "intc/intc_regs.def"
#include "common/register_constants.inc"

}  // namespace tessera::intc_regs
