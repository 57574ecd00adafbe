// The reference of ap_object.s: what the program does to one CU's CMEM,
// byte for byte, written from the program's arithmetic (README.md, "The
// program") rather than from the set-up, so that the test on the array's
// functional core checks the program and the test against a scalar
// rasterizer checks the set-up.
#pragma once

#include <cstdint>
#include <vector>

#include "renderers/ap_object/object_setup.h"

namespace tessera::ap_object {

// Runs the program on `cmem` (the CU's whole CMEM) with record h's row loop
// started at rows[h] - 1 (rows[h] >= 1 iterations).
void run_reference(const ObjectLayout& layout, uint8_t* cmem, const unsigned rows[2]);

// A pixel a ZSEND program sends: x and y (the frame's memory rows), z16 and
// RGB565, the operands of zsend.
struct ZsendPixel {
  uint16_t x = 0, y = 0, z = 0, colour = 0;
  bool operator==(const ZsendPixel& other) const {
    return x == other.x && y == other.y && z == other.z && colour == other.colour;
  }
};

// The same for a ZSEND program (layout.zsend): its CMEM bytes, and the
// pixels the CU sends, in the order it sends them, appended to `sent`. The
// depth and colour of a pixel are computed here as the host path reads and
// packs a slot (the top byte's clamp, pack_pixel's rounding), not as the
// program computes them, so that the test checks the two paths agree.
void run_reference_zsend(const ObjectLayout& layout, uint8_t* cmem, const unsigned rows[2],
                         std::vector<ZsendPixel>& sent);

}  // namespace tessera::ap_object
