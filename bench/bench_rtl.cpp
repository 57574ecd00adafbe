// bench_rtl: speed of the rasterizer's bit-exact C++ datapath units
// (tlm/raster/datapath/) against their Verilated Verilog twins
// (rtl_models/raster/, through the adapters the cosim tests use), on the
// same vectors. Prints one Markdown table; bench_raster runs it as a child.
// See README.md for the method.
//
//   bench_rtl [--vectors V] [--pool P] [--rounds R] [--seed S]
//
// For each unit, P random vectors (the pool, default 4096: it stays in the
// caches, as the core's operands do) are generated once, with the
// distributions of tests/raster/test_raster_*_cosim.cpp, outside the timed
// loops. A round times V operations on each side, one after the other: the
// pool is swept V / P times, every output stored into an array of P results
// (a compiler barrier between sweeps keeps every sweep's stores). The C++
// side calls the unit's one-call entry point, inline from its header, in a
// plain loop (the compiler may vectorise across vectors: that is the point
// of branch-free units); the RTL side calls the adapter. R rounds, paired:
// min and median ns per operation of each side, and the ratio both ways
// (of the mins; median of the per-round ratios). Times are the thread's CPU
// time (CLOCK_THREAD_CPUTIME_ID), not wall time, so that time-slicing on a
// shared machine does not count. After timing, every output
// field of the pool's results is folded into a checksum per side; both must
// agree (a cosim run in one number), or bench_rtl exits with 1.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <limits>
#include <new>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "attr_interp_adapter.h"
#include "bench_support.h"
#include "blend_logic_op_adapter.h"
#include "edge_function_adapter.h"
#include "fog_unit_adapter.h"
#include "fragment_tests_adapter.h"
#include "guarded_main.h"
#include "raster/datapath/attribute_interpolator.h"
#include "raster/datapath/blend_logic_op.h"
#include "raster/datapath/edge_function.h"
#include "raster/datapath/fog_unit.h"
#include "raster/datapath/fragment_tests.h"
#include "raster/datapath/reciprocal.h"
#include "raster/datapath/texel_address.h"
#include "raster/datapath/texture_env.h"
#include "recip_unit_adapter.h"
#include "texel_address_adapter.h"
#include "texture_env_adapter.h"

