// Batch forms of the datapath units: what they share (README.md, "Batch
// forms").
//
// Every unit has, beside its one-call scalar form, a batch form that takes a
// span of pixels (the stepped units: edge function, attribute interpolator)
// or a group of fragments drawn with one state (the others), inputs and
// outputs as arrays of one field each. Its kernel is a plain loop over the
// scalar arithmetic, inline in the unit's header; the loop has no branch
// that depends on a lane and no table indexed per lane but the units' own
// tables, so the compiler vectorises it. The batch entry point, compiled in
// the unit's .cpp, runs that kernel in the widest variant the processor
// has: generic x86-64 (SSE2), x86-64-v3 (AVX2) or x86-64-v4 (AVX-512). The
// variants are the same source compiled for three instruction sets; the
// arithmetic is integer only, so they give the same bits, and the cosim
// tests run every vector through every variant the machine can run.
//
// Why variants at run time rather than -march for the build: soc_sim must
// run on any x86-64, and the build's default flags give SSE2 only, which
// has no 64-bit compare, no variable shift and no 32-bit multiply; the
// AVX-512 variant is about three times as fast as SSE2 on these kernels.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace tessera::raster {

enum class BatchIsa : uint8_t { generic, avx2, avx512 };

std::string_view to_string(BatchIsa isa);

// The widest variant this build has and this processor runs: what the batch
// entry points use unless told otherwise. Decided once.
BatchIsa best_batch_isa();

// Every variant this build has and this processor runs, generic first (for
// the tests and the benchmark).
const std::vector<BatchIsa>& runnable_batch_isas();

namespace batch_detail {

// The variants are built with GCC on x86-64; elsewhere only the generic one.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define TESSERA_BATCH_VARIANTS 1
// Jump threading off: it turns the units' branch-free selects back into
// branches inside the loops, which the vectoriser then refuses.
#define TESSERA_BATCH_OPTIMIZE __attribute__((optimize("no-thread-jumps")))
#define TESSERA_BATCH_TARGET_AVX2 __attribute__((target("arch=x86-64-v3"))) TESSERA_BATCH_OPTIMIZE
#define TESSERA_BATCH_TARGET_AVX512 \
  __attribute__((target("arch=x86-64-v4,prefer-vector-width=256"))) TESSERA_BATCH_OPTIMIZE
#else
#define TESSERA_BATCH_VARIANTS 0
#define TESSERA_BATCH_OPTIMIZE
#define TESSERA_BATCH_TARGET_AVX2
#define TESSERA_BATCH_TARGET_AVX512
#endif

// Kernel::run(args...) compiled for one instruction set. Kernel::run is
// always_inline, so its loop is vectorised for the variant's set; the scalar
// units it calls are inlined into it (an out-of-line copy, if the compiler
// made one, would be the generic one every translation unit shares).
template <class Kernel, class... Args>
TESSERA_BATCH_OPTIMIZE __attribute__((noinline, flatten)) void run_generic(const Args&... args) {
  Kernel::run(args...);
}
#if TESSERA_BATCH_VARIANTS
template <class Kernel, class... Args>
TESSERA_BATCH_TARGET_AVX2 __attribute__((noinline, flatten)) void run_avx2(const Args&... args) {
  Kernel::run(args...);
}
template <class Kernel, class... Args>
TESSERA_BATCH_TARGET_AVX512 __attribute__((noinline, flatten)) void run_avx512(const Args&... args) {
  Kernel::run(args...);
}
#endif

// A variant the processor cannot run falls back to the best it can.
template <class Kernel, class... Args>
void dispatch(BatchIsa isa, const Args&... args) {
#if TESSERA_BATCH_VARIANTS
  if (isa > best_batch_isa()) isa = best_batch_isa();
  if (isa == BatchIsa::avx512) return run_avx512<Kernel, Args...>(args...);
  if (isa == BatchIsa::avx2) return run_avx2<Kernel, Args...>(args...);
#endif
  (void)isa;
  run_generic<Kernel, Args...>(args...);
}

}  // namespace batch_detail

#define TESSERA_BATCH_KERNEL static inline __attribute__((always_inline))

}  // namespace tessera::raster
