// The study's pixel experiments (docs/experiments.md), as applications that
// run on the host model with `--backend arm` (the host computes) or
// `--backend ap-pixel` (the array computes, through ap-pixel's program and
// layout, sw_driver/renderers/ap_pixel):
//
//  - study_shading: N single-pixel shades (default 192,000), each with its
//    own attribute set, as the study's shading loop: C = C0 + x dC/dx +
//    y dC/dy for the first --attributes of R, G, B, A, S, T, Z (default
//    seven; six, as the study measured, with ap.pixel.program=study). On
//    the array a pass gives each of the 96 CUs its own values and position
//    and reads the results back (through the CIU, or with dma.enabled=true
//    through the system/array DMA: plain arrays reshuffled in and out; no
//    broadcast, since no two CUs share a value). The array program is
//    ap.pixel.program's: tuned (16.8, seven attributes only) or study
//    (8.8, its shade<n> entry for n attributes).
//  - study_patches: patches of pixels sharing one attribute set, squares of
//    1 x 1 to 6 x 6 and lines of 1 to 40 pixels: the host steps the
//    attributes incrementally (arm), or sends the 21 values to every CU and
//    one block of ap.pixel.block x ap.pixel.block pixels per CU, runs the
//    program (ap.pixel.program's) and reads the pixels back (ap-pixel).
//
// The figures go to stats.json's driver section (study.*), in host time
// from the first input load to the last result stored, and every result is
// checked against the same arithmetic done natively (a mismatch is an
// error, status 1): the integer part of the 16.8 sum the host keeps from
// the tuned program, the whole 8.8 value (the 16.8 sum modulo 2^16) from
// the study's.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/apps.h"
#include "apps/study_common.h"
#include "config/config.h"
#include "costs/host_cost.h"
#include "device/array_driver.h"
#include "device/dma_driver.h"
#include "renderers/ap_pixel/pixel_setup.h"
#include "renderers/common/array_dma.h"
#include "renderers/common/host_time.h"

