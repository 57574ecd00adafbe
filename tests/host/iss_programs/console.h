/* Output of the ISS test programs: on the ISS a byte register of the test
 * machine, natively stdout; the two outputs must be the same. */
#pragma once
#ifdef __arm__
static inline void put_char(char c) {
  *(volatile unsigned char*)0xf0000000u = (unsigned char)c;
}
#else
#include <stdio.h>
static inline void put_char(char c) {
  putchar(c);
}
#endif

static inline void put_text(const char* text) {
  while (*text) put_char(*text++);
}

static inline void put_hex(const char* label, unsigned value) {
  put_text(label);
  put_char(' ');
  for (int shift = 28; shift >= 0; shift -= 4) put_char("0123456789abcdef"[(value >> shift) & 15u]);
  put_char('\n');
}
