// Register offsets and field masks of the rasterizer, from raster_regs.def.
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::raster_regs {

#define TESSERA_REGISTER_TABLE "raster/raster_regs.def"
#include "common/register_constants.inc"

}  // namespace tessera::raster_regs
