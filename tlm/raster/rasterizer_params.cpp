// The rasterizer's parameters: raster.*.
#include <string>

#include "common/screen_size.h"
#include "raster/rasterizer.h"

namespace tessera {

namespace {
// The plain-C++ core's defaults (core/tile_rasterizer.h): the tile and the
// cycle costs are written there once, and these keys default to them.
const raster::RunConfig CORE;
const raster::CycleCosts COSTS;
}  // namespace

ParamGroup RasterizerParams::parameters() {
  using param::integer;
  // The clock: the paper synthesised the reciprocal unit alone for one cycle
  // at 250 MHz in 0.18 um; a whole pipeline with multipliers, tile buffers
  // and a bus interface closes at a lower frequency, and 100 MHz keeps it
  // on the order of the 96 MHz bus.
  return {
      "raster",
      {
          param::real("raster.clock_mhz", 100.0, 1, 1000, "MHz", "rasterizer pipeline clock"),
          integer("raster.tile_width", CORE.tile_width, 1, 256, "pixels", "tile buffer width (the paper: 32)"),
          integer("raster.tile_height", CORE.tile_height, 1, 256, "lines", "tile buffer height (the paper: 16)"),
          integer("raster.recip_method", static_cast<unsigned>(CORE.recip_method) + 1, 1, 3, "",
                  "reciprocal unit at reset: 1 fixed-point table, 2 floating-point table, 3 the paper's Method 3"),
          integer("raster.texture_units", 2, 1, raster::MAX_TEXTURE_UNITS, "units",
                  "texture units, each a sampler (with mipmaps) and a combiner; with driver.backend=raster, "
                  "driver.texture_units (GL_MAX_TEXTURE_UNITS) may not exceed it"),
          integer("raster.burst_beats", 16, 1, 256, "beats", "longest burst of the rasterizer's bus accesses"),
          integer("raster.beat_bytes", 4, 4, 16, "bytes",
                  "bytes per beat of the rasterizer's bus interface, its data width: 4, 8 or 16, at most "
                  "bus.width_bits / 8"),
          integer("raster.cycles.command", COSTS.command, 0, 1000, "cycles", "decoding one command word"),
          integer("raster.cycles.setup", COSTS.setup, 0, 1000, "cycles", "triangle setup (gradients, one reciprocal)"),
          integer("raster.cycles.tile_start", COSTS.tile_start, 0, 1000, "cycles", "starting a tile"),
          integer("raster.cycles.tile_pixel_clear", COSTS.tile_pixel_clear, 0, 1000, "cycles",
                  "per pixel of a tile-buffer clear (0: the buffers clear in one go)"),
          integer("raster.cycles.fragment", COSTS.fragment, 0, 1000, "cycles",
                  "per fragment: one pixel pipeline, one per cycle"),
          integer("raster.cycles.texel", COSTS.texel, 0, 1000, "cycles", "per texel fetched"),
          integer("raster.cycles.tile_write_word", COSTS.tile_write_word, 0, 1000, "cycles",
                  "per word of a finished tile written back (besides the bus time)"),
      },
      [](const Config& config) {
        const uint64_t beat = config.get_uint("raster.beat_bytes");
        if (beat != 4 && beat != 8 && beat != 16)
          throw ConfigError("configuration: 'raster.beat_bytes' expects 4, 8 or 16, got " + std::to_string(beat));
        // A master cannot be wider than the bus it drives.
        const uint64_t bus_bits = config.get_uint("bus.width_bits");
        if (beat * 8 > bus_bits)
          throw ConfigError("configuration: impossible combination: raster.beat_bytes=" + std::to_string(beat) +
                            " is wider than the bus (bus.width_bits=" + std::to_string(bus_bits) + ")");
        // The driver offers GL_MAX_TEXTURE_UNITS = driver.texture_units; on
        // the rasterizer each needs a unit of the hardware.
        if (config.has("driver.backend") && config.has("driver.texture_units") &&
            config.get_string("driver.backend") == "raster") {
          const uint64_t units = config.get_uint("raster.texture_units");
          const uint64_t driver_units = config.get_uint("driver.texture_units");
          if (driver_units > units)
            throw ConfigError(
                "configuration: impossible combination: driver.texture_units=" + std::to_string(driver_units) +
                " with driver.backend=raster, whose rasterizer has " + std::to_string(units) +
                " (raster.texture_units=" + std::to_string(units) + "): lower the one or raise the other");
        }
      }};
}

RasterizerParams RasterizerParams::from_config(const Config& config) {
  RasterizerParams p;
  p.tile_width = static_cast<unsigned>(config.get_uint("raster.tile_width"));
  p.tile_height = static_cast<unsigned>(config.get_uint("raster.tile_height"));
  const uint64_t method = config.get_uint("raster.recip_method");
  p.recip_method = method == 1   ? raster::RecipMethod::method1
                   : method == 2 ? raster::RecipMethod::method2
                                 : raster::RecipMethod::method3;
  p.texture_units = static_cast<unsigned>(config.get_uint("raster.texture_units"));
  p.burst_beats = static_cast<unsigned>(config.get_uint("raster.burst_beats"));
  p.beat_bytes = static_cast<unsigned>(config.get_uint("raster.beat_bytes"));
  auto cycles = [&](const char* key) {
    return static_cast<unsigned>(config.get_uint(std::string("raster.cycles.") + key));
  };
  p.costs.command = cycles("command");
  p.costs.setup = cycles("setup");
  p.costs.tile_start = cycles("tile_start");
  p.costs.tile_pixel_clear = cycles("tile_pixel_clear");
  p.costs.fragment = cycles("fragment");
  p.costs.texel = cycles("texel");
  p.costs.tile_write_word = cycles("tile_write_word");
  p.clock_period = sc_core::sc_time(1e3 / config.get_real("raster.clock_mhz"), sc_core::SC_NS);
  return p;
}

RasterizerParams RasterizerParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
