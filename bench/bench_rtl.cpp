// bench_rtl: speed of the rasterizer's bit-exact C++ datapath units
// (tlm/raster/datapath/) against their Verilated Verilog twins
// (rtl_models/raster/, through the adapters the cosim tests use), on the
// same vectors. Prints one Markdown table, a row per raster unit of
// rtl_models/units.def in the table's order; bench_raster runs it as a
// child. See README.md for the method.
//
//   bench_rtl [--vectors V] [--pool P] [--batch B] [--rounds R] [--seed S] [--isa NAME]
//
// For each unit, a pool of about P random vectors (default 4096: it stays in
// the caches, as the core's operands do) is generated once, outside the
// timed loops, by the generators the cosim tests draw their random vectors
// from (testbench/cosim/raster_vectors.h), cut into batches of B vectors (default 32, a tile row) that share what the
// core's batches share: a state or a plane, or the row of a span. Three sides sweep the
// pool, each storing every output field of every vector:
//   batch   the unit's batch form (batch.h), one call per batch, the variant
//           --isa names or the widest the processor has: how the raster core
//           calls the unit;
//   scalar  the unit's one-call scalar form, one call per vector, inline;
//   RTL     the adapter, one call per vector: port packing, Verilated eval()
//           (three for the clocked reciprocal unit), unpacking. The RTL has
//           no batch form: its cost per vector is its eval.
// A round times V vectors (whole pool sweeps, a compiler barrier after each)
// on each side; the order of the three sides rotates from round to round, so
// that a change in the machine's load hits each in turn. R rounds: min and
// median ns per vector of each side, and RTL / batch as the ratio of the
// mins and the median of the per-round ratios (the goal column). Times are
// the thread's CPU time (CLOCK_THREAD_CPUTIME_ID), not wall time, so that
// time-slicing on a shared machine does not count. After timing, every
// output field of the pool's results is folded into a checksum per side;
// all three must agree (a cosim run in one number), or bench_rtl exits
// with 1.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <functional>
#include <iostream>
#include <memory>
#include <new>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "attribute_interpolator_adapter.h"
#include "bench_support.h"
#include "blend_logic_op_adapter.h"
#include "cosim/raster_vectors.h"
#include "edge_function_adapter.h"
#include "fog_unit_adapter.h"
#include "fragment_tests_adapter.h"
#include "guarded_main.h"
#include "lod_unit_adapter.h"
#include "raster/datapath/attribute_interpolator.h"
#include "raster/datapath/blend_logic_op.h"
#include "raster/datapath/edge_function.h"
#include "raster/datapath/fog_unit.h"
#include "raster/datapath/fragment_tests.h"
#include "raster/datapath/lod_unit.h"
#include "raster/datapath/reciprocal.h"
#include "raster/datapath/texel_address.h"
#include "raster/datapath/texture_combiner.h"
#include "raster/datapath/texture_env.h"
#include "reciprocal_adapter.h"
#include "texel_address_adapter.h"
#include "texture_combiner_adapter.h"
#include "texture_env_adapter.h"

namespace {

using namespace tessera::raster;
using tessera::FogMode;
using tessera::TexEnv;
using tessera::bench::load_average;
using tessera::bench::machine_summary;
using tessera::bench::min_median;
using tessera::bench::MinMedian;

struct Options {
  uint64_t vectors = 1'000'000;
  uint64_t pool = 4096;
  unsigned batch = 32;
  unsigned rounds = 15;
  uint64_t seed = 0xbe4c4;
  std::string isa;  // empty: the widest the processor has
};

// ---------------------------------------------------------------------------
// Checksums: an order-dependent fold of every output field (FNV-1a step on a
// whole word). The batch side folds its arrays lane by lane in the same
// order as the scalar and RTL sides fold their result structs.

inline uint64_t fold(uint64_t sum, uint64_t field) {
  return (sum ^ field) * 0x100000001b3ull;
}

uint64_t fold(uint64_t sum, const ReciprocalResult& r) {
  sum = fold(sum, r.q5_16);
  sum = fold(sum, r.invalid_operand);
  sum = fold(sum, r.mantissa);
  return fold(sum, r.exponent_field());
}

uint64_t fold(uint64_t sum, const EdgeEvaluation& r) {
  sum = fold(sum, static_cast<uint64_t>(r.value.raw));
  sum = fold(sum, static_cast<uint64_t>(r.value_next_x.raw));
  sum = fold(sum, static_cast<uint64_t>(r.value_next_y.raw));
  sum = fold(sum, r.inside);
  sum = fold(sum, r.l1_length.raw);
  sum = fold(sum, static_cast<uint64_t>(r.distance.raw));
  return fold(sum, r.coverage.raw);
}

uint64_t fold(uint64_t sum, const AttributeEvaluation& r) {
  sum = fold(sum, static_cast<uint64_t>(r.value.raw));
  sum = fold(sum, static_cast<uint64_t>(r.value_next_x.raw));
  sum = fold(sum, static_cast<uint64_t>(r.value_next_y.raw));
  return fold(sum, r.output);
}

uint64_t fragment_flags(const FragmentTestResult& r) {
  return (r.alpha_pass ? FRAGMENT_ALPHA_PASS : 0) | (r.stencil_pass ? FRAGMENT_STENCIL_PASS : 0) |
         (r.depth_pass ? FRAGMENT_DEPTH_PASS : 0) | (r.pass ? FRAGMENT_PASS : 0) |
         (r.depth_write ? FRAGMENT_DEPTH_WRITE : 0);
}

uint64_t fold(uint64_t sum, const FragmentTestResult& r) {
  return fold(fold(sum, fragment_flags(r)), r.stencil.raw);
}

uint64_t fold(uint64_t sum, const TexelFootprint& r) {
  sum = fold(sum, uint64_t{r.s.index0} | uint64_t{r.s.index1} << 8 | uint64_t{r.s.weight} << 16);
  sum = fold(sum, uint64_t{r.t.index0} | uint64_t{r.t.index1} << 8 | uint64_t{r.t.weight} << 16);
  for (uint32_t address : r.address) sum = fold(sum, address);
  return sum;
}

uint64_t fold(uint64_t sum, const TextureEnvResult& r) {
  return fold(sum, uint64_t{r.texel.pack()} | uint64_t{r.fragment.pack()} << 32);
}

uint64_t fold(uint64_t sum, Rgba8 r) {
  return fold(sum, r.pack());
}

uint64_t fold(uint64_t sum, const FogUnitResult& r) {
  return fold(sum, uint64_t{r.color.pack()} | uint64_t{r.factor} << 32);
}

uint64_t lod_flags(const LodResult& r) {
  return (r.minified ? LOD_MINIFIED : 0) | (r.linear ? LOD_LINEAR : 0) | (r.two_levels ? LOD_TWO_LEVELS : 0);
}

uint64_t fold(uint64_t sum, const LodResult& r) {
  sum = fold(sum, static_cast<uint64_t>(int64_t{r.lambda}));
  sum = fold(sum, lod_flags(r));
  return fold(sum, uint64_t{r.level[0]} | uint64_t{r.level[1]} << 8 | uint64_t{r.weight} << 16);
}

template <class Result>
uint64_t checksum(const std::vector<Result>& results) {
  uint64_t sum = 0;
  for (const Result& r : results) sum = fold(sum, r);
  return sum;
}

// ---------------------------------------------------------------------------
// Timing.

// Stops the compiler from merging or dropping sweeps: every store before it
// happens, every load after it reads memory again.
inline void compiler_barrier(const void* p) {
  asm volatile("" : : "r"(p) : "memory");
}

// The CPU time of this thread: unlike the wall time it does not count the
// time the thread waited for a core, so a loaded machine (other processes
// time-sliced with this one) inflates it far less.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// A pool of vectors cut into batches: batch b is lanes first[b] .. first[b]
// + count[b] - 1 of the pool's arrays.
struct Batches {
  std::vector<uint32_t> first, count;
  uint32_t lanes = 0;

