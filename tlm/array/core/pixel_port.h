// Where the array's zsend instruction delivers its pixels: the port of the
// z-buffer unit beside the array (tlm/zbuf), seen from the array's core as a
// plain C++ interface so that neither core depends on the other's SystemC
// wrapper.
//
// One zsend is one call of send(): the pixels of every CU whose mask was
// set, in ascending lane order (lane = row x columns + column), and when
// they reach the port. The unit answers with the cycle in which it takes
// each pixel; the controller keeps the port's reservation over the
// instruction stream (array_controller.h, tlm/zbuf/README.md "Timing").
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

// When a send's pixels reach the port, in cycles after the zsend's issue:
// in lockstep every pixel at 0; under row-sequential issue (array.issue_skew
// = row) the pixels of row r at r x row_delay, row r being lane /
// row_lanes. The port takes none of them before `first` (it is still taking
// an earlier send's pixels until then).
struct SendArrival {
  unsigned row_lanes = 1;
  unsigned row_delay = 0;
  uint64_t first = 0;
  uint64_t arrival(uint16_t lane) const { return uint64_t{lane} / row_lanes * row_delay; }
};

// The port's answer: per pixel, the cycle after the zsend's issue in which
// it is taken; and the cycles in which the port took any (a send's cycles
// need not follow each other: a later row may arrive after the port has
// taken an earlier one).
struct SendTimes {
  std::vector<uint64_t> cycles;
  uint64_t busy = 0;
};

class PixelPort {
 public:
  virtual ~PixelPort() = default;
  // Takes one zsend's pixels (ascending lanes, possibly none).
  virtual SendTimes send(const std::vector<SentPixel>& pixels, const SendArrival& arrival) = 0;
};

}  // namespace tessera::ap
