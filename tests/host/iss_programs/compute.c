/* A workload for the ISS compiled twice, for the ARM922T (ARM and Thumb,
 * soft float) and natively: integer arithmetic, division (libgcc's on the
 * ARM), 64-bit products, IEEE single and double arithmetic (soft-float on
 * the ARM: correctly rounded + - x / and conversions, so both agree to the
 * bit), a sort, a CRC, memmove/memset of newlib, recursion and a jump table.
 * It prints one hex line per result; the test compares the two outputs. */
#include <stdint.h>
#include <string.h>

#include "console.h"

static uint32_t seed = 12345;
static uint32_t next_random(void) {
  seed = seed * 1103515245u + 12345u;
  return seed;
}

static uint32_t crc32(const uint8_t* data, unsigned length) {
  uint32_t crc = 0xffffffffu;
  for (unsigned i = 0; i < length; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

static void insertion_sort(int32_t* values, int count) {
  for (int i = 1; i < count; ++i) {
    const int32_t v = values[i];
    int j = i - 1;
    while (j >= 0 && values[j] > v) {
      values[j + 1] = values[j];
      --j;
    }
    values[j + 1] = v;
  }
}

static unsigned fibonacci(unsigned n) {
  return n < 2 ? n : fibonacci(n - 1) + fibonacci(n - 2);
}

static int classify(unsigned x) {
  switch (x % 7) { /* a jump table */
    case 0: return 11;
    case 1: return 23;
    case 2: return 37;
    case 3: return 41;
    case 4: return 53;
    case 5: return 67;
    default: return 79;
  }
}

static uint8_t buffer[512];
static int32_t values[64];

int main(void) {
  uint32_t sum = 0, product = 1;
  int32_t quotients = 0, remainders = 0;
  uint64_t wide = 0;
  for (int i = 0; i < 200; ++i) {
    const uint32_t a = next_random(), b = next_random() | 1u;
    sum += a ^ (b >> 3);
    product = product * (a | 1u) + (b << 7);
    quotients += (int32_t)a / (int32_t)(b >> 20 | 1u);
    remainders += (int32_t)(a % (b >> 12 | 3u));
    wide += (uint64_t)a * b + ((int64_t)(int32_t)a * (int32_t)b >> 13);
  }
  put_hex("sum", sum);
  put_hex("product", product);
  put_hex("quotients", (uint32_t)quotients);
  put_hex("remainders", (uint32_t)remainders);
  put_hex("wide.hi", (uint32_t)(wide >> 32));
  put_hex("wide.lo", (uint32_t)wide);

  float f = 1.0f, g = 0.0f;
  double d = 1.0;
  for (int i = 1; i < 100; ++i) {
    f = f * 1.0625f + (float)i / 7.0f;
    g -= f / (float)(i * i + 1);
    d = d * 0.999 + (double)i / 3.0 - (double)f * 1e-3;
  }
  union {
    float f;
    uint32_t u;
  } fu = {f}, gu = {g};
  union {
    double d;
    uint64_t u;
  } du = {d};
  put_hex("float f", fu.u);
  put_hex("float g", gu.u);
  put_hex("double.hi", (uint32_t)(du.u >> 32));
  put_hex("double.lo", (uint32_t)du.u);
  put_hex("float->int", (uint32_t)(int32_t)(g * 1000.0f));
  put_hex("double->uint", (uint32_t)(d * 16.0));

  for (unsigned i = 0; i < sizeof buffer; ++i) buffer[i] = (uint8_t)next_random();
  memmove(buffer + 100, buffer + 7, 200); /* overlapping: memmove, as memcpy would be undefined */
  memset(buffer + 400, 0x5a, 33);
  put_hex("crc32", crc32(buffer, sizeof buffer));

  for (int i = 0; i < 64; ++i) values[i] = (int32_t)next_random() >> 7;
  insertion_sort(values, 64);
  uint32_t order = 0;
  for (int i = 0; i < 64; ++i) order = order * 31u + (uint32_t)values[i];
  put_hex("sorted", order);
  put_hex("min", (uint32_t)values[0]);
  put_hex("fibonacci(20)", fibonacci(20));
  int classes = 0;
  for (unsigned i = 0; i < 100; ++i) classes += classify(next_random());
  put_hex("classes", (uint32_t)classes);
  return 0;
}
