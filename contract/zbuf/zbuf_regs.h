// Register offsets and field masks of the z-buffer unit (zbuf_regs.def), and
// the layout of its colour-plane window (memory_map.def: zbuf_colour).
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::zbuf_regs {

#define TESSERA_REGISTER_TABLE "zbuf/zbuf_regs.def"
#include "common/register_constants.inc"

inline constexpr uint32_t ID_VALUE = reset_value::ID;

// The colour window: entry e of the window (e = row x WIDTH + column) at
// byte offset 2 e, 16 bits little-endian like the host, so that a window of
// the display's size reads as a frame of 16-bit pixels: one DMA copy
// (mem_to_mem, FRAME_SIZE.WIDTH x 2 bytes a row) puts it in the back buffer.
inline constexpr uint32_t COLOUR_ENTRY_BYTES = 2;

}  // namespace tessera::zbuf_regs
