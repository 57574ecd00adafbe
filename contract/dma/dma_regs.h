// Register offsets and bits of the system/array DMA, from dma_regs.def.
#pragma once

#include <cstdint>

namespace tessera::dma_regs {

#define TESSERA_DMA_REG(name, offset, reset, access) inline constexpr uint32_t name = offset;
#define TESSERA_DMA_CHANNEL_REG(name, offset, reset, access) inline constexpr uint32_t CH_##name = offset;
#include "dma/dma_regs.def"
#undef TESSERA_DMA_CHANNEL_REG
#undef TESSERA_DMA_REG

inline constexpr uint32_t ID_VALUE = 0x444D4101;
inline constexpr uint32_t CHANNEL_BASE = 0x100;
inline constexpr uint32_t CHANNEL_STRIDE = 0x40;
inline constexpr unsigned MAX_CHANNELS = 8;
inline constexpr uint32_t channel_base(unsigned channel) {
  return CHANNEL_BASE + CHANNEL_STRIDE * channel;
}

inline constexpr uint32_t START_GO = 1u << 0;
inline constexpr uint32_t START_CHAIN_ONLY = 1u << 1;
inline constexpr uint32_t STATUS_BUSY = 1u << 0;
inline constexpr uint32_t STATUS_DONE = 1u << 1;
inline constexpr uint32_t STATUS_ERROR = 1u << 2;
inline constexpr uint32_t STATUS_REFUSED = 1u << 3;
inline constexpr uint32_t ERROR_DESC_REGISTERS = 0xFFFFFFFF;
inline constexpr uint32_t irq_done(unsigned channel) {
  return 1u << (2 * channel);
}
inline constexpr uint32_t irq_error(unsigned channel) {
  return 1u << (2 * channel + 1);
}

}  // namespace tessera::dma_regs
