#include "dma/dma_descriptor.h"

namespace tessera::dma {

const char* error_text(Error error) {
  switch (error) {
#define TESSERA_DMA_ERROR(name, code, text) \
  case Error::name:                         \
    return text;
#include "dma/dma_errors.def"
#undef TESSERA_DMA_ERROR
  }
  return "unknown error";
}

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::mem_to_cmem: return "mem_to_cmem";
    case Kind::cmem_to_mem: return "cmem_to_mem";
    case Kind::mem_to_mem: return "mem_to_mem";
    case Kind::broadcast: return "broadcast";
  }
  return "unknown";
}

unsigned Descriptor::element_bytes() const {
  const unsigned field = (ctrl & CTRL_ELEMENT_MASK) >> CTRL_ELEMENT_SHIFT;
  return field == 0 ? 1 : field;
}

std::array<uint32_t, DESCRIPTOR_WORDS> encode(const Descriptor& d) {
  return {d.ctrl, d.src, d.dst, d.length, d.src_stride, d.dst_stride, d.next, d.mask};
}

Descriptor decode(const std::array<uint32_t, DESCRIPTOR_WORDS>& w) {
  return {w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7]};
}

Descriptor decode_bytes(const uint8_t* bytes) {
  std::array<uint32_t, DESCRIPTOR_WORDS> words{};
  for (unsigned i = 0; i < DESCRIPTOR_WORDS; ++i)
    words[i] = uint32_t{bytes[4 * i]} | uint32_t{bytes[4 * i + 1]} << 8 | uint32_t{bytes[4 * i + 2]} << 16 |
               uint32_t{bytes[4 * i + 3]} << 24;
  return decode(words);
}

void encode_bytes(const Descriptor& d, uint8_t* bytes) {
  const auto words = encode(d);
  for (unsigned i = 0; i < DESCRIPTOR_WORDS; ++i)
    for (unsigned b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<uint8_t>(words[i] >> (8 * b));
}

}  // namespace tessera::dma