  Batches(uint64_t pool, unsigned batch) {
    while (lanes < pool) {
      first.push_back(lanes);
      count.push_back(batch);
      lanes += batch;
    }
  }
  size_t size() const { return first.size(); }
};

// One side of a unit's measurement: a sweep over the whole pool, storing
// every output, and the checksum of the last sweep's outputs.
struct Side {
  std::function<void()> sweep;
  std::function<uint64_t()> checksum;
};

// The sides' indices in Unit::side and UnitResult.
constexpr unsigned BATCH = 0, SCALAR = 1, RTL = 2, SIDES = 3;

struct Unit {
  uint64_t lanes = 0;  // vectors per sweep
  Side side[SIDES];
};

// The scalar and RTL sides store results constructed in place: an assignment
// would build each result in a temporary on the stack and copy it, which
// costs a store-forwarding stall per result, more than a unit itself.
template <class Result, class Make>
void store(std::vector<Result>& out, size_t i, Make&& make) {
  static_assert(std::is_trivially_destructible_v<Result>, "results are overwritten in place");
  ::new (static_cast<void*>(out.data() + i)) Result(make());
}

// ---------------------------------------------------------------------------
// The units, bench_<name> for each raster unit of rtl_models/units.def. Each
// builds its pool (testbench/cosim/raster_vectors.h, the generators of the
// cosim tests' random vectors, in batches sharing a state) and its three
// sides over it.

Unit bench_reciprocal(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<uint32_t> x;
    std::vector<uint32_t> q5_16, mantissa, invalid;
    std::vector<int32_t> exponent;
    std::vector<ReciprocalResult> scalar, rtl_out;
    ReciprocalRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  p->x.resize(n);
  for (auto& x : p->x) x = random_reciprocal_operand(rng);
  p->q5_16.resize(n);
  p->mantissa.resize(n);
  p->invalid.resize(n);
  p->exponent.resize(n);
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH] = {[p, isa] {
                     for (size_t b = 0; b < p->batches.size(); ++b) {
                       const uint32_t f = p->batches.first[b];
                       reciprocal_method3_batch(
                           p->x.data() + f, p->batches.count[b],
                           {p->q5_16.data() + f, p->mantissa.data() + f, p->exponent.data() + f, p->invalid.data() + f},
                           isa);
                     }
                     compiler_barrier(p->q5_16.data());
                   },
                   [p] {
                     uint64_t sum = 0;
                     for (size_t i = 0; i < p->x.size(); ++i) {
                       sum = fold(sum, p->q5_16[i]);
                       sum = fold(sum, p->invalid[i]);
                       sum = fold(sum, p->mantissa[i]);
                       sum = fold(sum, static_cast<uint32_t>(p->exponent[i]) & ((1u << RECIP_EXPONENT_BITS) - 1));
                     }
                     return sum;
                   }};
  u.side[SCALAR] = {[p] {
                      for (size_t i = 0; i < p->x.size(); ++i)
                        store(p->scalar, i,
                              [&] { return reciprocal(static_cast<uint16_t>(p->x[i]), RecipMethod::method3); });
                      compiler_barrier(p->scalar.data());
                    },
                    [p] { return checksum(p->scalar); }};
  u.side[RTL] = {[p] {
                   for (size_t i = 0; i < p->x.size(); ++i)
                     store(p->rtl_out, i, [&] { return p->rtl.evaluate(static_cast<uint16_t>(p->x[i])); });
                   compiler_barrier(p->rtl_out.data());
                 },
                 [p] { return checksum(p->rtl_out); }};
  return u;
}

