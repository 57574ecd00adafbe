// study_forward_texture: van Sinten's two-pass forward texture mapping
// (sw_driver/forward_texture/README.md): a generated checkerboard texture
// warped onto the display under a perspective 3 x 3 matrix, rows then
// columns (or columns first, as the pass-order rule picks), with the
// prefiltered resampling of Eq. 6, every frame; the warped image is shown
// (grey) as the frame. The warp runs where the back end draws: `--backend
// arm` on the host, `--backend ap-tile` or `ap-pixel` on the array
// (resample_lines.s, one line per CU, the same program for both: the lines
// in and the results out by the DMA when dma.enabled, else through the CIU;
// the box filter only, unless the factors are looked up in the array's
// shared table), with the same image byte for byte.
//
// Options (after "--"): --texture-size N (a square of N x N texels, 2 ..
// 1024, default 128; on the array at most 512), --filter box|tent (default
// box), --filter-width F (1 .. 8, default 2), --matrix A,B,C,D,E,F,G,H,I
// (decimals: x w = A u + B v + C, y w = D u + E v + F, w = G u + H v + I;
// default a square seen tilted back, DEFAULT_MATRIX), --array-factors
// computed|table (on the array: the program computes the box's factors, the
// J2210's way, default; or looks the filter's up in the shared table,
// resample_lines_lut, which needs array.features.lut and a table of 256 F
// entries, array.lut.entries), --array-mapping lines|chain (on the array:
// one line per CU, default; or van Sinten's own mapping, resample_chain.s,
// a border per CU and the sums passed down each row's chain, its factors
// always looked up, which needs the Image Blender preset's delayed
// execution, row ring, selecting adds and table). Magnification is refused
// (upscale the texture first), as are a singular matrix and a texture that
// does not fit.
//
// The figures go to stats.json's driver section (study.*): the warp's host
// time per frame (study.warp_ns, from the texture's first load to the last
// pixel stored) and its split (compute_ns; on the array write_ns, wait_ns,
// read_ns), the pass order; on the array the programs run, their cycles,
// the lines and borders, and the bytes and DMA descriptors moved. The
// native model charges the forward_texture_* rows of the measured cost
// table.
#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/apps.h"
#include "apps/study_common.h"
#include "config/config.h"
#include "costs/host_cost.h"
#include "device/display_driver.h"
#include "forward_texture/array_resampler.h"
#include "forward_texture/warp.h"
#include "renderers/common/host_time.h"

namespace tessera {

namespace {

namespace ft = forward_texture;

constexpr const char* APP = "study_forward_texture";
constexpr const char* DEFAULT_MATRIX = "0.9,0.25,40,0.05,0.8,30,0,0.002,1";
constexpr unsigned CHECKER_SQUARE = 8;  // texels per side of a checkerboard square

std::string option_text(const AppEnvironment& env, const std::string& name, const std::string& fallback) {
  for (size_t i = 0; i + 1 < env.args.size(); ++i)
    if (env.args[i] == name) return env.args[i + 1];
  return fallback;
}

// A decimal ("-1.25", "40") as a fixed-point value with `fraction_bits`
// fraction bits, rounded down, in 32-bit integer arithmetic (at most four
// integer and nine fraction digits). False when the text is not such a
// decimal or the value does not fit below 2^(31 - fraction_bits).
bool parse_fixed(const std::string& text, int fraction_bits, int32_t& value) {
  size_t i = 0;
  const bool negative = !text.empty() && text[0] == '-';
  if (negative) ++i;
  uint32_t whole = 0, fraction = 0, scale = 1;
  unsigned whole_digits = 0, fraction_digits = 0;
  for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i, ++whole_digits)
    whole = whole * 10 + static_cast<uint32_t>(text[i] - '0');
  if (i < text.size() && text[i] == '.')
    for (++i; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i, ++fraction_digits) {
      fraction = fraction * 10 + static_cast<uint32_t>(text[i] - '0');
      scale *= 10;
    }
  if (i != text.size() || whole_digits + fraction_digits == 0 || whole_digits > 4 || fraction_digits > 9) return false;
  if (whole >= (uint32_t{1} << (31 - fraction_bits))) return false;
  // fraction / scale in binary, a bit at a time: 2 fraction < 2 10^9 < 2^31.
  uint32_t bits = 0;
  for (int b = 0; b < fraction_bits; ++b) {
    fraction *= 2;
    bits <<= 1;
    if (fraction >= scale) bits |= 1, fraction -= scale;
  }
  const auto magnitude = static_cast<int32_t>((whole << fraction_bits) | bits);
  value = negative ? -magnitude : magnitude;
  return true;
}

ft::PerspectiveMatrix parse_matrix(const std::string& text) {
  std::vector<std::string> fields(1);
  for (char c : text) {
    if (c == ',')
      fields.emplace_back();
    else
      fields.back() += c;
  }
  if (fields.size() != 9)
    throw std::invalid_argument(std::string(APP) + ": --matrix takes nine decimals A,B,C,D,E,F,G,H,I, not '" + text +
                                "'");
  int32_t v[9];
  for (int k = 0; k < 9; ++k) {
    const int bits = k < 6 ? ft::Q12_20_FRACTION_BITS : ft::Q2_30_FRACTION_BITS;
    if (!parse_fixed(fields[static_cast<size_t>(k)], bits, v[k]))
      throw std::invalid_argument(std::string(APP) + ": --matrix: '" + fields[static_cast<size_t>(k)] + "' (entry " +
                                  "ABCDEFGHI"[k] + ") is not a decimal within " + (k < 6 ? "+-2048" : "+-2") +
                                  " with at most nine places");
  }
  return {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]};
}

