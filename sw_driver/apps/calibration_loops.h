/* The host calibration loops in C (calibration_loops.c). */
#pragma once

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

void tessera_calibration_add16(const uint16_t* a, const uint16_t* b, uint16_t* c, unsigned n);
void tessera_calibration_mul16x8(const int16_t* a, const int16_t* b, int16_t* c, unsigned n);

#ifdef __cplusplus
}
#endif