Unit bench_edge_function(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<EdgeSpanVector> spans;
    std::vector<int32_t> value, value_next_y, distance;
    std::vector<uint32_t> inside, coverage, l1;
    std::vector<EdgeEvaluation> scalar, rtl_out;
    EdgeFunctionRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  for (size_t b = 0; b < p->batches.size(); ++b) p->spans.push_back(random_edge_span(rng, p->batches.count[b]));
  p->value.resize(n + p->batches.size());  // count + 1 values a span
  p->value_next_y.resize(n);
  p->distance.resize(n);
  p->inside.resize(n);
  p->coverage.resize(n);
  p->l1.resize(p->batches.size());
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH] = {[p, isa] {
                     for (size_t b = 0; b < p->batches.size(); ++b) {
                       const uint32_t f = p->batches.first[b];
                       const EdgeSpanVector& s = p->spans[b];
                       p->l1[b] = edge_span(s.edge, s.px, s.py, p->batches.count[b], s.recip,
                                            {p->value.data() + f + b, p->value_next_y.data() + f, p->inside.data() + f,
                                             p->distance.data() + f, p->coverage.data() + f},
                                            isa)
                                      .raw;
                     }
                     compiler_barrier(p->value.data());
                   },
                   [p] {
                     uint64_t sum = 0;
                     for (size_t b = 0; b < p->batches.size(); ++b)
                       for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                         const uint32_t i = p->batches.first[b] + k;
                         sum = fold(sum, static_cast<uint64_t>(int64_t{p->value[i + b]}));
                         sum = fold(sum, static_cast<uint64_t>(int64_t{p->value[i + b + 1]}));
                         sum = fold(sum, static_cast<uint64_t>(int64_t{p->value_next_y[i]}));
                         sum = fold(sum, p->inside[i]);
                         sum = fold(sum, p->l1[b]);
                         sum = fold(sum, static_cast<uint64_t>(int64_t{p->distance[i]}));
                         sum = fold(sum, p->coverage[i]);
                       }
                     return sum;
                   }};
  u.side[SCALAR] = {[p] {
                      for (size_t b = 0; b < p->batches.size(); ++b) {
                        const EdgeSpanVector& s = p->spans[b];
                        for (uint32_t k = 0; k < p->batches.count[b]; ++k)
                          store(p->scalar, p->batches.first[b] + k,
                                [&] { return evaluate_edge(s.edge, s.px + k, s.py, s.recip); });
                      }
                      compiler_barrier(p->scalar.data());
                    },
                    [p] { return checksum(p->scalar); }};
  u.side[RTL] = {[p] {
                   for (size_t b = 0; b < p->batches.size(); ++b) {
                     const EdgeSpanVector& s = p->spans[b];
                     for (uint32_t k = 0; k < p->batches.count[b]; ++k)
                       store(p->rtl_out, p->batches.first[b] + k,
                             [&] { return p->rtl.evaluate(s.edge, s.px + k, s.py, s.recip); });
                   }
                   compiler_barrier(p->rtl_out.data());
                 },
                 [p] { return checksum(p->rtl_out); }};
  return u;
}

Unit bench_attribute_interpolator(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<AttributePlane> planes;
    std::vector<int32_t> dx, dy;
    std::vector<int64_t> value, value_next_x, value_next_y;
    std::vector<uint32_t> output;
    std::vector<AttributeEvaluation> scalar, rtl_out;
    AttributeInterpolatorRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  for (auto* v : {&p->dx, &p->dy}) v->resize(n);
  for (auto* v : {&p->value, &p->value_next_x, &p->value_next_y}) v->resize(n);
  p->output.resize(n);
  for (size_t b = 0; b < p->batches.size(); ++b) {
    p->planes.push_back(random_attribute_plane(rng));
    for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
      const PixelOffset o = random_pixel_offset(rng);
      p->dx[p->batches.first[b] + k] = o.dx;
      p->dy[p->batches.first[b] + k] = o.dy;
    }
  }
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH] = {
      [p, isa] {
        for (size_t b = 0; b < p->batches.size(); ++b) {
          const uint32_t f = p->batches.first[b];
          attribute_batch(
              p->planes[b], p->dx.data() + f, p->dy.data() + f, p->batches.count[b],
              {p->value.data() + f, p->value_next_x.data() + f, p->value_next_y.data() + f, p->output.data() + f}, isa);
        }
        compiler_barrier(p->value.data());
      },
      [p] {
        uint64_t sum = 0;
        for (uint32_t i = 0; i < p->dx.size(); ++i) {
          sum = fold(sum, static_cast<uint64_t>(p->value[i]));
          sum = fold(sum, static_cast<uint64_t>(p->value_next_x[i]));
          sum = fold(sum, static_cast<uint64_t>(p->value_next_y[i]));
          sum = fold(sum, p->output[i]);
        }
        return sum;
      }};
  u.side[SCALAR] = {[p] {
                      for (size_t b = 0; b < p->batches.size(); ++b)
                        for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                          const uint32_t i = p->batches.first[b] + k;
                          store(p->scalar, i, [&] { return evaluate_attribute(p->planes[b], p->dx[i], p->dy[i]); });
                        }
                      compiler_barrier(p->scalar.data());
                    },
                    [p] { return checksum(p->scalar); }};
  u.side[RTL] = {[p] {
                   for (size_t b = 0; b < p->batches.size(); ++b)
                     for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                       const uint32_t i = p->batches.first[b] + k;
                       store(p->rtl_out, i, [&] { return p->rtl.evaluate(p->planes[b], p->dx[i], p->dy[i]); });
                     }
                   compiler_barrier(p->rtl_out.data());
                 },
                 [p] { return checksum(p->rtl_out); }};
  return u;
}

