// Register offsets and field masks of the system/array DMA, from
// dma_regs.def, and the layout of its channels.
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::dma_regs {

#define TESSERA_REGISTER_TABLE "dma/dma_regs.def"
#include "common/register_constants.inc"

// What ID reads: "DMA", version 1.
inline constexpr uint32_t ID_VALUE = reset_value::ID;
// Channel c's registers start at channel_base(c).
inline constexpr uint32_t CHANNEL_BASE = 0x100;
inline constexpr uint32_t CHANNEL_STRIDE = 0x40;
inline constexpr unsigned MAX_CHANNELS = 8;
inline constexpr uint32_t channel_base(unsigned channel) {
  return CHANNEL_BASE + CHANNEL_STRIDE * channel;
}

// ERROR_DESC when the failing descriptor is the register descriptor.
inline constexpr uint32_t ERROR_DESC_REGISTERS = 0xFFFFFFFF;
// The IRQ bits of channel c.
inline constexpr uint32_t irq_done(unsigned channel) {
  return 1u << (2 * channel);
}
inline constexpr uint32_t irq_error(unsigned channel) {
  return 1u << (2 * channel + 1);
}

}  // namespace tessera::dma_regs
