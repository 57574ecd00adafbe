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
// expand_channel) as constexpr tables built from them, for the per-pixel
// loops: the same values, a load instead of a division and a loop.
struct Rgb565Tables {
  uint8_t reduce5[256], reduce6[256], expand5[32], expand6[64];
};
constexpr Rgb565Tables make_rgb565_tables() {
  Rgb565Tables t{};
  for (uint32_t c = 0; c < 256; ++c) {
    t.reduce5[c] = uint8_t(reduce_channel(c, 5));
    t.reduce6[c] = uint8_t(reduce_channel(c, 6));
  }
  for (uint32_t v = 0; v < 32; ++v) t.expand5[v] = uint8_t(expand_channel(v, 5));
  for (uint32_t v = 0; v < 64; ++v) t.expand6[v] = uint8_t(expand_channel(v, 6));
  return t;
}
inline constexpr Rgb565Tables RGB565_TABLES = make_rgb565_tables();

// pack_pixel and unpack_pixel of RGB565 through the tables.
constexpr uint32_t pack_rgb565(uint32_t rgba) {
  const Rgb565Tables& t = RGB565_TABLES;
  return uint32_t{t.reduce5[rgba & 0xff]} << 11 | uint32_t{t.reduce6[(rgba >> 8) & 0xff]} << 5 |
         uint32_t{t.reduce5[(rgba >> 16) & 0xff]};
}
constexpr uint32_t unpack_rgb565(uint32_t packed) {
  const Rgb565Tables& t = RGB565_TABLES;
  return uint32_t{t.expand5[(packed >> 11) & 31]} | uint32_t{t.expand6[(packed >> 5) & 63]} << 8 |
         uint32_t{t.expand5[packed & 31]} << 16 | 0xffu << 24;
}
static_assert(pack_rgb565(0x00c08040u) == pack_pixel(PixelFormat::rgb565, 0x00c08040u) &&
                  unpack_rgb565(0xa5a5u) == unpack_pixel(PixelFormat::rgb565, 0xa5a5u),
              "the RGB565 tables follow common/pixel_format.h");

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
  Rgba8 quantise(Rgba8 c) const {
    return m_config.color_format == PixelFormat::rgba8888 ? c : Rgba8::unpack(unpack_rgb565(pack_rgb565(c.pack())));
  }

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
