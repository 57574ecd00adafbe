// The tile cache: the on-chip colour (RGBA8), depth (0.24) and stencil (8.0)
// buffers of the tile being drawn, filled from the frame buffer before the
// first command that needs them, written back when the tile's list ends,
// and the clears done in them (README.md, "Tile loop"). One tile at a time,
// where Mesa softpipe's sp_tile_cache keeps several.
#pragma once

#include <cstdint>
#include <vector>

#include "raster/core/command_decoder.h"
#include "raster/core/draw_state.h"
#include "raster/core/rect.h"
#include "raster/core/run_context.h"
#include "raster/datapath/fixed_point.h"

namespace tessera::raster {

class TileCache {
 public:
  // Buffers of tile_width x tile_height pixels; the sizes must have been checked.
  explicit TileCache(const RunConfig& config);

  // Moves to tile (tile_x, tile_y) of the tile table, (0, 0) at the top left.
  void select(unsigned tile_x, unsigned tile_y);
  // The tile in GL window coordinates (partial at the right and bottom edges).
  const Rect& tile() const { return m_tile; }

  // A clear of all three buffers with every mask open over the whole tile:
  // it overwrites every bit, so the tile need not be loaded first.
  bool clears_whole_tile(const ClearCommand& clear, const DrawState& state) const;
  void load(RunContext& run);        // one port read per row, colour then depth/stencil
  void write_back(RunContext& run);  // colour rows, then depth/stencil rows
  // The clear within the scissor, through the clear's masks.
  void clear(RunContext& run, const ClearCommand& clear, const DrawState& state);

  // The buffers' index of GL pixel (px, py), which must lie in tile().
  unsigned index(int px, int py) const {
    const unsigned row = m_config.height - 1 - unsigned(py);
    return (row - m_row0) * m_config.tile_width + (unsigned(px) - unsigned(m_tile.x0));
  }
  Rgba8& color(unsigned i) { return m_color[i]; }
  uint32_t& depth(unsigned i) { return m_depth[i]; }
  uint8_t& stencil(unsigned i) { return m_stencil[i]; }
  // What the colour buffer keeps of a colour: with RGB565, 5-6-5 bits
  // expanded back and alpha 255 (common/pixel_format.h).
  Rgba8 quantise(Rgba8 c) const;

 private:
  const RunConfig& m_config;
  Rect m_tile;
  unsigned m_row0 = 0;  // first memory row (top) of the tile
  std::vector<Rgba8> m_color;
  std::vector<uint32_t> m_depth;  // 0.24
  std::vector<uint8_t> m_stencil;
  std::vector<uint8_t> m_row_bytes;
};

}  // namespace tessera::raster
