// Every configuration parameter of the SoC, with its default: the one place
// defaults live. The README's configuration reference is generated from this
// table (soc_sim --config-reference), and validate() below checks the
// combinations that are individually legal but impossible together.
#include <cmath>
#include <string>

#include "common/pixel_format.h"
#include "config/config.h"

namespace tessera {
namespace {

ParamSpec boolean(std::string key, bool value, std::string description) {
  return {std::move(key), ParamType::boolean, value, std::move(description), "", 0, 0, {}};
}
ParamSpec integer(std::string key, int64_t value, double min, double max, std::string unit, std::string description) {
  return {std::move(key), ParamType::integer, value, std::move(description), std::move(unit), min, max, {}};
}
ParamSpec real(std::string key, double value, double min, double max, std::string unit, std::string description) {
  return {std::move(key), ParamType::real, value, std::move(description), std::move(unit), min, max, {}};
}
ParamSpec choice(std::string key, std::string value, std::vector<std::string> choices, std::string description) {
  return {std::move(key), ParamType::choice, std::move(value), std::move(description), "", 0, 0, std::move(choices)};
}
ParamSpec text(std::string key, std::string value, std::string description) {
  return {std::move(key), ParamType::string, std::move(value), std::move(description), "", 0, 0, {}};
}

std::vector<std::string> pixel_format_name_list() {
  std::vector<std::string> names;
  for (const PixelFormatInfo& info : PIXEL_FORMATS) names.emplace_back(info.name);
  return names;
}

}  // namespace

const std::vector<ParamSpec>& parameter_specs() {
  static const std::vector<ParamSpec> specs = {
      // Simulation
      text("sim.app", "teapot", "application to run: a built-in name or a path to a shared library"),
      integer("sim.frames", 3, 1, 100000, "frames", "frames the application draws before the simulation ends"),
      integer("sim.quantum_ns", 1000, 0, 1000000, "ns",
              "temporal-decoupling quantum of the loosely-timed initiators (0: synchronise on every access)"),
      integer("sim.run_ahead_us", 1000, 0, 1000000, "us",
              "how far ahead of the kernel the host may run past its quantum while no other process has "
              "anything scheduled that soon (0: always synchronise at the end of the quantum)"),
      integer("sim.time_limit_ms", 60000, 1, 3600000, "ms",
              "simulated-time limit; a run that reaches it stops with an error"),
      choice("sim.log_level", "warning", {"quiet", "error", "warning", "info", "debug"},
             "lowest severity of the log lines printed on stderr"),

      // Software on the host
      choice("driver.backend", "arm", {"arm", "raster"},
             "renderer back end of the GL ES driver: arm (software on the host) or raster (the rasterizer block)"),

      // Host: ARM922T
      real("host.clock_mhz", 192.0, 1, 2000, "MHz", "ARM922T core clock"),
      integer("host.irq_lines", 8, 4, 32, "lines", "interrupt inputs of the host"),
      integer("host.cycles.alu", 1, 0, 100, "cycles", "data-processing instruction (ARM9TDMI: 1)"),
      integer("host.cycles.load", 1, 0, 100, "cycles", "LDR/LDRH/LDRB issue, cache hit (ARM9TDMI: 1)"),
      integer("host.cycles.load_use", 1, 0, 100, "cycles",
              "interlock when a loaded value is used by the next instruction (ARM9TDMI: 1)"),
      integer("host.cycles.store", 1, 0, 100, "cycles", "STR/STRH/STRB issue (ARM9TDMI: 1)"),
      integer("host.cycles.mul", 3, 0, 100, "cycles",
              "MUL with a 16-bit multiplier (ARM9TDMI: 8 bits per cycle, early termination)"),
      integer("host.cycles.branch", 3, 0, 100, "cycles", "taken branch, pipeline refill (ARM9TDMI: 3)"),
      integer("host.cycles.fadd", 60, 0, 10000, "cycles", "soft-float single add/subtract"),
      integer("host.cycles.fmul", 50, 0, 10000, "cycles", "soft-float single multiply"),
      integer("host.cycles.fdiv", 130, 0, 10000, "cycles", "soft-float single divide"),
      integer("host.cycles.fsqrt", 200, 0, 10000, "cycles", "soft-float single square root"),
      integer("host.cycles.fcmp", 30, 0, 10000, "cycles", "soft-float compare"),
      integer("host.cycles.fconv", 30, 0, 10000, "cycles", "soft-float conversion to or from integer"),
      integer("host.cycles.call", 4, 0, 100, "cycles", "function call and return overhead"),
      integer("host.dcache.size_bytes", 8192, 0, 1048576, "bytes", "data cache size (0: no data cache)"),
      integer("host.dcache.line_bytes", 32, 4, 256, "bytes", "data cache line"),
      integer("host.dcache.ways", 64, 1, 1024, "ways", "data cache associativity (ARM922T: 64)"),
      integer("host.write_buffer.entries", 16, 1, 256, "entries", "posted-write buffer depth (ARM922T: 16)"),

      // Bus
      real("bus.clock_mhz", 96.0, 1, 2000, "MHz", "AHB-style bus clock"),
      integer("bus.width_bits", 32, 32, 128, "bits", "data width: one beat per width (32, 64 or 128)"),
      choice("bus.arbitration", "fixed_priority", {"fixed_priority", "round_robin"},
             "arbitration among requests made at the same bus cycle"),
      integer("bus.address_cycles", 1, 0, 16, "bus cycles", "address phase of a transfer"),
      integer("bus.error_cycles", 2, 1, 16, "bus cycles", "length of an error response"),

      // System memory
      integer("mem.size_mib", 16, 1, 256, "MiB", "system memory size"),
      integer("mem.first_access_cycles", 3, 0, 64, "bus cycles",
              "wait states before the first beat of an access (calibrated, see docs/calibration.md)"),
      integer("mem.beat_cycles", 1, 1, 16, "bus cycles", "cycles per data beat of a burst"),

      // Display
      integer("display.width", 320, 16, 2048, "pixels", "visible pixels per line"),
      integer("display.height", 240, 16, 2048, "lines", "visible lines"),
      choice("display.format", "rgb565", pixel_format_name_list(), "frame-buffer pixel format"),
      boolean("display.dma", false,
              "true: a display DMA scans the front buffer out over the bus; false: the host copies each frame to the "
              "display port"),
      real("display.refresh_hz", 60.0, 1, 240, "Hz", "refresh rate of the display DMA"),
      integer("display.vblank_lines", 20, 1, 1000, "lines", "vertical blanking interval, in line times"),
      integer("display.burst_beats", 16, 1, 256, "beats", "burst length of the display DMA's fetches"),
      integer("display.fifo_lines", 1, 1, 16, "lines",
              "line buffer of the display DMA: how many lines ahead it may fetch"),

      // Rasterizer. Its clock: the paper synthesised the reciprocal unit
      // alone for one cycle at 250 MHz in 0.18 um; a whole pipeline with
      // multipliers, tile buffers and a bus interface closes at a lower
      // frequency, and 100 MHz keeps it on the order of the 96 MHz bus.
      real("raster.clock_mhz", 100.0, 1, 1000, "MHz", "rasterizer pipeline clock"),
      integer("raster.width", 320, 16, 2048, "pixels",
              "screen width the rasterizer covers (must equal display.width with driver.backend=raster)"),
      integer("raster.height", 240, 16, 2048, "lines",
              "screen height the rasterizer covers (must equal display.height with driver.backend=raster)"),
      integer("raster.tile_width", 32, 1, 256, "pixels", "tile buffer width (the paper: 32)"),
      integer("raster.tile_height", 16, 1, 256, "lines", "tile buffer height (the paper: 16)"),
      integer("raster.recip_method", 3, 1, 3, "",
              "reciprocal unit at reset: 1 fixed-point table, 2 floating-point table, 3 the paper's Method 3"),
      integer("raster.burst_beats", 16, 1, 256, "beats", "longest burst of the rasterizer's bus accesses"),
      integer("raster.cycles.command", 1, 0, 1000, "cycles", "decoding one command word"),
      integer("raster.cycles.setup", 8, 0, 1000, "cycles", "triangle setup (gradients, one reciprocal)"),
      integer("raster.cycles.tile_start", 4, 0, 1000, "cycles", "starting a tile"),
      integer("raster.cycles.tile_pixel_clear", 0, 0, 1000, "cycles",
              "per pixel of a tile-buffer clear (0: the buffers clear in one go)"),
      integer("raster.cycles.fragment", 1, 0, 1000, "cycles", "per fragment: one pixel pipeline, one per cycle"),
      integer("raster.cycles.texel", 1, 0, 1000, "cycles", "per texel fetched"),
      integer("raster.cycles.tile_write_word", 0, 0, 1000, "cycles",
              "per word of a finished tile written back (besides the bus time)"),
  };
  return specs;
}

void Config::validate() const {
  const uint64_t bytes_per_pixel = tessera::bytes_per_pixel(*pixel_format_from_name(get_string("display.format")));
  const uint64_t frame_bytes = get_uint("display.width") * get_uint("display.height") * bytes_per_pixel;
  const uint64_t memory_bytes = get_uint("mem.size_mib") << 20;
  // Two frame buffers must fit in system memory, with room for everything else.
  if (2 * frame_bytes > memory_bytes / 2)
    throw ConfigError(
        "configuration: impossible combination: two frame buffers of display.width=" +
        std::to_string(get_uint("display.width")) + " x display.height=" + std::to_string(get_uint("display.height")) +
        " display.format=" + get_string("display.format") + " pixels need " + std::to_string(2 * frame_bytes) +
        " bytes, more than half of mem.size_mib=" + std::to_string(get_uint("mem.size_mib")));
  const int64_t width = get_int("bus.width_bits");
  if (width != 32 && width != 64 && width != 128)
    throw ConfigError("configuration: 'bus.width_bits' expects 32, 64 or 128, got " + std::to_string(width));
  const int64_t line = get_int("host.dcache.line_bytes");
  if (line & (line - 1))
    throw ConfigError("configuration: 'host.dcache.line_bytes' expects a power of two, got " + std::to_string(line));
  const int64_t cache = get_int("host.dcache.size_bytes");
  const int64_t ways = get_int("host.dcache.ways");
  if (cache != 0 && (cache % (line * ways) != 0))
    throw ConfigError(
        "configuration: impossible combination: host.dcache.size_bytes=" + std::to_string(cache) +
        " is not a multiple of host.dcache.line_bytes x host.dcache.ways = " + std::to_string(line * ways));
  if (cache != 0) {
    const int64_t sets = cache / (line * ways);
    if (sets & (sets - 1))
      throw ConfigError("configuration: impossible combination: the data cache has " + std::to_string(sets) +
                        " sets; host.dcache.size_bytes / (line_bytes x ways) must be a power of two");
  }
  if (get_string("driver.backend") == "raster" && (get_uint("raster.width") != get_uint("display.width") ||
                                                   get_uint("raster.height") != get_uint("display.height")))
    throw ConfigError(
        "configuration: impossible combination: driver.backend=raster draws the display's frame buffers, "
        "but raster.width x raster.height = " +
        std::to_string(get_uint("raster.width")) + " x " + std::to_string(get_uint("raster.height")) +
        " differs from display.width x display.height = " + std::to_string(get_uint("display.width")) + " x " +
        std::to_string(get_uint("display.height")));
  const uint64_t fetch_bytes = get_uint("display.burst_beats") * static_cast<uint64_t>(width / 8);
  const uint64_t line_bytes = get_uint("display.width") * bytes_per_pixel;
  if (get_bool("display.dma") && line_bytes % std::min(fetch_bytes, line_bytes) != 0)
    throw ConfigError("configuration: impossible combination: a display line of " + std::to_string(line_bytes) +
                      " bytes is not a whole number of display.burst_beats bursts (" + std::to_string(fetch_bytes) +
                      " bytes)");
}

}  // namespace tessera
