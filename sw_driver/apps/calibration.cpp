// Host calibration micro-benchmarks of calibration.md: tight loops of 16-bit
// additions and of 16x8-bit multiplications, operands loaded from memory and
// the result stored, written as the ARM code a compiler emits for them:
//
//   loop: LDRH r3, [r0], #2        ; a[i]
//         LDRH r4, [r1], #2        ; b[i]      (LDRB for the 8-bit operand)
//         ADD  r3, r3, r4          ; uses r4 at once: load-use interlock (MUL)
//         STRH r3, [r2], #2        ; c[i]
//         SUBS r5, r5, #1
//         BNE  loop
//
// Each instruction is charged through the host model, so the rate printed is
// the model's; it is printed beside the rate measured on the J2210 board.
#include <cstdio>

#include "apps/apps.h"

namespace tessera {

namespace {

constexpr unsigned ITERATIONS = 65536;
constexpr double MEASURED_MILLIONS_PER_SECOND = 13.9;

int run_loop(AppEnvironment& env, bool multiply) {
  HostApi& host = *env.host;
  // Three arrays of ITERATIONS elements at 1 MiB, 2 MiB and 3 MiB.
  const uint32_t a = 1u << 20, b = 2u << 20, c = 3u << 20;
  if (env.memory_bytes < c + 2 * ITERATIONS) {
    std::fprintf(stderr, "calibration: needs at least %u bytes of system memory\n", c + 2 * ITERATIONS);
    return 1;
  }
  // Operands: a[i] = 3i + 1, b[i] = i mod 251 (written before timing starts;
  // plain stores do not allocate cache lines, so the loop starts cold).
  for (unsigned i = 0; i < ITERATIONS; ++i) {
    host.write16(a + 2 * i, static_cast<uint16_t>(3 * i + 1));
    if (multiply)
      host.write8(b + i, static_cast<uint8_t>(i % 251));
    else
      host.write16(b + 2 * i, static_cast<uint16_t>(i % 251));
  }
  const double start = host.now_seconds();
  uint32_t checksum = 0;
  for (unsigned i = 0; i < ITERATIONS; ++i) {
    const uint16_t x = host.read16(a + 2 * i);
    uint16_t result;
    if (multiply) {
      const uint8_t y = host.read8(b + i);
      host.compute(Op::load_use);
      host.compute(Op::mul);
      result = static_cast<uint16_t>(static_cast<int16_t>(x) * static_cast<int8_t>(y));
    } else {
      const uint16_t y = host.read16(b + 2 * i);
      host.compute(Op::load_use);
      host.compute(Op::alu);
      result = static_cast<uint16_t>(x + y);
    }
    host.write16(c + 2 * i, result);
    host.compute(Op::alu);
    host.compute(Op::branch);
    checksum += result;
  }
  const double seconds = host.now_seconds() - start;
  const double rate = ITERATIONS / seconds / 1e6;
  std::printf(
      "host calibration: %s loop of %u iterations: model %.2f million/s, measured %.1f million/s "
      "(%+.1f%%)\n",
      multiply ? "16x8-bit multiplication" : "16-bit addition", ITERATIONS, rate, MEASURED_MILLIONS_PER_SECOND,
      (rate / MEASURED_MILLIONS_PER_SECOND - 1) * 100);
  std::printf("host calibration: checksum %u\n", checksum);
  return 0;
}

}  // namespace

int calib_add_app(AppEnvironment& env) {
  return run_loop(env, false);
}
int calib_mul_app(AppEnvironment& env) {
  return run_loop(env, true);
}

}  // namespace tessera