namespace tessera {

namespace {

using study::check_options;
using study::ns;
using study::option;
using study::publish;
using study::publish_units;
using study::usage_guarded;

using ap_pixel::Attribute;
using ap_pixel::ATTRIBUTES;
using ap_pixel::ProgramVariant;
using ap_pixel::TriangleValues;

// Where the study's applications run: the host alone, or with the array.
enum class Target { host, array };

Target target_of(const AppEnvironment& env, const char* app) {
  const std::string backend = env.config != nullptr ? env.config->get_string("driver.backend") : "arm";
  if (backend == "arm") return Target::host;
  if (backend == "ap-pixel") return Target::array;
  throw std::invalid_argument(std::string(app) + " runs on --backend arm (the host computes) or --backend ap-pixel " +
                              "(the array computes), not on " + backend);
}

// The array program the array runs (ap.pixel.program; the host alone runs
// none).
ProgramVariant program_variant(const AppEnvironment& env, Target target) {
  if (target == Target::host || env.config == nullptr) return ProgramVariant::tuned;
  return ap_pixel::program_variant(env.config->get_string("ap.pixel.program"));
}

// The attribute set of shade (or patch) n: deterministic, gradients within
// 8.8, values within 16.8.
TriangleValues attribute_set(uint32_t n) {
  TriangleValues v;
  for (unsigned a = 0; a < ATTRIBUTES; ++a) {
    const uint32_t h = (n + 1) * 2654435761u + a * 40503u;
    v.c0[a] = (h >> 8) & 0xffff00u;
    v.gx[a] = static_cast<int16_t>(static_cast<int32_t>(h % 1021) - 510);
    v.gy[a] = static_cast<int16_t>(static_cast<int32_t>((h >> 12) % 1021) - 510);
  }
  return v;
}

// The integer part of a 16.8 result, as the host keeps it.
uint16_t integer_part(uint32_t value) {
  return static_cast<uint16_t>(value >> 8);
}

// The part of a result the host keeps: the integer part of tuned's 16.8
// value, the whole of study's 8.8 value (16.8 modulo 2^16).
uint16_t kept(ProgramVariant variant, uint32_t value) {
  return variant == ProgramVariant::study ? static_cast<uint16_t>(value) : integer_part(value);
}

constexpr unsigned INPUT_WORDS = 3 * ATTRIBUTES + 1;  // per set: c0, gx, gy per attribute; x, y packed

uint64_t ns(double seconds) {
  return static_cast<uint64_t>(std::llround(seconds * 1e9));
}

// Inputs as the host keeps them: per set 22 words in system memory.
void store_inputs(HostApi& host, uint32_t address, const TriangleValues& v, int x, int y) {
  uint8_t* p = host.store_span(address, 4, INPUT_WORDS);
  auto put = [&](unsigned word, uint32_t value) {
    for (unsigned b = 0; b < 4; ++b) p[4 * word + b] = static_cast<uint8_t>(value >> (8 * b));
  };
  for (unsigned a = 0; a < ATTRIBUTES; ++a) {
    put(3 * a, v.c0[a]);
    put(3 * a + 1, static_cast<uint16_t>(v.gx[a]));
    put(3 * a + 2, static_cast<uint16_t>(v.gy[a]));
  }
  put(3 * ATTRIBUTES, static_cast<uint32_t>(static_cast<uint8_t>(x)) | static_cast<uint32_t>(static_cast<uint8_t>(y))
                                                                           << 8);
}

TriangleValues load_inputs(HostApi& host, uint32_t address, int& x, int& y) {
  const uint8_t* p = host.load_span(address, 4, INPUT_WORDS);
  auto get = [&](unsigned word) {
    return uint32_t{p[4 * word]} | uint32_t{p[4 * word + 1]} << 8 | uint32_t{p[4 * word + 2]} << 16 |
           uint32_t{p[4 * word + 3]} << 24;
  };
  TriangleValues v;
  for (unsigned a = 0; a < ATTRIBUTES; ++a) {
    v.c0[a] = get(3 * a);
    v.gx[a] = static_cast<int16_t>(get(3 * a + 1));
    v.gy[a] = static_cast<int16_t>(get(3 * a + 2));
  }
  const uint32_t xy = get(3 * ATTRIBUTES);
  // Signed bytes.
  x = static_cast<int>(xy & 0xff) - ((xy & 0x80) != 0 ? 256 : 0);
  y = static_cast<int>((xy >> 8) & 0xff) - ((xy & 0x8000) != 0 ? 256 : 0);
  return v;
}

// The input words of a set as the host's own loop loads them: one LDR each
// (the words are 4-byte aligned, and little-endian as both host models
// are), no copy into a TriangleValues.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the inputs are stored little-endian");

const uint8_t* aligned_words(const uint8_t* p) {
  return static_cast<const uint8_t*>(__builtin_assume_aligned(p, 4));
}

uint32_t word_at(const uint8_t* words, unsigned k) {
  uint32_t w;
  std::memcpy(&w, words + 4 * k, 4);
  return w;
}

// A signed byte of the packed position word.
int signed_byte(uint32_t word, unsigned byte) {
  return static_cast<int8_t>(static_cast<uint8_t>(word >> (8 * byte)));
}

// One shade from its input words, as the study's loop does it: per
// attribute (the first `attributes`) C = C0 + x dC/dx + y dC/dy in 32
// bits (C0 < 2^24, |x|, |y| <= 128, |gradient| < 2^15: the products stay
// below 2^22), the integer part of the 16.8 result stored as 16 bits.
void shade(const uint8_t* in, uint8_t* out, unsigned attributes) {
  in = aligned_words(in);
  const uint32_t xy = word_at(in, 3 * ATTRIBUTES);
  const int32_t x = signed_byte(xy, 0), y = signed_byte(xy, 1);
  for (unsigned a = 0; a < attributes; ++a) {
    const uint32_t c0 = word_at(in, 3 * a);
    const auto gx = static_cast<int16_t>(word_at(in, 3 * a + 1));
    const auto gy = static_cast<int16_t>(word_at(in, 3 * a + 2));
    const uint32_t value = (c0 + static_cast<uint32_t>(x * gx + y * gy)) >> 8;
    out[2 * a] = static_cast<uint8_t>(value);  // two STRB: no library call for an unaligned halfword
    out[2 * a + 1] = static_cast<uint8_t>(value >> 8);
  }
}

int mismatch(const char* app, const std::string& where, unsigned attribute, unsigned got, unsigned expected) {
  std::fprintf(stderr, "%s: %s, attribute %u: %u, expected %u\n", app, where.c_str(), attribute, got, expected);
  return 1;
}

}  // namespace

namespace {

// One run of study_shading: what every pass shares.
struct ShadingRun {
  ShadingRun(const char* app_name, AppEnvironment& environment, Target where, ProgramVariant program,
             unsigned attribute_count)
      : app(app_name),
        env(environment),
        host(*environment.host),
        target(where),
        variant(program),
        attributes(attribute_count),
        layout(ap_pixel::PixelLayout::of(program)) {}