Unit bench_fragment_tests(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<FragmentTestState> states;
    std::vector<uint32_t> alpha, depth, stored_depth, stored_stencil, flags, stencil;
    std::vector<FragmentTestResult> scalar, rtl_out;
    FragmentTestsRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
    FragmentTestInput input(size_t i) const {
      return {unorm8::from_raw(alpha[i]), unorm24::from_raw(depth[i]), unorm24::from_raw(stored_depth[i]),
              stencil8::from_raw(stored_stencil[i])};
    }
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  for (auto* v : {&p->alpha, &p->depth, &p->stored_depth, &p->stored_stencil, &p->flags, &p->stencil}) v->resize(n);
  for (size_t b = 0; b < p->batches.size(); ++b) {
    const FragmentTestState s = random_fragment_test_state(rng);
    p->states.push_back(s);
    for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
      const uint32_t i = p->batches.first[b] + k;
      const FragmentTestInput f = random_fragment(rng, s);
      p->alpha[i] = f.alpha.raw;
      p->stored_stencil[i] = f.stored_stencil.raw;
      p->depth[i] = f.depth.raw;
      p->stored_depth[i] = f.stored_depth.raw;
    }
  }
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH] = {[p, isa] {
                     for (size_t b = 0; b < p->batches.size(); ++b) {
                       const uint32_t f = p->batches.first[b];
                       run_fragment_tests_batch(p->states[b],
                                                {p->alpha.data() + f, p->depth.data() + f, p->stored_depth.data() + f,
                                                 p->stored_stencil.data() + f},
                                                p->batches.count[b], {p->flags.data() + f, p->stencil.data() + f}, isa);
                     }
                     compiler_barrier(p->flags.data());
                   },
                   [p] {
                     uint64_t sum = 0;
                     for (uint32_t i = 0; i < p->flags.size(); ++i) sum = fold(fold(sum, p->flags[i]), p->stencil[i]);
                     return sum;
                   }};
  u.side[SCALAR] = {[p] {
                      for (size_t b = 0; b < p->batches.size(); ++b)
                        for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                          const uint32_t i = p->batches.first[b] + k;
                          store(p->scalar, i, [&] { return run_fragment_tests(p->states[b], p->input(i)); });
                        }
                      compiler_barrier(p->scalar.data());
                    },
                    [p] { return checksum(p->scalar); }};
  u.side[RTL] = {[p] {
                   for (size_t b = 0; b < p->batches.size(); ++b)
                     for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                       const uint32_t i = p->batches.first[b] + k;
                       store(p->rtl_out, i, [&] { return p->rtl.run(p->states[b], p->input(i)); });
                     }
                   compiler_barrier(p->rtl_out.data());
                 },
                 [p] { return checksum(p->rtl_out); }};
  return u;
}

// The sides of a unit whose result is one packed colour per vector (blend,
// combiner): the batch writes `out`, scalar and RTL their Rgba8 arrays.
template <class Pool>
void colour_checksums(Unit& u, const std::shared_ptr<Pool>& p) {
  u.side[BATCH].checksum = [p] {
    uint64_t sum = 0;
    for (uint32_t c : p->out) sum = fold(sum, c);
    return sum;
  };
  u.side[SCALAR].checksum = [p] { return checksum(p->scalar); };
  u.side[RTL].checksum = [p] { return checksum(p->rtl_out); };
}

Unit bench_blend_logic_op(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<BlendState> states;
    std::vector<uint32_t> src, dst, out;
    std::vector<Rgba8> scalar, rtl_out;
    BlendLogicOpRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  p->src.resize(n);
  p->dst.resize(n);
  p->out.resize(n);
  for (size_t b = 0; b < p->batches.size(); ++b) {
    p->states.push_back(random_blend_state(rng));
    for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
      const ColourPair pair = random_colour_pair(rng);
      p->src[p->batches.first[b] + k] = pair.src;
      p->dst[p->batches.first[b] + k] = pair.dst;
    }
  }
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH].sweep = [p, isa] {
    for (size_t b = 0; b < p->batches.size(); ++b) {
      const uint32_t f = p->batches.first[b];
      blend_logic_op_batch(p->states[b], p->src.data() + f, p->dst.data() + f, p->batches.count[b], p->out.data() + f,
                           isa);
    }
    compiler_barrier(p->out.data());
  };
  u.side[SCALAR].sweep = [p] {
    for (size_t b = 0; b < p->batches.size(); ++b)
      for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
        const uint32_t i = p->batches.first[b] + k;
        store(p->scalar, i,
              [&] { return blend_logic_op(p->states[b], Rgba8::unpack(p->src[i]), Rgba8::unpack(p->dst[i])); });
      }
    compiler_barrier(p->scalar.data());
  };
  u.side[RTL].sweep = [p] {
    for (size_t b = 0; b < p->batches.size(); ++b)
      for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
        const uint32_t i = p->batches.first[b] + k;
        store(p->rtl_out, i,
              [&] { return p->rtl.run(p->states[b], Rgba8::unpack(p->src[i]), Rgba8::unpack(p->dst[i])); });
      }
    compiler_barrier(p->rtl_out.data());
  };
  colour_checksums(u, p);
  return u;
}

