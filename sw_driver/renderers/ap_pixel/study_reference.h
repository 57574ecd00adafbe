// The study program's arithmetic (ap_pixel_study.s) in plain C++, on one
// CU's CMEM image laid out as its PixelLayout says: the reference the
// program is checked against byte for byte (tests/sw_driver/renderers/
// ap_pixel/). Written from the study's statements (README.md, "The study
// program"): 16-bit 8.8 values, big-endian, every sum and product modulo
// 2^16.
#pragma once

#include <cstdint>

#include "renderers/ap_pixel/pixel_setup.h"

namespace tessera::ap_pixel {

// Runs the study program on `cmem` (one CU's CMEM, at least
// layout.cmem_bytes): a block of `block` x `block` pixels, each with the
// first `attributes` attributes (block<k>: k, ATTRIBUTES; shade<n>: 1, n).
void run_study_reference(const PixelLayout& layout, unsigned block, unsigned attributes, uint8_t* cmem);

}  // namespace tessera::ap_pixel
