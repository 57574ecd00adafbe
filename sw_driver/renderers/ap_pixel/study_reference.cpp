#include "renderers/ap_pixel/study_reference.h"

namespace tessera::ap_pixel {

namespace {

uint16_t load16(const uint8_t* cmem, unsigned address) {
  return static_cast<uint16_t>(cmem[address] << 8 | cmem[address + 1]);
}

void store16(uint8_t* cmem, unsigned address, uint16_t value) {
  cmem[address] = static_cast<uint8_t>(value >> 8);
  cmem[address + 1] = static_cast<uint8_t>(value);
}

// A signed 16 x 8 multiplication into a 16-bit variable: the product's low
// 16 bits.
uint16_t multiply(uint16_t a, uint8_t b) {
  return static_cast<uint16_t>(int32_t{static_cast<int16_t>(a)} * int32_t{static_cast<int8_t>(b)});
}

uint16_t add(uint16_t a, uint16_t b) {
  return static_cast<uint16_t>(a + b);
}

}  // namespace

void run_study_reference(const PixelLayout& layout, unsigned block, unsigned attributes, uint8_t* cmem) {
  const unsigned t = layout.scratch;
  const auto out = [&](unsigned u, unsigned v, unsigned i) { return layout.result(u, v, static_cast<Attribute>(i)); };
  // The loop counts down, so attribute 0 is the last one evaluated.
  for (unsigned i = attributes; i-- > 0;) {
    const unsigned a = 2 * i;
    store16(cmem, t, multiply(load16(cmem, layout.gy + a), cmem[layout.dy]));
    store16(cmem, out(0, 0, i), add(load16(cmem, layout.c0 + a), load16(cmem, t)));
    store16(cmem, t, multiply(load16(cmem, layout.gx + a), cmem[layout.dx]));
    store16(cmem, out(0, 0, i), add(load16(cmem, out(0, 0, i)), load16(cmem, t)));
    for (unsigned v = 0; v < block; ++v) {
      if (v > 0) store16(cmem, out(0, v, i), add(load16(cmem, out(0, v - 1, i)), load16(cmem, layout.gy + a)));
      for (unsigned u = 1; u < block; ++u)
        store16(cmem, out(u, v, i), add(load16(cmem, out(u - 1, v, i)), load16(cmem, layout.gx + a)));
    }
  }
}

}  // namespace tessera::ap_pixel