namespace {

using namespace tessera::raster;
using tessera::BlendFactor;
using tessera::CompareFunc;
using tessera::FogMode;
using tessera::LogicOp;
using tessera::StencilOp;
using tessera::TexEnv;
using tessera::TexFilter;
using tessera::TexWrap;
using tessera::bench::load_average;
using tessera::bench::machine_summary;
using tessera::bench::min_median;
using tessera::bench::MinMedian;

struct Options {
  uint64_t vectors = 1'000'000;
  uint64_t pool = 4096;
  unsigned rounds = 15;
  uint64_t seed = 0xbe4c4;
};

// Order-dependent fold of one output field into the checksum (FNV-1a step
// on a whole word).
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

uint64_t fold(uint64_t sum, const FragmentTestResult& r) {
  const uint64_t flags = uint64_t{r.alpha_pass} | uint64_t{r.stencil_pass} << 1 | uint64_t{r.depth_pass} << 2 |
                         uint64_t{r.pass} << 3 | uint64_t{r.depth_write} << 4;
  return fold(fold(sum, flags), r.stencil.raw);
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

// One vector per unit: the arguments of the C++ call and of the adapter.
struct EdgeVector {
  Edge e;
  unsigned px, py;
  q5_16 recip;
};
struct AttrVector {
  AttributePlane plane;
  int dx, dy;
};
struct FragmentVector {
  FragmentTestState state;
  FragmentTestInput in;
};
struct BlendVector {
  BlendState state;
  Rgba8 src, dst;
};
struct TexelVector {
  TextureState state;
  q15_16 s, t;
};
struct FogVector {
  FogMode mode;
  int32_t argument;
  Rgba8 fragment, fog_color;
};
struct TexEnvVector {
  TexEnv mode;
  std::array<Rgba8, 4> texels;
  uint8_t weight_s, weight_t;
  Rgba8 fragment;
};

// The generators follow the random halves of the cosim tests, so that every
// branch (clamps, enables, undefined codes) is taken about as often as there.
std::vector<uint16_t> recip_vectors(std::mt19937_64& rng, uint64_t count) {
  std::vector<uint16_t> v(count);
  for (auto& x : v) x = static_cast<uint16_t>(rng() & RECIP_OPERAND_MAX);  // 0 is the invalid operand
  return v;
}

std::vector<EdgeVector> edge_vectors(std::mt19937_64& rng, uint64_t count) {
  std::vector<EdgeVector> v(count);
  for (auto& x : v) {
    const uint64_t bits = rng();
    const uint64_t more = rng();
    x.px = static_cast<unsigned>(more) & 0x1ff;
    x.py = static_cast<unsigned>(more >> 9) & 0x1ff;
    if (more >> 63) {  // a short edge near the pixel: distance and coverage leave their clamps
      const uint32_t cx = x.px * 16 + static_cast<uint32_t>((more >> 18) & 0x3f) - 32;
      const uint32_t cy = x.py * 16 + static_cast<uint32_t>((more >> 24) & 0x3f) - 32;
      x.e = Edge{q9_4::from_raw(cx), q9_4::from_raw(cy), q9_4::from_raw(cx + ((more >> 30) & 0x7f)),
                 q9_4::from_raw(cy + ((more >> 37) & 0x7f) - 64)};
      const uint32_t l1 = edge_l1_length(x.e).raw;
      x.recip = q5_16::from_raw(l1 == 0 ? 0 : static_cast<uint32_t>((uint64_t{1} << 20) / l1));
    } else {
      x.e = Edge{q9_4::from_raw(static_cast<uint32_t>(bits)), q9_4::from_raw(static_cast<uint32_t>(bits >> 13)),
                 q9_4::from_raw(static_cast<uint32_t>(bits >> 26)), q9_4::from_raw(static_cast<uint32_t>(bits >> 39))};
      x.recip = q5_16::from_raw(static_cast<uint32_t>(more >> 42));
    }
  }
  return v;
}

std::vector<AttrVector> attr_vectors(std::mt19937_64& rng, uint64_t count) {
  std::vector<AttrVector> v(count);
  auto word = [&rng]() { return sign_extend(rng(), 1 + static_cast<unsigned>(rng() % 40)); };
  for (auto& x : v) {
    const auto kind = static_cast<AttributeKind>(rng() & 3);  // 3: undefined kind
    const int64_t start = word(), grad_x = word(), grad_y = word();
    x.plane = AttributePlane{kind, start, grad_x, grad_y};
    const uint64_t offsets = rng();
    x.dx = static_cast<int>(offsets & 0x3ff) - 512;
    x.dy = static_cast<int>((offsets >> 10) & 0x3ff) - 512;
  }
  return v;
}

std::vector<FragmentVector> fragment_vectors(std::mt19937_64& rng, uint64_t count) {
  static constexpr std::array<CompareFunc, 8> FUNCS{CompareFunc::never,  CompareFunc::less,    CompareFunc::equal,
                                                    CompareFunc::lequal, CompareFunc::greater, CompareFunc::notequal,
                                                    CompareFunc::gequal, CompareFunc::always};
  static constexpr std::array<StencilOp, 7> OPS{StencilOp::keep,          StencilOp::zero, StencilOp::replace,
                                                StencilOp::incr,          StencilOp::decr, StencilOp::invert,
                                                static_cast<StencilOp>(7)};
  std::vector<FragmentVector> v(count);
  for (auto& x : v) {
    const uint64_t a = rng();
    const uint64_t b = rng();
    FragmentTestState& s = x.state;
    s.alpha_enable = a & 1;
    s.stencil_enable = (a >> 1) & 1;
    s.depth_enable = (a >> 2) & 1;
    s.depth_write_mask = (a >> 3) & 1;
    s.alpha_func = FUNCS[(a >> 4) & 7];
    s.stencil_func = FUNCS[(a >> 7) & 7];
    s.depth_func = FUNCS[(a >> 10) & 7];
    s.sfail = OPS[((a >> 13) & 0xff) % OPS.size()];
    s.dpfail = OPS[((a >> 21) & 0xff) % OPS.size()];
    s.dppass = OPS[((a >> 29) & 0xff) % OPS.size()];
    s.alpha_ref = unorm8::from_raw(static_cast<uint32_t>(a >> 37));
    s.stencil_ref = stencil8::from_raw(static_cast<uint32_t>(a >> 45));
    s.stencil_value_mask = static_cast<uint8_t>(a >> 53);
    s.stencil_write_mask = static_cast<uint8_t>(b);
    x.in.alpha = ((b >> 61) & 1) ? s.alpha_ref : unorm8::from_raw(static_cast<uint32_t>(b >> 8));
    x.in.stored_stencil = stencil8::from_raw(static_cast<uint32_t>(b >> 16));
    x.in.depth = unorm24::from_raw(static_cast<uint32_t>(b >> 24));
    x.in.stored_depth = (b >> 62) == 0 ? x.in.depth : unorm24::from_raw(static_cast<uint32_t>(rng()));
  }
  return v;
}

std::vector<BlendVector> blend_vectors(std::mt19937_64& rng, uint64_t count) {
  static constexpr std::array<BlendFactor, 12> FACTORS{BlendFactor::zero,
                                                       BlendFactor::one,
                                                       BlendFactor::src_color,
                                                       BlendFactor::one_minus_src_color,
                                                       BlendFactor::src_alpha,
                                                       BlendFactor::one_minus_src_alpha,
                                                       BlendFactor::dst_alpha,
                                                       BlendFactor::one_minus_dst_alpha,
                                                       BlendFactor::dst_color,
                                                       BlendFactor::one_minus_dst_color,
                                                       BlendFactor::src_alpha_saturate,
                                                       static_cast<BlendFactor>(15)};
  std::vector<BlendVector> v(count);
  for (auto& x : v) {
    const uint64_t a = rng();
    const uint64_t b = rng();
    x.state.blend_enable = (a & 3) != 0;  // mostly blending: it has the arithmetic
    x.state.logic_op_enable = ((a >> 2) & 7) == 0;
    x.state.src_factor = FACTORS[((a >> 5) & 0xff) % FACTORS.size()];
    x.state.dst_factor = FACTORS[((a >> 13) & 0xff) % FACTORS.size()];
    x.state.op = static_cast<LogicOp>((a >> 21) & 15);
    x.state.color_mask = ((a >> 25) & 3) == 0 ? static_cast<uint8_t>((a >> 27) & 15) : COLOR_MASK_ALL;
    x.src = Rgba8::unpack(static_cast<uint32_t>(b));
    x.dst = Rgba8::unpack(static_cast<uint32_t>(b >> 32));
  }
  return v;
}

std::vector<TexelVector> texel_vectors(std::mt19937_64& rng, uint64_t count) {
  static constexpr std::array<TexWrap, 2> WRAPS{TexWrap::repeat, TexWrap::clamp_to_edge};
  static constexpr std::array<TexFilter, 2> FILTERS{TexFilter::nearest, TexFilter::linear};
  std::vector<TexelVector> v(count);
  for (auto& x : v) {
    const uint64_t a = rng();
    const uint64_t b = rng();
    x.state.base = static_cast<uint32_t>(a >> 32);
    x.state.log2_width = static_cast<uint8_t>(a % 10);
    x.state.log2_height = static_cast<uint8_t>((a >> 4) % 10);
    x.state.wrap_s = WRAPS[(a >> 8) & 1];
    x.state.wrap_t = WRAPS[(a >> 9) & 1];
    x.state.filter = FILTERS[(a >> 10) & 1];
    // Mostly coordinates within a few repetitions, some across the whole range.
    const unsigned bits = ((a >> 11) & 7) != 0 ? 20 : 32;
    x.s = q15_16{sign_extend(b, bits)};
    x.t = q15_16{sign_extend(b >> 32, bits)};
  }
  return v;
}

std::vector<TexEnvVector> texenv_vectors(std::mt19937_64& rng, uint64_t count) {
  static constexpr std::array<TexEnv, 4> MODES{TexEnv::replace, TexEnv::modulate, TexEnv::decal,
                                               static_cast<TexEnv>(3)};
  std::vector<TexEnvVector> v(count);
  for (auto& x : v) {
    const uint64_t a = rng();
    const uint64_t b = rng();
    const uint64_t d = rng();
    x.mode = MODES[d & 3];
    x.texels = {Rgba8::unpack(static_cast<uint32_t>(a)), Rgba8::unpack(static_cast<uint32_t>(a >> 32)),
                Rgba8::unpack(static_cast<uint32_t>(b)), Rgba8::unpack(static_cast<uint32_t>(b >> 32))};
    x.weight_s = static_cast<uint8_t>(d >> 8);
    x.weight_t = static_cast<uint8_t>(d >> 16);
    x.fragment = Rgba8::unpack(static_cast<uint32_t>(d >> 32));
  }
  return v;
}

// Every mode code (3: no fog); arguments over the whole signed 16.16 range
// half the time, within the table's reach (0 to 32) the other half.
std::vector<FogVector> fog_vectors(std::mt19937_64& rng, uint64_t count) {
  std::vector<FogVector> v(count);
  for (auto& x : v) {
    const uint64_t a = rng();
    const uint64_t b = rng();
    x.mode = static_cast<FogMode>(a & 3);
    x.argument = (a >> 2) & 1 ? static_cast<int32_t>(a >> 32)
                              : static_cast<int32_t>((a >> 8) & 0x1fffff) - (1 << 16);  // -1 .. 31
    x.fragment = Rgba8::unpack(static_cast<uint32_t>(b));
    x.fog_color = Rgba8::unpack(static_cast<uint32_t>(b >> 32));
  }
  return v;
}

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

// `operations` calls of `unit(vector)` over the pool, the results stored in
// `out` (pool-sized); returns the thread's CPU time.
template <class Vector, class Result, class Unit>
double sweep(const std::vector<Vector>& pool, std::vector<Result>& out, uint64_t operations, Unit&& unit) {
  static_assert(std::is_trivially_destructible_v<Result>, "results are overwritten in place");
  const size_t n = pool.size();
  const double start = thread_cpu_seconds();
  for (uint64_t done = 0; done < operations; done += n) {
    const size_t count = static_cast<size_t>(std::min<uint64_t>(n, operations - done));
    const Vector* in = pool.data();
    Result* results = out.data();
    // Constructed in place (C++17 guaranteed elision): an assignment would
    // build each result in a temporary on the stack and copy it, which costs
    // a store-forwarding stall per result, more than the unit itself.
    for (size_t i = 0; i < count; ++i) ::new (static_cast<void*>(results + i)) Result(unit(in[i]));
    compiler_barrier(results);
  }
  return thread_cpu_seconds() - start;
}

template <class Result>
uint64_t checksum(const std::vector<Result>& results) {
  uint64_t sum = 0;
  for (const Result& r : results) sum = fold(sum, r);
  return sum;
}

struct UnitResult {
  std::string unit;
  std::vector<double> cpp_ns, rtl_ns, ratio;  // per round
  uint64_t cpp_checksum = 0, rtl_checksum = 0;
};

// R paired rounds of the C++ unit `model(vector)` and the adapter
// `rtl(vector)` over the same pool.
template <class Vector, class Model, class Rtl>
UnitResult measure(const char* unit, const std::vector<Vector>& pool, const Options& opt, Model&& model, Rtl&& rtl) {
  using Result = decltype(model(pool.front()));
  static_assert(std::is_same_v<Result, decltype(rtl(pool.front()))>, "both sides give the same result type");
  std::fprintf(stderr, "bench_rtl: %s ...\n", unit);
  UnitResult result;
  result.unit = unit;
  std::vector<Result> cpp_out(pool.size()), rtl_out(pool.size());
  const double ops = static_cast<double>(opt.vectors);
  sweep(pool, cpp_out, pool.size(), model);  // warm-up, not counted
  sweep(pool, rtl_out, pool.size(), rtl);
  for (unsigned r = 0; r < opt.rounds; ++r) {
    const double cpp_s = sweep(pool, cpp_out, opt.vectors, model);
    const double rtl_s = sweep(pool, rtl_out, opt.vectors, rtl);
    result.cpp_ns.push_back(cpp_s / ops * 1e9);
    result.rtl_ns.push_back(rtl_s / ops * 1e9);
    result.ratio.push_back(rtl_s / cpp_s);
  }
  result.cpp_checksum = checksum(cpp_out);
  result.rtl_checksum = checksum(rtl_out);
  return result;
}

std::string format_ns(double ns) {
  char text[32];
  std::snprintf(text, sizeof text, ns < 10 ? "%.2f" : "%.1f", ns);
  return text;
}

int run(const Options& opt) {
  const std::string load_before = load_average();
  const auto start = std::chrono::steady_clock::now();
  std::mt19937_64 rng(opt.seed);
  const uint64_t n = opt.pool;
  std::vector<UnitResult> results;
  {
    const auto vectors = recip_vectors(rng, n);
    RecipUnitRtl rtl;
    results.push_back(measure(
        "reciprocal (Method 3)", vectors, opt, [](uint16_t x) { return reciprocal(x, RecipMethod::method3); },
        [&rtl](uint16_t x) { return rtl.evaluate(x); }));
  }
  {
    const auto vectors = edge_vectors(rng, n);
    EdgeFunctionRtl rtl;
    results.push_back(measure(
        "edge function", vectors, opt, [](const EdgeVector& v) { return evaluate_edge(v.e, v.px, v.py, v.recip); },
        [&rtl](const EdgeVector& v) { return rtl.evaluate(v.e, v.px, v.py, v.recip); }));
  }
  {
    const auto vectors = attr_vectors(rng, n);
    AttrInterpRtl rtl;
    results.push_back(measure(
        "attribute interpolator", vectors, opt,
        [](const AttrVector& v) { return evaluate_attribute(v.plane, v.dx, v.dy); },
        [&rtl](const AttrVector& v) { return rtl.evaluate(v.plane, v.dx, v.dy); }));
  }
  {
    const auto vectors = fragment_vectors(rng, n);
    FragmentTestsRtl rtl;
    results.push_back(measure(
        "fragment tests", vectors, opt, [](const FragmentVector& v) { return run_fragment_tests(v.state, v.in); },
        [&rtl](const FragmentVector& v) { return rtl.run(v.state, v.in); }));
  }
  {
    const auto vectors = blend_vectors(rng, n);
    BlendLogicOpRtl rtl;
    results.push_back(measure(
        "blend / logic op", vectors, opt, [](const BlendVector& v) { return blend_logic_op(v.state, v.src, v.dst); },
        [&rtl](const BlendVector& v) { return rtl.run(v.state, v.src, v.dst); }));
  }
  {
    const auto vectors = texel_vectors(rng, n);
    TexelAddressRtl rtl;
    results.push_back(measure(
        "texel address", vectors, opt, [](const TexelVector& v) { return texel_lookup(v.state, v.s, v.t); },
        [&rtl](const TexelVector& v) { return rtl.lookup(v.state, v.s, v.t); }));
  }
  {
    const auto vectors = texenv_vectors(rng, n);
    TextureEnvRtl rtl;
    results.push_back(measure(
        "texture env (filter + env)", vectors, opt,
        [](const TexEnvVector& v) { return texture_filter_env(v.mode, v.texels, v.weight_s, v.weight_t, v.fragment); },
        [&rtl](const TexEnvVector& v) { return rtl.run(v.mode, v.texels, v.weight_s, v.weight_t, v.fragment); }));
  }

  {
    const auto vectors = fog_vectors(rng, n);
    FogUnitRtl rtl;
    results.push_back(measure(
        "fog unit", vectors, opt,
        [](const FogVector& v) { return fog_unit(v.mode, v.argument, v.fragment, v.fog_color); },
        [&rtl](const FogVector& v) { return rtl.run(v.mode, v.argument, v.fragment, v.fog_color); }));
  }

  std::printf(
      "| unit | C++ ns/op (min) | (median) | RTL ns/op (min) | (median) | RTL / C++ (mins) | (median of rounds) "
      "| goal >= 50 | checksum (both) |\n");
  std::printf("|---|--:|--:|--:|--:|--:|--:|---|---|\n");
  bool all_agree = true;
  for (const auto& r : results) {
    const bool agree = r.cpp_checksum == r.rtl_checksum;
    all_agree = all_agree && agree;
    char sum[64];
    if (agree)
      std::snprintf(sum, sizeof sum, "%016llx", static_cast<unsigned long long>(r.cpp_checksum));
    else
      std::snprintf(sum, sizeof sum, "DIFFER: %016llx / %016llx", static_cast<unsigned long long>(r.cpp_checksum),
                    static_cast<unsigned long long>(r.rtl_checksum));
    const MinMedian cpp = min_median(r.cpp_ns), rtl = min_median(r.rtl_ns), ratio = min_median(r.ratio);
    const double ratio_of_mins = rtl.min / cpp.min;
    std::printf("| %s | %s | %s | %s | %s | %.1f | %.1f | %s | %s |\n", r.unit.c_str(), format_ns(cpp.min).c_str(),
                format_ns(cpp.median).c_str(), format_ns(rtl.min).c_str(), format_ns(rtl.median).c_str(), ratio_of_mins,
                ratio.median, ratio.median >= 50 ? "met" : "**not met**", sum);
  }
  std::printf(
      "\n%u paired rounds per unit; a round times %llu operations on each side, sweeping a pool of %llu random "
      "vectors (seed %#llx) generated before timing. One op = one vector through the unit's whole function (C++: "
      "the datapath's one-call entry point, inline; RTL: its adapter, i.e. port packing + Verilated eval + "
      "unpacking); times are this thread's CPU time. The checksum folds every output field of the pool's results; C++ "
      "and RTL agree bit for bit when "
      "it is the same. %s\n",
      opt.rounds, static_cast<unsigned long long>(opt.vectors), static_cast<unsigned long long>(n),
      static_cast<unsigned long long>(opt.seed),
      machine_summary(load_before, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
          .c_str());
  return all_agree ? 0 : 1;
}

}  // namespace

static int run_main(int argc, char** argv) {
  Options opt;
  CLI::App cli{"bench_rtl: C++ datapath units of the rasterizer against their Verilated RTL, same vectors"};
  cli.add_option("--vectors", opt.vectors, "operations per side and round")
      ->check(CLI::Range(uint64_t{1}, uint64_t{100'000'000}))
      ->capture_default_str();
  cli.add_option("--pool", opt.pool, "distinct random vectors per unit, swept in every round")
      ->check(CLI::Range(uint64_t{1}, uint64_t{10'000'000}))
      ->capture_default_str();
  cli.add_option("--rounds", opt.rounds, "paired rounds (C++ then RTL); min and median are printed")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_option("--seed", opt.seed, "seed of the vector generator")->capture_default_str();
  CLI11_PARSE(cli, argc, argv);
  return run(opt);
}

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_rtl", [&] { return run_main(argc, argv); });
}
