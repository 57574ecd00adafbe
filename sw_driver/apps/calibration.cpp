// Calibration micro-benchmarks of docs/spec/calibration.md. The host's:
// tight loops of 16-bit additions and of 16x8-bit multiplications, operands
// loaded from memory and the result stored, written as the ARM code a
// compiler emits for them:
//
//   loop: LDRH r3, [r0], #2        ; a[i]
//         LDRH r4, [r1], #2        ; b[i]      (LDRSH: the 8-bit operand, kept in 16 bits)
//         ADD  r3, r3, r4          ; uses r4 at once: load-use interlock (MUL)
//         STRH r3, [r2], #2        ; c[i]
//         SUBS r5, r5, #1
//         BNE  loop
//
// On the ISS (host.model=iss) the loop is GCC's code for the same loop in C
// (calibration_loops.c), six instructions an iteration as above, and the
// rate printed is the ISS's; natively the loads and the store go through
// the host model's cache and bus, and the rest of an iteration is a row of
// the measured cost table (calib_add_iteration, calib_mul_iteration:
// sw_driver/costs). The rate is printed beside the one measured on the
// J2210 board.
//
// The display port's: the host copies one finished frame of the study's
// size (192x144, 16 bits per pixel) from its frame buffer in system memory
// to the display port, with the display driver's copy loop (LDM/STM of
// eight words, the port mode's present()), and the time is printed beside
// the 36 ms measured on the board.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#include "apps/apps.h"
#include "apps/calibration_loops.h"
#include "costs/host_cost.h"
#include "device/display_driver.h"
#include "display/display_regs.h"
#include "soc/memory_map.h"

