// Register offsets and field masks of the array controller (array_regs.def),
// and the layout of its two other windows: program memory and the CIU's
// view of CMEM (the CIU lane rule).
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::array_regs {

#define TESSERA_REGISTER_TABLE "array/array_regs.def"
#include "common/register_constants.inc"

// Program memory (memory_map.def: array_program): instruction word w at
// byte offset 8 w, low 32 bits first (little-endian, like the host).
inline constexpr uint32_t PROGRAM_WORD_BYTES = 8;

// The CIU window (memory_map.def: array_cmem): CMEM address a of CU group
// g at byte offset 4 (g x cmem_bytes + a). Group g = j x (columns / 4) + i
// is the four CUs of row j, columns 4i..4i+3; the word's byte k (k = 0 the
// least significant) is CU column 4i+k's byte at address a.
inline constexpr uint32_t CUS_PER_GROUP = 4;
inline constexpr uint32_t cmem_offset(uint32_t group, uint32_t address, uint32_t cmem_bytes) {
  return 4 * (group * cmem_bytes + address);
}

}  // namespace tessera::array_regs