Unit bench_texel_address(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<TextureState> states;
    std::vector<int32_t> s, t;
    std::vector<uint32_t> field[10];
    std::vector<TexelFootprint> scalar, rtl_out;
    TexelAddressRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  p->s.resize(n);
  p->t.resize(n);
  for (auto& f : p->field) f.resize(n);
  for (size_t b = 0; b < p->batches.size(); ++b) {
    p->states.push_back(random_texture_state(rng));
    for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
      const TexCoords coords = random_tex_coords(rng);
      p->s[p->batches.first[b] + k] = coords.s;
      p->t[p->batches.first[b] + k] = coords.t;
    }
  }
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH] = {
      [p, isa] {
        for (size_t b = 0; b < p->batches.size(); ++b) {
          const uint32_t f = p->batches.first[b];
          auto at = [&](unsigned k) { return p->field[k].data() + f; };
          texel_lookup_batch(p->states[b], p->s.data() + f, p->t.data() + f, p->batches.count[b],
                             {at(0), at(1), at(2), at(3), at(4), at(5), {at(6), at(7), at(8), at(9)}}, isa);
        }
        compiler_barrier(p->field[0].data());
      },
      [p] {
        uint64_t sum = 0;
        for (uint32_t i = 0; i < p->s.size(); ++i) {
          sum = fold(sum, uint64_t{p->field[0][i]} | uint64_t{p->field[1][i]} << 8 | uint64_t{p->field[2][i]} << 16);
          sum = fold(sum, uint64_t{p->field[3][i]} | uint64_t{p->field[4][i]} << 8 | uint64_t{p->field[5][i]} << 16);
          for (unsigned k = 6; k < 10; ++k) sum = fold(sum, p->field[k][i]);
        }
        return sum;
      }};
  u.side[SCALAR] = {[p] {
                      for (size_t b = 0; b < p->batches.size(); ++b)
                        for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                          const uint32_t i = p->batches.first[b] + k;
                          store(p->scalar, i,
                                [&] { return texel_lookup(p->states[b], q15_16{p->s[i]}, q15_16{p->t[i]}); });
                        }
                      compiler_barrier(p->scalar.data());
                    },
                    [p] { return checksum(p->scalar); }};
  u.side[RTL] = {[p] {
                   for (size_t b = 0; b < p->batches.size(); ++b)
                     for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                       const uint32_t i = p->batches.first[b] + k;
                       store(p->rtl_out, i,
                             [&] { return p->rtl.lookup(p->states[b], q15_16{p->s[i]}, q15_16{p->t[i]}); });
                     }
                   compiler_barrier(p->rtl_out.data());
                 },
                 [p] { return checksum(p->rtl_out); }};
  return u;
}

Unit bench_texture_env(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<TexEnv> modes;
    std::vector<uint32_t> texel[4], weight_s, weight_t, fragment, texel_out, fragment_out;
    std::vector<TextureEnvResult> scalar, rtl_out;
    TextureEnvRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
    std::array<Rgba8, 4> texels(size_t i) const {
      return {Rgba8::unpack(texel[0][i]), Rgba8::unpack(texel[1][i]), Rgba8::unpack(texel[2][i]),
              Rgba8::unpack(texel[3][i])};
    }
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  for (auto& t : p->texel) t.resize(n);
  for (auto* v : {&p->weight_s, &p->weight_t, &p->fragment, &p->texel_out, &p->fragment_out}) v->resize(n);
  for (size_t b = 0; b < p->batches.size(); ++b) {
    p->modes.push_back(random_texture_env_mode(rng));
    for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
      const uint32_t i = p->batches.first[b] + k;
      const TextureEnvLane lane = random_texture_env_lane(rng);
      for (unsigned j = 0; j < 4; ++j) p->texel[j][i] = lane.texel[j];
      p->weight_s[i] = lane.weight_s;
      p->weight_t[i] = lane.weight_t;
      p->fragment[i] = lane.fragment;
    }
  }
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH] = {
      [p, isa] {
        for (size_t b = 0; b < p->batches.size(); ++b) {
          const uint32_t f = p->batches.first[b];
          texture_filter_env_batch(
              p->modes[b],
              {{p->texel[0].data() + f, p->texel[1].data() + f, p->texel[2].data() + f, p->texel[3].data() + f},
               p->weight_s.data() + f,
               p->weight_t.data() + f,
               p->fragment.data() + f},
              p->batches.count[b], {p->texel_out.data() + f, p->fragment_out.data() + f}, isa);
        }
        compiler_barrier(p->texel_out.data());
      },
      [p] {
        uint64_t sum = 0;
        for (uint32_t i = 0; i < p->texel_out.size(); ++i)
          sum = fold(sum, uint64_t{p->texel_out[i]} | uint64_t{p->fragment_out[i]} << 32);
        return sum;
      }};
  u.side[SCALAR] = {[p] {
                      for (size_t b = 0; b < p->batches.size(); ++b)
                        for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                          const uint32_t i = p->batches.first[b] + k;
                          store(p->scalar, i, [&] {
                            return texture_filter_env(p->modes[b], p->texels(i), static_cast<uint8_t>(p->weight_s[i]),
                                                      static_cast<uint8_t>(p->weight_t[i]),
                                                      Rgba8::unpack(p->fragment[i]));
                          });
                        }
                      compiler_barrier(p->scalar.data());
                    },
                    [p] { return checksum(p->scalar); }};
  u.side[RTL] = {[p] {
                   for (size_t b = 0; b < p->batches.size(); ++b)
                     for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                       const uint32_t i = p->batches.first[b] + k;
                       store(p->rtl_out, i, [&] {
                         return p->rtl.run(p->modes[b], p->texels(i), static_cast<uint8_t>(p->weight_s[i]),
                                           static_cast<uint8_t>(p->weight_t[i]), Rgba8::unpack(p->fragment[i]));
                       });
                     }
                   compiler_barrier(p->rtl_out.data());
                 },
                 [p] { return checksum(p->rtl_out); }};
  return u;
}

