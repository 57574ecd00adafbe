// Register offsets of the simulation control block, from sim_control_regs.def.
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::sim_control_regs {

#define TESSERA_REGISTER_TABLE "soc/sim_control_regs.def"
#include "common/register_constants.inc"

}  // namespace tessera::sim_control_regs
