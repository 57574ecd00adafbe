/* The host calibration loops of docs/spec/calibration.md as plain C: a tight
 * loop of 16-bit additions and one of 16 x 8-bit multiplications, operands
 * loaded from memory and the result stored. Cross-compiled for the ARM922T
 * (host.model=iss), GCC's code for them is what the ISS times; the
 * host-compiled model charges a hand count of the same loop instead
 * (calibration.cpp). */
#include "apps/calibration_loops.h"

void tessera_calibration_add16(const uint16_t* a, const uint16_t* b, uint16_t* c, unsigned n) {
  for (unsigned i = 0; i < n; ++i) c[i] = (uint16_t)(a[i] + b[i]);
}

void tessera_calibration_mul16x8(const int16_t* a, const int16_t* b, int16_t* c, unsigned n) {
  for (unsigned i = 0; i < n; ++i) c[i] = (int16_t)(a[i] * b[i]);
}
