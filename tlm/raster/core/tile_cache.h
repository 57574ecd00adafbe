// The tile cache: the on-chip colour (RGBA8), depth (0.24) and stencil (8.0)
// buffers of the tile being drawn, filled from the frame buffer before the
// first command that needs them, written back when the tile's list ends,
// and the clears done in them (README.md, "Tile loop"). One tile at a time,
// where Mesa softpipe's sp_tile_cache keeps several.
#pragma once

#include <cstdint>
#include <vector>

#include "common/pixel_format.h"
#include "raster/core/command_decoder.h"
#include "raster/core/draw_state.h"
#include "raster/core/rect.h"
#include "raster/core/run_context.h"
#include "raster/datapath/fixed_point.h"

namespace tessera::raster {

// RGB565's channel conversions of common/pixel_format.h (reduce_channel,
// expand_channel) in arithmetic the per-pixel loops vectorise: the
// division by 255 as a multiply-free floor, the expansion as the bit
// replication it is; checked against pixel_format.h for every code below.
constexpr uint32_t reduce_rgb565_channel(uint32_t c, unsigned bits) {
  const uint32_t x = c * ((1u << bits) - 1) + 127;  // below 65280: floor(x / 255) exactly
  return (x + 1 + ((x + 1) >> 8)) >> 8;
}
constexpr uint32_t expand_rgb565_channel(uint32_t v, unsigned bits) {
  return ((v << (8 - bits)) | (v >> (2 * bits - 8))) & 0xff;
}

// pack_pixel and unpack_pixel of RGB565.
constexpr uint32_t pack_rgb565(uint32_t rgba) {
  return reduce_rgb565_channel(rgba & 0xff, 5) << 11 | reduce_rgb565_channel((rgba >> 8) & 0xff, 6) << 5 |
         reduce_rgb565_channel((rgba >> 16) & 0xff, 5);
}
constexpr uint32_t unpack_rgb565(uint32_t packed) {
  return expand_rgb565_channel((packed >> 11) & 31, 5) | expand_rgb565_channel((packed >> 5) & 63, 6) << 8 |
         expand_rgb565_channel(packed & 31, 5) << 16 | 0xffu << 24;
}

namespace tile_cache_detail {
constexpr bool rgb565_matches_pixel_format() {
  for (uint32_t c = 0; c < 256; ++c)
    if (reduce_rgb565_channel(c, 5) != reduce_channel(c, 5) || reduce_rgb565_channel(c, 6) != reduce_channel(c, 6))
      return false;
  for (uint32_t v = 0; v < 64; ++v)
    if ((v < 32 && expand_rgb565_channel(v, 5) != expand_channel(v, 5)) ||
        expand_rgb565_channel(v, 6) != expand_channel(v, 6))
      return false;
  return true;
}
static_assert(rgb565_matches_pixel_format(), "the RGB565 conversions follow common/pixel_format.h");
}  // namespace tile_cache_detail

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
  uint32_t& color(unsigned i) { return m_color[i]; }  // packed RGBA8 (Rgba8::pack)
  uint32_t& depth(unsigned i) { return m_depth[i]; }
  uint8_t& stencil(unsigned i) { return m_stencil[i]; }
  // What the colour buffer keeps of a colour: with RGB565, 5-6-5 bits
  // expanded back and alpha 255 (common/pixel_format.h).
  uint32_t quantise(uint32_t rgba) const {
    return m_config.color_format == PixelFormat::rgba8888 ? rgba : unpack_rgb565(pack_rgb565(rgba));
  }
  // The same for `count` colours in place (a batch kernel, batch.h).
  void quantise(uint32_t* rgba, unsigned count) const;

 private:
  const RunConfig& m_config;
  Rect m_tile;
  unsigned m_row0 = 0;            // first memory row (top) of the tile
  std::vector<uint32_t> m_color;  // packed RGBA8
  std::vector<uint32_t> m_depth;  // 0.24
  std::vector<uint8_t> m_stencil;
  std::vector<uint8_t> m_row_bytes;
};

}  // namespace tessera::raster