Unit bench_fog_unit(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<FogMode> modes;
    std::vector<Rgba8> fog_colors;
    std::vector<int32_t> argument;
    std::vector<uint32_t> fragment, factor, color;
    std::vector<FogUnitResult> scalar, rtl_out;
    FogUnitRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  p->argument.resize(n);
  for (auto* v : {&p->fragment, &p->factor, &p->color}) v->resize(n);
  for (size_t b = 0; b < p->batches.size(); ++b) {
    const FogUnitState state = random_fog_state(rng);
    p->modes.push_back(state.mode);
    p->fog_colors.push_back(state.colour);
    for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
      const uint32_t i = p->batches.first[b] + k;
      const FogLane lane = random_fog_lane(rng);
      p->argument[i] = lane.argument;
      p->fragment[i] = lane.fragment;
    }
  }
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH] = {[p, isa] {
                     for (size_t b = 0; b < p->batches.size(); ++b) {
                       const uint32_t f = p->batches.first[b];
                       fog_unit_batch(p->modes[b], p->fog_colors[b], p->argument.data() + f, p->fragment.data() + f,
                                      p->batches.count[b], {p->factor.data() + f, p->color.data() + f}, isa);
                     }
                     compiler_barrier(p->color.data());
                   },
                   [p] {
                     uint64_t sum = 0;
                     for (uint32_t i = 0; i < p->color.size(); ++i)
                       sum = fold(sum, uint64_t{p->color[i]} | uint64_t{p->factor[i]} << 32);
                     return sum;
                   }};
  u.side[SCALAR] = {[p] {
                      for (size_t b = 0; b < p->batches.size(); ++b)
                        for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                          const uint32_t i = p->batches.first[b] + k;
                          store(p->scalar, i, [&] {
                            return fog_unit(p->modes[b], p->argument[i], Rgba8::unpack(p->fragment[i]),
                                            p->fog_colors[b]);
                          });
                        }
                      compiler_barrier(p->scalar.data());
                    },
                    [p] { return checksum(p->scalar); }};
  u.side[RTL] = {[p] {
                   for (size_t b = 0; b < p->batches.size(); ++b)
                     for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                       const uint32_t i = p->batches.first[b] + k;
                       store(p->rtl_out, i, [&] {
                         return p->rtl.run(p->modes[b], p->argument[i], Rgba8::unpack(p->fragment[i]),
                                           p->fog_colors[b]);
                       });
                     }
                   compiler_barrier(p->rtl_out.data());
                 },
                 [p] { return checksum(p->rtl_out); }};
  return u;
}

Unit bench_lod_unit(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct Pool {
    Batches batches;
    std::vector<LodState> states;
    std::vector<uint32_t> rho, flags, level0, level1, weight;
    std::vector<int32_t> lambda;
    std::vector<LodResult> scalar, rtl_out;
    LodUnitRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  p->lambda.resize(n);
  for (auto* v : {&p->rho, &p->flags, &p->level0, &p->level1, &p->weight}) v->resize(n);
  for (size_t b = 0; b < p->batches.size(); ++b) {
    p->states.push_back(random_lod_state(rng));
    for (uint32_t k = 0; k < p->batches.count[b]; ++k) p->rho[p->batches.first[b] + k] = random_lod_rho(rng);
  }
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH] = {[p, isa] {
                     for (size_t b = 0; b < p->batches.size(); ++b) {
                       const uint32_t f = p->batches.first[b];
                       const LodState& s = p->states[b];
                       lod_unit_batch(s.min, s.mag, s.mipmap, s.last_level, p->rho.data() + f, p->batches.count[b],
                                      {p->lambda.data() + f, p->flags.data() + f, p->level0.data() + f,
                                       p->level1.data() + f, p->weight.data() + f},
                                      isa);
                     }
                     compiler_barrier(p->lambda.data());
                   },
                   [p] {
                     uint64_t sum = 0;
                     for (uint32_t i = 0; i < p->rho.size(); ++i) {
                       sum = fold(sum, static_cast<uint64_t>(int64_t{p->lambda[i]}));
                       sum = fold(sum, p->flags[i]);
                       sum = fold(sum,
                                  uint64_t{p->level0[i]} | uint64_t{p->level1[i]} << 8 | uint64_t{p->weight[i]} << 16);
                     }
                     return sum;
                   }};
  u.side[SCALAR] = {[p] {
                      for (size_t b = 0; b < p->batches.size(); ++b) {
                        const LodState& s = p->states[b];
                        for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                          const uint32_t i = p->batches.first[b] + k;
                          store(p->scalar, i,
                                [&] { return lod_unit(p->rho[i], s.min, s.mag, s.mipmap, s.last_level); });
                        }
                      }
                      compiler_barrier(p->scalar.data());
                    },
                    [p] { return checksum(p->scalar); }};
  u.side[RTL] = {[p] {
                   for (size_t b = 0; b < p->batches.size(); ++b) {
                     const LodState& s = p->states[b];
                     for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
                       const uint32_t i = p->batches.first[b] + k;
                       store(p->rtl_out, i,
                             [&] { return p->rtl.run(p->rho[i], s.min, s.mag, s.mipmap, s.last_level); });
                     }
                   }
                   compiler_barrier(p->rtl_out.data());
                 },
                 [p] { return checksum(p->rtl_out); }};
  return u;
}

