// Register offsets and bits of the display controller, from display_regs.def.
#pragma once

#include <cstdint>

namespace tessera::display_regs {

#define TESSERA_DISPLAY_REG(name, offset, reset, access) inline constexpr uint32_t name = offset;
#include "display/display_regs.def"
#undef TESSERA_DISPLAY_REG

inline constexpr uint32_t CTRL_ENABLE = 1u << 0;
inline constexpr uint32_t STATUS_VBLANK = 1u << 0;
inline constexpr uint32_t STATUS_SWAP_PENDING = 1u << 1;
inline constexpr uint32_t IRQ_VBLANK = 1u << 0;
inline constexpr uint32_t IRQ_SWAP_DONE = 1u << 1;
inline constexpr uint32_t IRQ_FRAME_PRESENTED = 1u << 2;

}  // namespace tessera::display_regs
