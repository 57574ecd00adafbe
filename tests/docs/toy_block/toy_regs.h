// The toy block's register constants (docs/how_to_add_a_block.md, section 4).
#pragma once

#include "common/register_table.h"

namespace tessera::toy_regs {
#define TESSERA_REGISTER_TABLE "toy_regs.def"
#include "common/register_constants.inc"
}  // namespace tessera::toy_regs