namespace tessera {

namespace {

constexpr unsigned ITERATIONS = 65536;
constexpr double MEASURED_MILLIONS_PER_SECOND = 13.9;

int run_loop(AppEnvironment& env, bool multiply) {
  HostApi& host = *env.host;
  // Three arrays of ITERATIONS elements 1 MiB apart in the driver's heap
  // (the memory below it is the program's own on the ISS).
  const uint32_t a = env.heap_base, b = a + (1u << 20), c = a + (2u << 20);
  if (env.heap_end < c + 2 * ITERATIONS) {
    std::fprintf(stderr,
                 "calibration: needs 2 MiB + %u bytes of the driver's heap, which has %" PRIu32
                 " (more system memory: mem.size_mib)\n",
                 2 * ITERATIONS, env.heap_end - env.heap_base);
    return 1;
  }
  // Operands: a[i] = 3i + 1, b[i] = i mod 251 (written before timing starts;
  // plain stores do not allocate cache lines, so the loop starts cold). The
  // multiplication's b is an 8-bit value (i mod 251 as a signed byte) held
  // in a 16-bit element like the addition's: the board ran both loops at
  // the same rate, which in a loop bound by its memory traffic means the
  // same traffic (docs/calibration.md, "calib_mul: the loop's form").
  for (unsigned i = 0; i < ITERATIONS; ++i) {
    host.write16(a + 2 * i, static_cast<uint16_t>(3 * i + 1));
    const uint16_t operand = multiply ? static_cast<uint16_t>(static_cast<int16_t>(static_cast<int8_t>(i % 251)))
                                      : static_cast<uint16_t>(i % 251);
    host.write16(b + 2 * i, operand);
  }
  const double start = host.now_seconds();
  uint32_t checksum = 0;
#if defined(TESSERA_HOST_ISS)
  // On the ISS the loop is GCC's code for the C loop itself
  // (calibration_loops.c); the checksum is read afterwards.
  if (multiply)
    tessera_calibration_mul16x8(reinterpret_cast<const int16_t*>(a), reinterpret_cast<const int16_t*>(b),
                                reinterpret_cast<int16_t*>(c), ITERATIONS);
  else
    tessera_calibration_add16(reinterpret_cast<const uint16_t*>(a), reinterpret_cast<const uint16_t*>(b),
                              reinterpret_cast<uint16_t*>(c), ITERATIONS);
  const double seconds = host.now_seconds() - start;
  for (unsigned i = 0; i < ITERATIONS; ++i) checksum += host.read16(c + 2 * i);
#else
  for (unsigned i = 0; i < ITERATIONS; ++i) {
    const uint16_t x = host.read16(a + 2 * i);
    uint16_t result;
    // The iteration's instructions but its loads and store, as the ISS
    // runs GCC's loop (the row's cycles are measured there).
    if (multiply) {
      const uint16_t y = host.read16(b + 2 * i);
      costs::charge(host, costs::HostCost::calib_mul_iteration);
      result = static_cast<uint16_t>(static_cast<int16_t>(x) * static_cast<int16_t>(y));
    } else {
      const uint16_t y = host.read16(b + 2 * i);
      costs::charge(host, costs::HostCost::calib_add_iteration);
      result = static_cast<uint16_t>(x + y);
    }
    host.write16(c + 2 * i, result);
    checksum += result;
  }
  const double seconds = host.now_seconds() - start;
#endif
  const double rate = ITERATIONS / seconds / 1e6;
  std::printf(
      "host calibration: %s loop of %u iterations: model %.2f million/s, measured %.1f million/s "
      "(%+.1f%%)\n",
      multiply ? "16x8-bit multiplication" : "16-bit addition", ITERATIONS, rate, MEASURED_MILLIONS_PER_SECOND,
      (rate / MEASURED_MILLIONS_PER_SECOND - 1) * 100);
  std::printf("host calibration: checksum %" PRIu32 "\n", checksum);
  return 0;
}

}  // namespace

int calib_add_app(AppEnvironment& env) {
  return run_loop(env, false);
}
int calib_mul_app(AppEnvironment& env) {
  return run_loop(env, true);
}

namespace {

constexpr unsigned STUDY_WIDTH = 192, STUDY_HEIGHT = 144;
constexpr double MEASURED_FRAME_COPY_MS = 36.0;
constexpr int EXIT_BAD_INPUT = 2;  // soc_sim's status for bad input

}  // namespace

int calib_display_port_app(AppEnvironment& env) {
  HostApi& host = *env.host;
  DisplayDriver display(env);
  if (display.dma() || display.width() != STUDY_WIDTH || display.height() != STUDY_HEIGHT ||
      display.format() != PixelFormat::rgb565) {
    std::fprintf(stderr,
                 "calib_display_port: the board's figure is for the host copying a %ux%u rgb565 frame to the display "
                 "port; this display is %ux%u %s in %s mode: run with --set display.width=%u --set display.height=%u "
                 "(and display.dma=false, display.format=rgb565)\n",
                 STUDY_WIDTH, STUDY_HEIGHT, display.width(), display.height(), pixel_format_name(display.format()),
                 display.dma() ? "DMA" : "port", STUDY_WIDTH, STUDY_HEIGHT);
    return EXIT_BAD_INPUT;
  }
  // The finished frame: a ramp, stored before the timed part. The stores
  // miss the data cache, which does not allocate on writes, so the copy
  // starts with a cold cache, as after drawing a frame larger than it.
  const unsigned pixels = STUDY_WIDTH * STUDY_HEIGHT;
  uint8_t* frame = host.store_span(display.back_buffer(), 2, pixels);
  for (unsigned i = 0; i < pixels; ++i) {
    const auto value = static_cast<uint16_t>(i * 7);
    std::memcpy(frame + 2 * i, &value, 2);
  }
  // An uncached read waits for the write buffer: the frame is in memory.
  host.read32(memory_map::display_regs.base + display_regs::FRAMES);

  const double start = host.now_seconds();
  display.present();
  // Until the last word has reached the port: the read waits for the
  // write buffer to drain.
  const uint32_t frames = host.read32(memory_map::display_regs.base + display_regs::FRAMES);
  const double milliseconds = (host.now_seconds() - start) * 1e3;
  std::printf(
      "display port calibration: host copy of one %ux%u 16-bit frame to the display port: model %.3f ms, measured "
      "%.0f ms (%+.1f%%)\n",
      STUDY_WIDTH, STUDY_HEIGHT, milliseconds, MEASURED_FRAME_COPY_MS,
      (milliseconds / MEASURED_FRAME_COPY_MS - 1) * 100);
  return frames == 1 ? 0 : 1;
}

}  // namespace tessera

