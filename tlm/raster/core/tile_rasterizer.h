// Functional core of the tile-based fixed-function rasterizer (plain C++, no
// SystemC): walks the driver's tile table (command_format.h), runs each
// tile's command list into on-chip tile buffers with the bit-exact datapath
// units of raster/datapath/, and writes the finished tiles back through a
// RasterPort. README.md in this folder walks the pipeline and states the
// formats, the rounding, the fill rule and the cycle costs.
#pragma once

#include <cstdint>

#include "common/histogram.h"
#include "common/pixel_format.h"
#include "raster/command_format.h"
#include "raster/core/raster_port.h"
#include "raster/datapath/reciprocal.h"

namespace tessera::raster {

// Rasterizer clock cycles per unit of work (README.md, "Cycle costs"). The
// defaults are raster.cycles.*'s (RasterizerParams::parameters reads them).
struct CycleCosts {
  unsigned command = 1, setup = 8, tile_start = 4, tile_pixel_clear = 0, fragment = 1, texel = 1, tile_write_word = 0;
};

// One run's frame, from the registers. The tile's size and the reciprocal
// method default to the paper's, raster.tile_width, raster.tile_height and
// raster.recip_method's defaults; the screen (WIDTH, HEIGHT) is the display's.
struct RunConfig {
  unsigned width = 0, height = 0, tile_width = 32, tile_height = 16;  // the screen: set from WIDTH, HEIGHT
  uint32_t tile_table = 0, color_base = 0, depth_base = 0;
  PixelFormat color_format = PixelFormat::rgb565;
  RecipMethod recip_method = RecipMethod::method3;
  unsigned texture_units = MAX_TEXTURE_UNITS;  // the hardware's units: a texture_units state may enable as many
};

struct RunResult {
  RasterError error = RasterError::none;
  uint32_t error_address = 0;
  uint64_t tiles = 0, commands = 0, triangles = 0, triangles_skipped = 0, fragments = 0, fragments_written = 0,
           texels = 0, bytes_read = 0, bytes_written = 0;
  uint64_t setup_cycles = 0, tile_cycles = 0, fragment_cycles = 0, texel_cycles = 0;  // sum = all cycles reported
  // The pixels of each span: a run of one row's pixels of a triangle in a
  // tile that the traversal hands to the shader (before the tests).
  Log2Histogram span_pixels;
};

class TileRasterizer {
 public:
  explicit TileRasterizer(RasterPort& port, const CycleCosts& costs = {});
  RunResult run(const RunConfig& config);  // walks the whole tile table; never throws on bad input

 private:
  RasterPort& m_port;
  CycleCosts m_costs;
};

}  // namespace tessera::raster
