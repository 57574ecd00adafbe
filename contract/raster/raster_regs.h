// Register offsets and bits of the rasterizer, from raster_regs.def.
#pragma once

#include <cstdint>

namespace tessera::raster_regs {

#define TESSERA_RASTER_REG(name, offset, reset, access) inline constexpr uint32_t name = offset;
#include "raster/raster_regs.def"
#undef TESSERA_RASTER_REG

inline constexpr uint32_t STATUS_BUSY = 1u << 0;
inline constexpr uint32_t STATUS_DONE = 1u << 1;
inline constexpr uint32_t STATUS_ERROR = 1u << 2;
inline constexpr uint32_t IRQ_DONE = 1u << 0;
inline constexpr uint32_t IRQ_ERROR = 1u << 1;

}  // namespace tessera::raster_regs