Unit bench_texture_combiner(VectorRng& rng, const Options& opt, BatchIsa isa) {
  struct State {
    CombinerState ports;  // as the RTL takes it
    TextureUnitEnv unit;  // as the C++ twin takes it
  };
  struct Pool {
    Batches batches;
    std::vector<State> states;
    std::vector<uint32_t> primary, previous, texel, out;
    std::vector<Rgba8> scalar, rtl_out;
    TextureCombinerRtl rtl;
    explicit Pool(const Options& o) : batches(o.pool, o.batch) {}
  };
  auto p = std::make_shared<Pool>(opt);
  const uint32_t n = p->batches.lanes;
  for (auto* v : {&p->primary, &p->previous, &p->texel, &p->out}) v->resize(n);
  for (size_t b = 0; b < p->batches.size(); ++b) {
    const CombinerState ports = random_combiner_state(rng);
    p->states.push_back({ports, ports.unit()});
    for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
      const uint32_t i = p->batches.first[b] + k;
      const CombinerLane lane = random_combiner_lane(rng);
      p->primary[i] = lane.primary;
      p->previous[i] = lane.previous;
      p->texel[i] = lane.texel;
    }
  }
  p->scalar.resize(n);
  p->rtl_out.resize(n);
  Unit u{n, {}};
  u.side[BATCH].sweep = [p, isa] {
    for (size_t b = 0; b < p->batches.size(); ++b) {
      const uint32_t f = p->batches.first[b];
      texture_combiner_batch(p->states[b].unit, p->primary.data() + f, p->previous.data() + f, p->texel.data() + f,
                             p->batches.count[b], p->out.data() + f, isa);
    }
    compiler_barrier(p->out.data());
  };
  u.side[SCALAR].sweep = [p] {
    for (size_t b = 0; b < p->batches.size(); ++b)
      for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
        const uint32_t i = p->batches.first[b] + k;
        store(p->scalar, i, [&] {
          return texture_combiner(p->states[b].unit, Rgba8::unpack(p->primary[i]), Rgba8::unpack(p->previous[i]),
                                  Rgba8::unpack(p->texel[i]));
        });
      }
    compiler_barrier(p->scalar.data());
  };
  u.side[RTL].sweep = [p] {
    for (size_t b = 0; b < p->batches.size(); ++b) {
      const State& s = p->states[b];
      for (uint32_t k = 0; k < p->batches.count[b]; ++k) {
        const uint32_t i = p->batches.first[b] + k;
        store(p->rtl_out, i, [&] {
          return p->rtl.run(s.unit.env, s.unit.base_format, Rgba8::unpack(p->primary[i]), Rgba8::unpack(p->previous[i]),
                            Rgba8::unpack(p->texel[i]), s.unit.env_color, s.ports.rgb_word, s.ports.alpha_word);
        });
      }
    }
    compiler_barrier(p->rtl_out.data());
  };
  colour_checksums(u, p);
  return u;
}

// The units bench_rtl measures: every raster unit of rtl_models/units.def,
// in the table's order, each by its bench_<name> above (a raster unit added
// to the table without one does not compile). The array's CU has a
// benchmark of its own, bench_cu_rtl.
struct BenchedUnit {
  const char* name;
  Unit (*make)(VectorRng& rng, const Options& opt, BatchIsa isa);
};

const BenchedUnit BENCHED_UNITS[] = {
#define TESSERA_RTL_UNIT_IN_raster(name) {#name, bench_##name},
#define TESSERA_RTL_UNIT_IN_array(name)
#define TESSERA_RTL_UNIT(name, folder, ...) TESSERA_RTL_UNIT_IN_##folder(name)
#include "units.def"
#undef TESSERA_RTL_UNIT
#undef TESSERA_RTL_UNIT_IN_array
#undef TESSERA_RTL_UNIT_IN_raster
};

// ---------------------------------------------------------------------------

struct UnitResult {
  std::string name;
  std::vector<double> ns[SIDES];  // per round
  std::vector<double> ratio;      // RTL / batch, per round
  uint64_t checksum[SIDES] = {};
};

// R rounds of whole sweeps over the pool, the three sides in an order that
// rotates from round to round.
UnitResult measure(const char* name, Unit& u, const Options& opt) {
  std::fprintf(stderr, "bench_rtl: %s ...\n", name);
  UnitResult result;
  result.name = name;
  const uint64_t sweeps = std::max<uint64_t>(1, (opt.vectors + u.lanes - 1) / u.lanes);
  const double vectors = static_cast<double>(sweeps * u.lanes);
  for (Side& side : u.side) side.sweep();  // warm-up, not counted
  for (unsigned r = 0; r < opt.rounds; ++r) {
    double seconds[SIDES] = {};
    for (unsigned k = 0; k < SIDES; ++k) {
      const unsigned s = (r + k) % SIDES;
      const double start = thread_cpu_seconds();
      for (uint64_t i = 0; i < sweeps; ++i) u.side[s].sweep();
      seconds[s] = thread_cpu_seconds() - start;
    }
    for (unsigned s = 0; s < SIDES; ++s) result.ns[s].push_back(seconds[s] / vectors * 1e9);
    result.ratio.push_back(seconds[RTL] / seconds[BATCH]);
  }
  for (unsigned s = 0; s < SIDES; ++s) result.checksum[s] = u.side[s].checksum();
  return result;
}

