// Register offsets and field masks of the display controller, from
// display_regs.def.
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::display_regs {

#define TESSERA_REGISTER_TABLE "display/display_regs.def"
#include "common/register_constants.inc"

}  // namespace tessera::display_regs