namespace tessera {

namespace {

// The operation classes the host-compiled cost model charges one parameter
// each for that are not single instructions (the soft-float operations,
// host.cycles.fadd ..., and a function call with its return,
// host.cycles.call), timed one class at a time over the same loop of table
// lookups, and the loop alone, so that the difference is the operation's
// cost: what the ISS measures for GCC's and the soft-float library's code,
// or what the cost model charges natively.
constexpr unsigned OPERATION_ITERATIONS = 4096, OPERAND_TABLE = 256;

struct Operands {
  float a[OPERAND_TABLE], b[OPERAND_TABLE];
  int32_t i[OPERAND_TABLE];
  Operands() {
    uint32_t state = 0x2545f491u;  // xorshift32: the same operands on every host
    auto next = [&state] {
      state ^= state << 13;
      state ^= state >> 17;
      state ^= state << 5;
      return state;
    };
    // Magnitudes 2^-8 .. 2^12, either sign: a vertex's coordinates, colours
    // and depths, the GL front end's operands.
    for (unsigned k = 0; k < OPERAND_TABLE; ++k) {
      a[k] = std::ldexp(static_cast<float>(next() & 0xffffff) / 16777216.0f + 1.0f, static_cast<int>(next() % 21) - 8) *
             ((next() & 1) != 0 ? -1.0f : 1.0f);
      b[k] = std::ldexp(static_cast<float>(next() & 0xffffff) / 16777216.0f + 1.0f, static_cast<int>(next() % 21) - 8) *
             ((next() & 1) != 0 ? -1.0f : 1.0f);
      i[k] = static_cast<int32_t>(next() >> 12) - (1 << 19);
    }
  }
};

volatile float g_float_sink;
volatile int32_t g_int_sink;

// A function the compiler must call: its body is the store the loop alone
// makes, so the difference is the call, the return and the argument.
__attribute__((noinline)) void store_through_call(int32_t value) {
  g_int_sink = value;
}

// Host seconds of OPERATION_ITERATIONS of `body(k)`; natively, `op` (if
// any) charged once per iteration.
template <typename Body>
double timed_loop(HostApi& host, const std::optional<Op>& op, Body body) {
  const double start = host.now_seconds();
  for (unsigned n = 0; n < OPERATION_ITERATIONS; ++n) {
    body(n % OPERAND_TABLE);
    if (op) host.compute(*op);
    host.compute(Op::alu, 3);  // the loop's index, compare and table address
    host.compute(Op::branch);
  }
  return host.now_seconds() - start;
}

}  // namespace

int calib_operations_app(AppEnvironment& env) {
  HostApi& host = *env.host;
  static const Operands operands;
  const Operands& o = operands;
  const double cycles_per_second = host.clock_hz();
  const double loop = timed_loop(host, std::nullopt, [&](unsigned k) { g_float_sink = o.a[k]; });
  const double int_loop = timed_loop(host, std::nullopt, [&](unsigned k) { g_int_sink = o.i[k]; });
  struct Row {
    const char* name;
    double seconds, baseline;
  };
  const Row rows[] = {
      {"fadd", timed_loop(host, Op::fadd, [&](unsigned k) { g_float_sink = o.a[k] + o.b[k]; }), loop},
      {"fmul", timed_loop(host, Op::fmul, [&](unsigned k) { g_float_sink = o.a[k] * o.b[k]; }), loop},
      {"fdiv", timed_loop(host, Op::fdiv, [&](unsigned k) { g_float_sink = o.a[k] / o.b[k]; }), loop},
      {"fsqrt", timed_loop(host, Op::fsqrt, [&](unsigned k) { g_float_sink = std::sqrt(std::fabs(o.a[k])); }), loop},
      {"fcmp", timed_loop(host, Op::fcmp, [&](unsigned k) { g_int_sink = o.a[k] < o.b[k]; }), int_loop},
      // Conversions both ways, half the iterations each way.
      {"fconv",
       timed_loop(host, Op::fconv,
                  [&](unsigned k) {
                    if (k & 1)
                      g_float_sink = static_cast<float>(o.i[k]);
                    else
                      g_int_sink = static_cast<int32_t>(o.a[k] * 256.0f);
                  }),
       (loop + int_loop) / 2},
      {"call", timed_loop(host, Op::call, [&](unsigned k) { store_through_call(o.i[k]); }), int_loop},
  };
  for (const Row& row : rows)
    std::printf("host calibration: %s: %.1f cycles per operation (host.cycles.%s)\n", row.name,
                (row.seconds - row.baseline) * cycles_per_second / OPERATION_ITERATIONS, row.name);
  return 0;
}

}  // namespace tessera