std::string format_ns(double ns) {
  char text[32];
  std::snprintf(text, sizeof text, ns < 1 ? "%.3f" : ns < 10 ? "%.2f" : "%.1f", ns);
  return text;
}

int run(const Options& opt) {
  BatchIsa isa = best_batch_isa();
  if (!opt.isa.empty()) {
    bool found = false;
    for (BatchIsa candidate : runnable_batch_isas())
      if (to_string(candidate) == opt.isa) {
        isa = candidate;
        found = true;
      }
    if (!found) {
      std::cerr << "bench_rtl: --isa " << opt.isa << ": not a batch variant this build has and this processor runs (";
      for (BatchIsa candidate : runnable_batch_isas()) std::cerr << " " << to_string(candidate);
      std::cerr << " )\n";
      return 2;
    }
  }
  const std::string load_before = load_average();
  const auto start = std::chrono::steady_clock::now();
  VectorRng rng(opt.seed);
  std::vector<UnitResult> results;
  for (const BenchedUnit& unit : BENCHED_UNITS) {
    Unit u = unit.make(rng, opt, isa);
    results.push_back(measure(unit.name, u, opt));
  }

  std::printf(
      "| unit | C++ batch ns/op (min) | (median) | scalar ns/op (median) | RTL ns/op (min) | (median) "
      "| RTL / batch (mins) | (median of rounds) | goal >= 50 | checksum (all three) |\n");
  std::printf("|---|--:|--:|--:|--:|--:|--:|--:|---|---|\n");
  bool all_agree = true;
  for (const auto& r : results) {
    const bool agree = r.checksum[BATCH] == r.checksum[RTL] && r.checksum[SCALAR] == r.checksum[RTL];
    all_agree = all_agree && agree;
    char sum[96];
    if (agree)
      std::snprintf(sum, sizeof sum, "%016llx", static_cast<unsigned long long>(r.checksum[RTL]));
    else
      std::snprintf(
          sum, sizeof sum, "DIFFER: %016llx / %016llx / %016llx", static_cast<unsigned long long>(r.checksum[BATCH]),
          static_cast<unsigned long long>(r.checksum[SCALAR]), static_cast<unsigned long long>(r.checksum[RTL]));
    const MinMedian batch = min_median(r.ns[BATCH]), scalar = min_median(r.ns[SCALAR]), rtl = min_median(r.ns[RTL]);
    const MinMedian ratio = min_median(r.ratio);
    std::printf("| %s | %s | %s | %s | %s | %s | %.1f | %.1f | %s | %s |\n", r.name.c_str(),
                format_ns(batch.min).c_str(), format_ns(batch.median).c_str(), format_ns(scalar.median).c_str(),
                format_ns(rtl.min).c_str(), format_ns(rtl.median).c_str(), rtl.min / batch.min, ratio.median,
                ratio.median >= 50 ? "met" : "**not met**", sum);
  }
  std::printf(
      "\n%u rounds per unit, the order of the three sides rotating; a round times about %llu vectors on each side, "
      "whole sweeps of a pool of %llu random vectors (seed %#llx) generated before timing, in batches of %u that "
      "share a state or a row. One op = one vector through the unit's whole function, every output field stored. "
      "C++ batch: the batch form, one call per batch, variant %s; scalar: the one-call form, inline; RTL: its "
      "adapter (port packing, Verilated eval, unpacking). Times are this thread's CPU time. The checksum folds every "
      "output field of the pool's results; the three sides agree bit for bit when it is the same. %s\n",
      opt.rounds, static_cast<unsigned long long>(opt.vectors), static_cast<unsigned long long>(opt.pool),
      static_cast<unsigned long long>(opt.seed), opt.batch, std::string(to_string(isa)).c_str(),
      machine_summary(load_before, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
          .c_str());
  return all_agree ? 0 : 1;
}

}  // namespace

static int run_main(int argc, char** argv) {
  Options opt;
  CLI::App cli{"bench_rtl: C++ datapath units of the rasterizer against their Verilated RTL, same vectors"};
  cli.add_option("--vectors", opt.vectors, "vectors per side and round (rounded up to whole pool sweeps)")
      ->check(CLI::Range(uint64_t{1}, uint64_t{100'000'000}))
      ->capture_default_str();
  cli.add_option("--pool", opt.pool, "random vectors per unit, swept in every round")
      ->check(CLI::Range(uint64_t{1}, uint64_t{10'000'000}))
      ->capture_default_str();
  cli.add_option("--batch", opt.batch, "vectors a batch (a span of a row, or fragments under one state)")
      ->check(CLI::Range(1, 512))
      ->capture_default_str();
  cli.add_option("--rounds", opt.rounds, "rounds (batch, scalar and RTL, the order rotating); min and median printed")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_option("--seed", opt.seed, "seed of the vector generator")->capture_default_str();
  cli.add_option("--isa", opt.isa,
                 "batch variant: x86-64, x86-64-v3 or x86-64-v4 (default: the widest this processor runs)");
  CLI11_PARSE(cli, argc, argv);
  return run(opt);
}

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_rtl", [&] { return run_main(argc, argv); });
}
