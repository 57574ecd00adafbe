// The reference of ap_object.s: what the program does to one CU's CMEM,
// byte for byte, written from the program's arithmetic (README.md, "The
// program") rather than from the set-up, so that the test on the array's
// functional core checks the program and the test against a scalar
// rasterizer checks the set-up.
#pragma once

#include <cstdint>

#include "renderers/ap_object/object_setup.h"

namespace tessera::ap_object {

// Runs the program on `cmem` (the CU's whole CMEM) with record h's row loop
// started at rows[h] - 1 (rows[h] >= 1 iterations).
void run_reference(const ObjectLayout& layout, uint8_t* cmem, const unsigned rows[2]);

}  // namespace tessera::ap_object