  const char* app;
  AppEnvironment& env;
  HostApi& host;
  Target target;
  ProgramVariant variant;
  unsigned attributes;
  ap_pixel::PixelLayout layout;
  std::unique_ptr<ArrayDriver> array;
  unsigned per_pass = 96;
  // With the DMA: the values c0 .. the end of gy of every CU (one row of
  // one byte per CU per CMEM byte: 63 for tuned, whose gradients' sign
  // bytes stay 0 as the program makes them, 42 for study), dx and dy (2
  // rows), and the results (a row of 16-bit values per attribute), in
  // system memory, and the two chains. Each shade has its own values, so
  // a broadcast has nothing to carry here (dma.broadcast changes nothing).
  unsigned value_rows = 0;
  uint32_t staged_values = 0, staged_offsets = 0, staged_results = 0, chain_in = 0, chain_out = 0;
  // One pass of inputs in system memory, rewritten for every pass (not
  // timed), and the results.
  uint32_t inputs = 0, results = 0;
  unsigned entry = 0;  // the program's entry for one pixel of `attributes` attributes
  renderers::HostTime time;
  uint64_t cycles = 0;
  // A pass's loaded sets and results, allocated once.
  std::vector<TriangleValues> sets;
  std::vector<int> xs, ys;
  std::vector<std::array<uint16_t, ATTRIBUTES>> got;
};

// The study's loop on the host: each shade's 22 words loaded and its
// seven results stored, nothing else.
void shade_pass_on_host(ShadingRun& r, unsigned n) {
  renderers::TimedScope timed(r.host, r.time, renderers::HostSplit::compute);
  const uint8_t* in = r.host.load_span(r.inputs, 4, n * INPUT_WORDS);
  uint8_t* out = r.host.store_span(r.results, 2, n * r.attributes);
  costs::charge(r.host, costs::HostCost::study_shade_pass);
  costs::charge(r.host, costs::HostCost::study_shade, n);
  costs::charge(r.host, costs::HostCost::study_shade_attribute, uint64_t{n} * r.attributes);
  for (unsigned i = 0; i < n; ++i) shade(in + i * INPUT_WORDS * 4, out + i * r.attributes * 2, r.attributes);
}

// Through the DMA: the host stores every CU's 63 bytes and position into
// plain arrays (2 ALU a byte: shifted out of its value and stored), one
// chain reshuffles them in; a run; one chain brings the seven 16-bit
// integer parts of every CU out, which the host loads.
void shade_pass_through_dma(ShadingRun& r, DmaDriver& dma, unsigned n) {
  HostApi& host = r.host;
  const unsigned per_pass = r.per_pass;
  {
    renderers::TimedScope timed(host, r.time, renderers::HostSplit::array_write);
    for (unsigned i = 0; i < n; ++i) r.sets[i] = load_inputs(host, r.inputs + i * INPUT_WORDS * 4, r.xs[i], r.ys[i]);
    uint8_t* values = host.store_span(r.staged_values, 1, r.value_rows * per_pass);
    std::fill(values, values + size_t{r.value_rows} * per_pass, 0);
    for (unsigned i = 0; i < n; ++i)
      ap_pixel::for_each_value_byte(
          r.sets[i], r.layout,
          [&](unsigned address, uint8_t byte) { values[size_t{address - r.layout.c0} * per_pass + i] = byte; },
          r.attributes);
    uint8_t* offsets = host.store_span(r.staged_offsets, 1, 2 * per_pass);
    std::fill(offsets, offsets + 2 * per_pass, 0);
    for (unsigned i = 0; i < n; ++i) {
      offsets[i] = static_cast<uint8_t>(r.xs[i]);
      offsets[per_pass + i] = static_cast<uint8_t>(r.ys[i]);
    }
    costs::charge(host, costs::HostCost::study_shade_staged, n);
    dma.start_chain(0, r.chain_in);
    dma.wait(0);
  }
  {
    renderers::TimedScope timed(host, r.time, renderers::HostSplit::array_wait);
    r.cycles += r.array->run(r.entry);
  }
  {
    renderers::TimedScope timed(host, r.time, renderers::HostSplit::array_read);
    dma.start_chain(0, r.chain_out);
    dma.wait(0);
    for (unsigned a = 0; a < r.attributes; ++a) {
      const uint8_t* p = host.load_span(r.staged_results + 2 * a * per_pass, 2, n);
      for (unsigned i = 0; i < n; ++i) r.got[i][a] = static_cast<uint16_t>(p[2 * i] | p[2 * i + 1] << 8);
    }
  }
}

// Through the CIU: every CU its own value bytes (49 tuned, 6 per
// attribute study) and position, a run, a 16-bit read per attribute.
void shade_pass_through_ciu(ShadingRun& r, unsigned n) {
  HostApi& host = r.host;
  ArrayDriver& array = *r.array;
  {
    renderers::TimedScope timed(host, r.time, renderers::HostSplit::array_write);
    for (unsigned i = 0; i < n; ++i) r.sets[i] = load_inputs(host, r.inputs + i * INPUT_WORDS * 4, r.xs[i], r.ys[i]);
    std::vector<uint8_t> column(array.cus(), 0);
    std::vector<std::pair<unsigned, std::vector<uint8_t>>> planes;
    for (unsigned i = 0; i < n; ++i) {
      unsigned k = 0;
      ap_pixel::for_each_value_byte(
          r.sets[i], r.layout,
          [&](unsigned address, uint8_t byte) {
            if (planes.size() <= k) planes.emplace_back(address, std::vector<uint8_t>(array.cus(), 0));
            planes[k++].second[i] = byte;
          },
          r.attributes);
    }
    for (const auto& [address, plane] : planes) array.write_all8(address, plane);
    for (unsigned i = 0; i < n; ++i) column[i] = static_cast<uint8_t>(r.xs[i]);
    array.write_all8(r.layout.dx, column);
    for (unsigned i = 0; i < n; ++i) column[i] = static_cast<uint8_t>(r.ys[i]);
    array.write_all8(r.layout.dy, column);
  }
  {
    renderers::TimedScope timed(host, r.time, renderers::HostSplit::array_wait);
    r.cycles += array.run(r.entry);
  }
  {
    renderers::TimedScope timed(host, r.time, renderers::HostSplit::array_read);
    for (unsigned a = 0; a < r.attributes; ++a) {
      const std::vector<uint16_t> values = array.read_all16(r.layout.result(0, 0, static_cast<Attribute>(a)));
      for (unsigned i = 0; i < n; ++i) r.got[i][a] = values[i];
    }
  }
}

// The pass's results, checked against the sets as generated, not as
// loaded; 0, or 1 after naming the first mismatch.
int check_pass(ShadingRun& r, unsigned first, unsigned n) {
  if (r.target == Target::host) {
    const uint8_t* out = r.host.load_span(r.results, 2, n * r.attributes);
    for (unsigned i = 0; i < n; ++i)
      for (unsigned a = 0; a < r.attributes; ++a)
        r.got[i][a] = static_cast<uint16_t>(out[2 * (i * r.attributes + a)] | out[2 * (i * r.attributes + a) + 1] << 8);
  }
  for (unsigned i = 0; i < n; ++i) {
    const uint32_t s = first + i;
    const TriangleValues set = attribute_set(s);
    const int x = static_cast<int>(s % 192) - 96, y = static_cast<int>(s / 192 % 144) - 72;
    for (unsigned a = 0; a < r.attributes; ++a) {
      const uint32_t value = ap_pixel::shade_reference(set, static_cast<Attribute>(a), x, y, 0, 0);
      const uint16_t expected = r.target == Target::host ? integer_part(value) : kept(r.variant, value);
      if (r.got[i][a] != expected) return mismatch(r.app, "shade " + std::to_string(s), a, r.got[i][a], expected);
    }
  }
  return 0;
}

// The staged arrays and the two chains of a run through the DMA.
void stage_dma_chains(ShadingRun& r, DmaDriver& dma) {
  const ap_pixel::PixelLayout& layout = r.layout;
  if (layout.gx != layout.c0 + layout.value_bytes * ATTRIBUTES ||
      layout.gy != layout.gx + layout.value_bytes * ATTRIBUTES || layout.dy != layout.dx + 1)
    throw std::logic_error(std::string(r.app) + ": the program's c0, gx, gy (or dx, dy) are not adjacent");
  std::vector<dma::Descriptor> out;
  for (unsigned a = 0; a < r.attributes; ++a)
    out.push_back(DmaDriver::from_cmem(layout.result(0, 0, static_cast<Attribute>(a)),
                                       r.staged_results + 2 * a * r.per_pass, r.per_pass, 2));
  dma.write_chain(r.chain_in, {DmaDriver::to_cmem(r.staged_values, layout.c0, r.value_rows * r.per_pass, 1),
                               DmaDriver::to_cmem(r.staged_offsets, layout.dx, 2 * r.per_pass, 1)});
  dma.write_chain(r.chain_out, out);
}

int study_shading(AppEnvironment& env) {
  const char* app = "study_shading";
  const Target target = target_of(env, app);
  check_options(env, app, {"--shades", "--attributes"});
  const unsigned shades = option(env, app, "--shades", 192000, 1, 10000000);
  const ProgramVariant variant = program_variant(env, target);
  const unsigned attributes =
      option(env, app, "--attributes", variant == ProgramVariant::study ? 6 : ATTRIBUTES, 1, ATTRIBUTES);
  if (target == Target::array && variant == ProgramVariant::tuned && attributes != ATTRIBUTES)
    throw std::invalid_argument(std::string(app) + ": --attributes " + std::to_string(attributes) +
                                " needs ap.pixel.program=study: the tuned program evaluates all " +
                                std::to_string(ATTRIBUTES));
  ShadingRun r(app, env, target, variant, attributes);
  HostApi& host = r.host;
  r.entry = variant == ProgramVariant::study ? r.layout.shade_entry[attributes] : r.layout.entry[1];
  DmaDriver dma(env);
  renderers::DmaUse use;
  if (target == Target::array) {
    r.array = std::make_unique<ArrayDriver>(env);
    r.array->load(ap_pixel::program_of(variant));
    use = renderers::dma_use(env, dma);
    r.per_pass = r.array->cus();
  }
  const unsigned per_pass = r.per_pass;
  r.value_rows = 3 * r.layout.value_bytes * ATTRIBUTES;
  r.staged_values = env.heap_base + 2 * per_pass * INPUT_WORDS * 4 + 4096;
  r.staged_offsets = r.staged_values + r.value_rows * per_pass;
  r.staged_results = r.staged_offsets + 2 * per_pass;
  r.chain_in = r.staged_results + 2 * ATTRIBUTES * per_pass;
  r.chain_out = r.chain_in + 2 * dma::DESCRIPTOR_BYTES;
  if (use.enabled) stage_dma_chains(r, dma);
  r.inputs = env.heap_base;
  r.results = r.inputs + per_pass * INPUT_WORDS * 4;
  uint64_t passes = 0;
  double total = 0;
  costs::reset_cost_meter();
  r.sets.resize(per_pass);
  r.xs.resize(per_pass);
  r.ys.resize(per_pass);
  r.got.resize(per_pass);
  for (unsigned first = 0; first < shades; first += per_pass) {
    const unsigned n = std::min(per_pass, shades - first);
    for (unsigned i = 0; i < n; ++i) {
      const uint32_t s = first + i;
      store_inputs(host, r.inputs + i * INPUT_WORDS * 4, attribute_set(s), static_cast<int>(s % 192) - 96,
                   static_cast<int>(s / 192 % 144) - 72);
    }
    const double start = host.now_seconds();
    if (target == Target::host) {
      shade_pass_on_host(r, n);
    } else if (use.enabled) {
      shade_pass_through_dma(r, dma, n);
    } else {
      shade_pass_through_ciu(r, n);
    }
    total += host.now_seconds() - start;
    ++passes;
    if (check_pass(r, first, n) != 0) return 1;
  }
  publish(env, "shades", "single-pixel shades computed", shades);
  publish(env, "attributes", "attributes per shade", attributes);
  publish(env, "passes", "array passes (96 shades each), or groups of 96 on the host", passes);
  publish(env, "array_cycles", "array cycles of the shading program", r.cycles);
  publish(env, "total_ns", "host time from the first input load to the last result", ns(total));
  publish(env, "compute_ns", "host time computing the shades itself", ns(host, r.time.compute));
  publish(env, "write_ns", "host time writing inputs to the array", ns(host, r.time.array_write));
  publish(env, "wait_ns", "host time waiting for the array", ns(host, r.time.array_wait));
  publish(env, "read_ns", "host time reading results from the array", ns(host, r.time.array_read));
  publish_units(env);
  std::string detail;
  if (target == Target::array && variant != ProgramVariant::tuned)
    detail = std::string(" (") + ap_pixel::program_variant_name(variant) + " program, " + std::to_string(attributes) +
             " attributes)";
  else if (attributes != ATTRIBUTES)
    detail = " (" + std::to_string(attributes) + " attributes)";
  std::printf("%s: %u shades on the %s%s: %.3f ms\n", app, shades, target == Target::host ? "host" : "array",
              detail.c_str(), total * 1e3);
  return 0;
}

int study_patches(AppEnvironment& env) {
  const char* app = "study_patches";
  const Target target = target_of(env, app);
  // A line of 255 pixels centred on its origin keeps every block's offset
  // within a CU's signed byte.
  check_options(env, app, {"--max-pixels"});
  const unsigned max_pixels = option(env, app, "--max-pixels", 40, 1, 255);
  HostApi& host = *env.host;
  const ProgramVariant variant = program_variant(env, target);
  const ap_pixel::PixelLayout layout = ap_pixel::PixelLayout::of(variant);
  std::unique_ptr<ArrayDriver> array;
  unsigned block = 1;
  if (target == Target::array) {
    array = std::make_unique<ArrayDriver>(env);
    array->load(ap_pixel::program_of(variant));
    if (env.config != nullptr) block = static_cast<unsigned>(env.config->get_uint("ap.pixel.block"));
  }
  const uint32_t inputs = env.heap_base, results = inputs + INPUT_WORDS * 4;
  struct Shape {
    const char* name;
    unsigned width, height;
  };
  std::vector<Shape> shapes;
  for (unsigned side = 1; side * side <= max_pixels; ++side) shapes.push_back({"square", side, side});
  for (unsigned n = 1; n <= max_pixels; ++n) shapes.push_back({"line", n, 1});
  unsigned patch = 0;
  renderers::HostTime time;  // the timed rounds', all in compute
  costs::reset_cost_meter();
  for (const Shape& shape : shapes) {
    const TriangleValues values = attribute_set(patch++);
    const int ox = -static_cast<int>(shape.width) / 2, oy = -static_cast<int>(shape.height) / 2;
    store_inputs(host, inputs, values, ox, oy);
    std::vector<std::array<uint16_t, ATTRIBUTES>> got(size_t{shape.width} * shape.height);
    // Twice, the second timed: the first warms the caches.
    double elapsed = 0;
    for (unsigned round = 0; round < 2; ++round) {
      std::optional<renderers::TimedScope> timed;
      if (round == 1) timed.emplace(host, time, renderers::HostSplit::compute);
      const double start = host.now_seconds();
      if (target == Target::host) {
        // Start values per attribute from the input words, then one
        // addition per pixel and attribute, row by row (32 bits, modulo
        // 2^24 as the CU's sums: only the low 24 bits are kept).
        const uint8_t* in = aligned_words(host.load_span(inputs, 4, INPUT_WORDS));
        const uint32_t xy = word_at(in, 3 * ATTRIBUTES);
        const int32_t x0 = signed_byte(xy, 0), y0 = signed_byte(xy, 1);
        uint32_t row_start[ATTRIBUTES], step_x[ATTRIBUTES], step_y[ATTRIBUTES];
        costs::charge(host, costs::HostCost::study_patch);
        for (unsigned a = 0; a < ATTRIBUTES; ++a) {
          const int32_t gx = static_cast<int16_t>(word_at(in, 3 * a + 1));
          const int32_t gy = static_cast<int16_t>(word_at(in, 3 * a + 2));
          step_x[a] = static_cast<uint32_t>(gx);
          step_y[a] = static_cast<uint32_t>(gy);
          row_start[a] = word_at(in, 3 * a) + static_cast<uint32_t>(x0 * gx + y0 * gy);
        }
        for (unsigned r = 0; r < shape.height; ++r) {
          costs::charge(host, costs::HostCost::study_patch_row);
          uint8_t* out = host.store_span(results + r * shape.width * ATTRIBUTES * 2, 2, shape.width * ATTRIBUTES);
          costs::charge(host, costs::HostCost::study_patch_pixel, shape.width);
          uint32_t value[ATTRIBUTES];
          for (unsigned a = 0; a < ATTRIBUTES; ++a) value[a] = row_start[a];
          for (unsigned c = 0; c < shape.width; ++c)
            for (unsigned a = 0; a < ATTRIBUTES; ++a) {
              out[2 * (c * ATTRIBUTES + a)] = static_cast<uint8_t>(value[a] >> 8);
              out[2 * (c * ATTRIBUTES + a) + 1] = static_cast<uint8_t>(value[a] >> 16);
              value[a] += step_x[a];
            }
          for (unsigned a = 0; a < ATTRIBUTES; ++a) row_start[a] += step_y[a];
        }
      } else {
        // The 21 values to every CU; blocks of block x block pixels, one
        // per CU, row by row; the pixels of the patch read back.
        int x0 = 0, y0 = 0;
        const TriangleValues v = load_inputs(host, inputs, x0, y0);
        ap_pixel::for_each_value_byte(v, layout, [&](unsigned address, uint8_t byte) { array->fill8(address, byte); });
        const unsigned across = (shape.width + block - 1) / block, up = (shape.height + block - 1) / block;
        const unsigned blocks = across * up, cus = array->cus();
        for (unsigned first = 0; first < blocks; first += cus) {
          const unsigned n = std::min(cus, blocks - first);
          const unsigned groups = (n + 3) / 4, per_row = array->groups_per_row();
          for (unsigned g = 0; g < groups; ++g) {
            uint32_t dx = 0, dy = 0;
            for (unsigned b = 0; b < 4 && 4 * g + b < n; ++b) {
              const unsigned index = first + 4 * g + b;
              dx |= uint32_t{static_cast<uint8_t>(x0 + static_cast<int>(index % across * block))} << (8 * b);
              dy |= uint32_t{static_cast<uint8_t>(y0 + static_cast<int>(index / across * block))} << (8 * b);
            }
            costs::charge(host, costs::HostCost::study_offset_group);
            array->write32(g % per_row, g / per_row, layout.dx, dx);
            array->write32(g % per_row, g / per_row, layout.dy, dy);
          }
          array->run(layout.entry[block]);
          for (unsigned g = 0; g < groups; ++g)
            for (unsigned v_in = 0; v_in < block; ++v_in)
              for (unsigned u_in = 0; u_in < block; ++u_in) {
                // Read this place only if one of the group's blocks has a
                // pixel of the patch there.
                bool any = false;
                for (unsigned b = 0; b < 4 && 4 * g + b < n; ++b) {
                  const unsigned index = first + 4 * g + b;
                  any = any ||
                        (index % across * block + u_in < shape.width && index / across * block + v_in < shape.height);
                }
                if (!any) continue;
                for (unsigned a = 0; a < ATTRIBUTES; ++a) {
                  const unsigned address = layout.result(u_in, v_in, static_cast<Attribute>(a));
                  const uint32_t hi = array->read32(g % per_row, g / per_row, address);
                  const uint32_t mid = array->read32(g % per_row, g / per_row, address + 1);
                  costs::charge(host, costs::HostCost::study_result_attribute);
                  for (unsigned b = 0; b < 4 && 4 * g + b < n; ++b) {
                    const unsigned index = first + 4 * g + b;
                    const unsigned c = index % across * block + u_in, r = index / across * block + v_in;
                    if (c >= shape.width || r >= shape.height) continue;
                    got[r * shape.width + c][a] =
                        static_cast<uint16_t>(((hi >> (8 * b)) & 0xff) << 8 | ((mid >> (8 * b)) & 0xff));
                  }
                }
              }
        }
      }
      elapsed = host.now_seconds() - start;
    }
    if (target == Target::host) {
      const uint8_t* out = host.load_span(results, 2, shape.width * shape.height * ATTRIBUTES);
      for (size_t p = 0; p < got.size(); ++p)
        for (unsigned a = 0; a < ATTRIBUTES; ++a)
          got[p][a] = static_cast<uint16_t>(out[2 * (p * ATTRIBUTES + a)] | out[2 * (p * ATTRIBUTES + a) + 1] << 8);
    }
    for (unsigned r = 0; r < shape.height; ++r)
      for (unsigned c = 0; c < shape.width; ++c)
        for (unsigned a = 0; a < ATTRIBUTES; ++a) {
          const uint16_t expected =
              kept(variant, ap_pixel::shade_reference(values, static_cast<Attribute>(a), ox, oy, c, r));
          if (got[r * shape.width + c][a] != expected)
            return mismatch(app,
                            std::string(shape.name) + " " + std::to_string(shape.width) + "x" +
                                std::to_string(shape.height) + " pixel (" + std::to_string(c) + ", " +
                                std::to_string(r) + ")",
                            a, got[r * shape.width + c][a], expected);
        }
    publish(env, std::string("patch.") + shape.name + "." + std::to_string(shape.width * shape.height) + "_ns",
            "host time for one patch of that many pixels, all seven attributes", ns(elapsed));
  }
  publish(env, "block", "pixels per side of a CU's block (1 on the host)", block);
  publish(env, "compute_ns", "host time of the timed rounds of every patch", ns(host, time.compute));
  publish_units(env);
  std::printf("%s: %u patches on the %s\n", app, static_cast<unsigned>(shapes.size()),
              target == Target::host ? "host" : "array");
  return 0;
}

}  // namespace

int study_shading_app(AppEnvironment& env) {
  return usage_guarded(env, study_shading);
}

int study_patches_app(AppEnvironment& env) {
  return usage_guarded(env, study_patches);
}

}  // namespace tessera