ft::ArrayFactors parse_array_factors(const std::string& name) {
  if (name == "computed") return ft::ArrayFactors::computed;
  if (name == "table") return ft::ArrayFactors::table;
  throw std::invalid_argument(std::string(APP) + ": --array-factors is computed or table, not '" + name + "'");
}

ft::ArrayMapping parse_array_mapping(const std::string& name) {
  if (name == "lines") return ft::ArrayMapping::lines;
  if (name == "chain") return ft::ArrayMapping::chain;
  throw std::invalid_argument(std::string(APP) + ": --array-mapping is lines or chain, not '" + name + "'");
}

ft::FilterKind parse_filter(const std::string& name) {
  if (name == "box") return ft::FilterKind::box;
  if (name == "tent") return ft::FilterKind::tent;
  throw std::invalid_argument(std::string(APP) + ": --filter is box or tent, not '" + name + "'");
}

// Texel (u, v) of the checkerboard: squares of CHECKER_SQUARE texels, light
// ones 224, dark ones a ramp from 16 to 96 along the diagonal.
uint8_t checker(unsigned u, unsigned v, unsigned size) {
  if (((u / CHECKER_SQUARE) + (v / CHECKER_SQUARE)) % 2 == 0) return 224;
  return static_cast<uint8_t>(16 + 80 * (u + v) / (2 * size));
}

// The array program's options: --array-mapping, and --array-factors (the
// chain always looks its factors up), refused where they cannot run.
struct ArrayChoice {
  ft::ArrayMapping mapping;
  ft::ArrayFactors factors;
};

ArrayChoice array_choice(AppEnvironment& env, bool on_array) {
  const ft::ArrayMapping mapping = parse_array_mapping(option_text(env, "--array-mapping", "lines"));
  const ft::ArrayFactors factors = parse_array_factors(
      option_text(env, "--array-factors", mapping == ft::ArrayMapping::chain ? "table" : "computed"));
  if (mapping == ft::ArrayMapping::chain && !on_array)
    throw std::invalid_argument(std::string(APP) +
                                ": --array-mapping chain is an array program's (--backend ap-tile "
                                "or ap-pixel)");
  if (factors == ft::ArrayFactors::table && !on_array)
    throw std::invalid_argument(std::string(APP) +
                                ": --array-factors table is the array program's (--backend ap-tile or ap-pixel); "
                                "the host looks its factors up in its own table");
  if (mapping == ft::ArrayMapping::chain && factors == ft::ArrayFactors::computed)
    throw std::invalid_argument(std::string(APP) +
                                ": --array-mapping chain looks its factors up (resample_chain.s): --array-factors "
                                "computed is the one-line-per-CU program's");
  return {mapping, factors};
}

