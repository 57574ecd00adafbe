// Where the array's zsend instruction delivers its pixels: the port of the
// z-buffer unit beside the array (tlm/zbuf), seen from the array's core as a
// plain C++ interface so that neither core depends on the other's SystemC
// wrapper.
//
// One zsend is one call of send(): the pixels of every CU whose mask was
// set, in ascending lane order (lane = row x columns + column). The unit
// answers with the array cycles its ports are busy taking them; the
// controller keeps the port's reservation over the instruction stream
// (array_controller.h, tlm/zbuf/README.md "Timing").
#pragma once

#include <cstdint>
#include <vector>

namespace tessera::ap {

// The operands of zsend, as the CU read them (big-endian pairs of bytes).
struct SentPixel {
  uint16_t lane = 0;
  uint16_t x = 0;
  uint16_t y = 0;
  uint16_t z = 0;
  uint16_t colour = 0;
};

class PixelPort {
 public:
  virtual ~PixelPort() = default;
  // Takes one zsend's pixels (ascending lanes, possibly none); returns the
  // array cycles the unit's ports are busy with them.
  virtual uint64_t send(const std::vector<SentPixel>& pixels) = 0;
};

}  // namespace tessera::ap
