// The system/array DMA's descriptor as the software writes it: its eight
// 32-bit words (in memory, little-endian, and in a channel's registers),
// the kinds, the CTRL fields and the error codes a channel reports. Part of
// the software-visible contract: the driver builds descriptors with it, the
// DMA's functional core (tlm/dma/core/dma_engine.h) checks and moves them.
// tlm/dma/README.md walks through the layout.
#pragma once

#include <array>
#include <cstdint>

namespace tessera::dma {

enum class Kind : uint32_t {
  mem_to_cmem = 0,  // reshuffle: a plain array in CU order lands array-ready
  cmem_to_mem = 1,  // the reverse
  mem_to_mem = 2,   // a plain copy
  broadcast = 3,    // the same bytes into every CU of a mask, in one pass
};

enum class Error : uint32_t {
#define TESSERA_DMA_ERROR(name, code, text) name = (code),
#include "dma/dma_errors.def"
#undef TESSERA_DMA_ERROR
};

const char* error_text(Error error);
const char* kind_name(Kind kind);

inline constexpr unsigned DESCRIPTOR_WORDS = 8;
inline constexpr unsigned DESCRIPTOR_BYTES = 4 * DESCRIPTOR_WORDS;
// CTRL word fields.
inline constexpr uint32_t CTRL_KIND_MASK = 0x7;
inline constexpr unsigned CTRL_ELEMENT_SHIFT = 4;
inline constexpr uint32_t CTRL_ELEMENT_MASK = 0x3u << CTRL_ELEMENT_SHIFT;
// The rest of CTRL is reserved: a descriptor with any of it set is refused.
inline constexpr uint32_t CTRL_RESERVED_MASK = ~(CTRL_KIND_MASK | CTRL_ELEMENT_MASK);

// Word order: the same in memory (little-endian words) and in registers.
struct Descriptor {
  uint32_t ctrl = 0;
  uint32_t src = 0;
  uint32_t dst = 0;
  uint32_t length = 0;
  uint32_t src_stride = 0;
  uint32_t dst_stride = 0;
  uint32_t next = 0;  // next descriptor in memory, 0: the end
  uint32_t mask = 0;  // broadcast: CU mask in memory, 0: every CU

  uint32_t kind_code() const { return ctrl & CTRL_KIND_MASK; }
  Kind kind() const { return static_cast<Kind>(kind_code()); }
  // 1 or 2 for a valid reshuffle (0 in the field reads as 1).
  unsigned element_bytes() const;

  static uint32_t make_ctrl(Kind kind, unsigned element_bytes = 1) {
    return static_cast<uint32_t>(kind) | (element_bytes << CTRL_ELEMENT_SHIFT);
  }
};

std::array<uint32_t, DESCRIPTOR_WORDS> encode(const Descriptor& d);
Descriptor decode(const std::array<uint32_t, DESCRIPTOR_WORDS>& words);
// From / to 32 bytes of memory (little-endian words, the host's order).
Descriptor decode_bytes(const uint8_t* bytes);
void encode_bytes(const Descriptor& d, uint8_t* bytes);

// Bytes of the CU mask in memory: ceil(lanes / 8).
inline unsigned mask_bytes(unsigned lanes) {
  return (lanes + 7) / 8;
}

}  // namespace tessera::dma