int study_forward_texture(AppEnvironment& env) {
  study::check_options(
      env, APP, {"--texture-size", "--filter", "--filter-width", "--matrix", "--array-factors", "--array-mapping"});
  const std::string backend = env.config != nullptr ? env.config->get_string("driver.backend") : "arm";
  const bool on_array = backend == "ap-tile" || backend == "ap-pixel";
  if (backend != "arm" && !on_array)
    throw std::invalid_argument(
        std::string(APP) + " runs on --backend arm (the host warps) or ap-tile / ap-pixel (the array warps); not on " +
        backend);
  const unsigned size = study::option(env, APP, "--texture-size", 128, 2, ft::MAX_IMAGE_SIZE);
  const ft::FilterKind kind = parse_filter(option_text(env, "--filter", "box"));
  const unsigned width = study::option(env, APP, "--filter-width", 2, 1, ft::MAX_FILTER_WIDTH);
  const ft::PerspectiveMatrix matrix = parse_matrix(option_text(env, "--matrix", DEFAULT_MATRIX));
  const ArrayChoice choice = array_choice(env, on_array);
  const ft::ArrayMapping mapping = choice.mapping;
  const ft::ArrayFactors factors = choice.factors;
  HostApi& host = *env.host;
  DisplayDriver display(env);
  const int out_width = static_cast<int>(display.width()), out_height = static_cast<int>(display.height());
  if (const std::string error = ft::matrix_error(matrix, static_cast<int>(size), static_cast<int>(size));
      !error.empty())
    throw std::invalid_argument(std::string(APP) + ": " + error);
  const ft::FilterTable table = ft::make_filter_table(kind, static_cast<int>(width));

  // The texture in system memory, one byte a texel (not timed).
  const uint32_t texture_address = env.heap_base;
  const uint32_t texels = size * size;
  uint8_t* stored = host.store_span(texture_address, 1, texels);
  for (unsigned v = 0; v < size; ++v)
    for (unsigned u = 0; u < size; ++u) stored[v * size + u] = checker(u, v, size);
  const uint32_t image_address = texture_address + ((texels + 3) & ~3u);

  renderers::HostTime time;
  std::optional<ft::ArrayResampler> array;
  if (on_array) {
    const uint32_t staging = image_address + ((static_cast<uint32_t>(out_width * out_height) + 31) & ~31u);
    array.emplace(env, time, staging, env.heap_end, factors, mapping);
    if (const std::string error = array->check(table, static_cast<int>(size)); !error.empty())
      throw std::invalid_argument(std::string(APP) + ": " +
                                  (mapping == ft::ArrayMapping::chain   ? "--array-mapping chain: "
                                   : factors == ft::ArrayFactors::table ? "--array-factors table: "
                                                                        : "") +
                                  error);
  }
  costs::reset_cost_meter();
  uint64_t warp_cycles = 0;
  ft::PassOrderChoice order;
  std::vector<uint32_t> row((static_cast<size_t>(out_width) * display.bytes_per_pixel() + 3) / 4);
  for (unsigned frame = 0; frame < env.frames; ++frame) {
    ft::WarpResult warped;
    // On the array the resampler times its own parts into `time`; the
    // warp's time outside them is compute.
    const uint64_t parts_before = time.compute + time.array_write + time.array_wait + time.array_read;
    renderers::HostTime whole;
    {
      renderers::TimedScope timed(host, whole, renderers::HostSplit::compute);
      ft::Image texture{static_cast<int>(size), static_cast<int>(size), {}};
      const uint8_t* in = host.load_span(texture_address, 1, texels);
      texture.texels.assign(in, in + texels);
      warped = ft::warp_texture(texture, matrix, table, out_width, out_height, array ? &*array : nullptr);
      if (!warped.error.empty()) throw std::invalid_argument(std::string(APP) + ": " + warped.error);
      const uint64_t first_lines = size, second_lines = static_cast<uint64_t>(out_width);
      costs::charge(host, costs::HostCost::forward_texture_line, first_lines + second_lines);
      if (array) {
        // The rest is the resampler's: the row pass's texels made q8_8, the
        // image rounded and copied.
        costs::charge(host, costs::HostCost::forward_texture_texel_load, first_lines * size);
        costs::charge(host, costs::HostCost::forward_texture_output_pixel,
                      static_cast<uint64_t>(out_width) * static_cast<uint64_t>(out_height));
      } else {
        // Per pass: a line's set-up, its texel borders (each a fixed-iteration
        // division, F lookups and F scalings), the pixels it closes.
        // The second pass walks the intermediate image's columns, a texel a
        // row apart: its borders cost the cache misses the first pass's do not.
        const uint64_t first_borders = first_lines * (size + 1), second_borders = second_lines * (size + 1);
        costs::charge(host, costs::HostCost::forward_texture_row_border, first_borders);
        costs::charge(host, costs::HostCost::forward_texture_column_border, second_borders);
        costs::charge(host, costs::HostCost::forward_texture_factor, (first_borders + second_borders) * width);
        costs::charge(
            host, costs::HostCost::forward_texture_pixel,
            first_lines * static_cast<uint64_t>(out_width) + second_lines * static_cast<uint64_t>(out_height));
      }
      std::memcpy(host.store_span(image_address, 1, static_cast<uint32_t>(warped.image.texels.size())),
                  warped.image.texels.data(), warped.image.texels.size());
    }
    const uint64_t parts = time.compute + time.array_write + time.array_wait + time.array_read - parts_before;
    time.compute += whole.compute - parts;
    warp_cycles += whole.compute;
    order = warped.pass_order;
    // The warped image shown, grey (not timed: the study's figure is the warp).
    const uint32_t buffer = display.back_buffer();
    for (int y = 0; y < out_height; ++y) {
      auto* bytes = reinterpret_cast<uint8_t*>(row.data());
      for (int x = 0; x < out_width; ++x) {
        const uint32_t grey = warped.image.at(x, out_height - 1 - y);  // y up in the warp, down on the display
        store_pixel(display.format(), bytes + static_cast<size_t>(x) * display.bytes_per_pixel(),
                    pack_pixel(display.format(), grey | grey << 8 | grey << 16 | 0xffu << 24));
      }
      costs::charge(host, costs::HostCost::pattern_pixel, static_cast<uint64_t>(out_width));
      const uint32_t line = buffer + static_cast<uint32_t>(y) * display.stride();
      const auto words = static_cast<unsigned>(row.size());
      for (unsigned w = 0; w < words; w += 8) host.write_words(line + 4 * w, &row[w], std::min(8u, words - w));
    }
    display.present();
  }
  const unsigned frames = env.frames > 0 ? env.frames : 1;
  study::publish(env, "compute_ns",
                 "host time of the warps on the host, every frame's (on the array: outside the "
                 "array's transfers and runs)",
                 study::ns(host, time.compute));
  study::publish(env, "warp_ns", "host time of one warp (the frames' mean)", study::ns(host, warp_cycles) / frames);
  if (array) {
    const ft::ArrayResampler::Figures& f = array->figures();
    study::publish(env, "write_ns", "host time sending the lines to the array (every frame's)",
                   study::ns(host, time.array_write));
    study::publish(env, "wait_ns", "host time waiting for the array's programs (every frame's)",
                   study::ns(host, time.array_wait));
    study::publish(env, "read_ns", "host time fetching and scattering the results (every frame's)",
                   study::ns(host, time.array_read));
    study::publish(env, "array_runs", "array programs run (a batch of one line per CU each)", f.runs);
    study::publish(env, "array_cycles", "array cycles of the resampling programs", f.cycles);
    study::publish(env, "array_lines", "lines the array resampled", f.lines);
    study::publish(env, "array_borders", "texel borders the array resampled", f.borders);
    study::publish(env, "array_steps",
                   "texel steps of the programs (a step takes every CU one border on: a run's n + 1 with one line "
                   "per CU, its rounds with the chain)",
                   f.steps);
    study::publish(env, "values_written", "bytes the array's data lines carried into CMEM", f.traffic.values_written);
    study::publish(env, "values_read", "bytes the array's data lines carried out of CMEM", f.traffic.values_read);
    study::publish(env, "dma_descriptors", "DMA descriptors run (0 through the CIU)", f.traffic.dma_descriptors);
    study::publish(env, "through_dma", "1 when the DMA moved the lines and results", array->through_dma() ? 1 : 0);
  }
  study::publish(env, "columns_first", "1 when the pass-order rule mapped the texture's columns first",
                 order.order == ft::PassOrder::columns_first ? 1 : 0);
  study::publish(env, "texture_size", "texels per side of the texture", size);
  study::publish(env, "filter_width", "F, the filter's width in pixels", width);
  study::publish_units(env);
  std::printf("%s: %ux%u texture onto %dx%d, %s filter of width %u, %s first, on the %s%s\n", APP, size, size,
              out_width, out_height, ft::filter_name(kind), width,
              order.order == ft::PassOrder::columns_first ? "columns" : "rows", array ? "array" : "host",
              mapping == ft::ArrayMapping::chain   ? " (van Sinten's mapping: a border per CU, the sums down the chain)"
              : factors == ft::ArrayFactors::table ? " (factors from the lookup table)"
                                                   : "");
  return 0;
}

}  // namespace

int study_forward_texture_app(AppEnvironment& env) {
  return study::usage_guarded(env, study_forward_texture);
}

}  // namespace tessera
