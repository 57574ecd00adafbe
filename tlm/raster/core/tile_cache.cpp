// See tile_cache.h; memory layouts and the load rule are in README.md.
#include "raster/core/tile_cache.h"

#include <algorithm>

#include "common/pixel_format.h"
#include "raster/core/little_endian.h"

namespace tessera::raster {

TileCache::TileCache(const RunConfig& config) : m_config(config) {
  const size_t tile_pixels = size_t{config.tile_width} * config.tile_height;
  m_color.resize(tile_pixels);
  m_depth.resize(tile_pixels);
  m_stencil.resize(tile_pixels);
  m_row_bytes.resize(size_t{config.tile_width} * 4);
}

void TileCache::select(unsigned tile_x, unsigned tile_y) {
  const RunConfig& c = m_config;
  m_row0 = tile_y * c.tile_height;
  const unsigned row1 = std::min(m_row0 + c.tile_height, c.height);
  m_tile = {int(tile_x * c.tile_width), int(c.height - row1), int(std::min((tile_x + 1) * c.tile_width, c.width)),
            int(c.height - m_row0)};
}

bool TileCache::clears_whole_tile(const ClearCommand& clear, const DrawState& state) const {
  const bool all = clear.color && clear.depth && clear.stencil && clear.color_mask == 15 && clear.depth_write &&
                   clear.stencil_write_mask == 0xff;
  return all && (!state.scissor || state.scissor_box.contains(m_tile));
}

void TileCache::load(RunContext& run) {
  const RunConfig& c = m_config;
  const unsigned width = unsigned(m_tile.x1 - m_tile.x0), rows = unsigned(m_tile.y1 - m_tile.y0);
  const unsigned bpp = bytes_per_pixel(c.color_format);
  for (unsigned r = 0; r < rows; ++r) {
    const unsigned row = m_row0 + r;
    const uint32_t color_address = c.color_base + (row * c.width + unsigned(m_tile.x0)) * bpp;
    if (!run.read(color_address, m_row_bytes.data(), width * bpp)) return;
    for (unsigned x = 0; x < width; ++x) {
      const uint8_t* p = m_row_bytes.data() + x * bpp;
      m_color[r * c.tile_width + x] = Rgba8::unpack(unpack_pixel(c.color_format, load_pixel(c.color_format, p)));
    }
    const uint32_t depth_address = c.depth_base + (row * c.width + unsigned(m_tile.x0)) * 4;
    if (!run.read(depth_address, m_row_bytes.data(), width * 4)) return;
    for (unsigned x = 0; x < width; ++x) {
      const uint32_t v = load_le32(m_row_bytes.data() + x * 4);
      m_depth[r * c.tile_width + x] = v & 0xffffff;
      m_stencil[r * c.tile_width + x] = uint8_t(v >> 24);
    }
    run.charge(run.result().tile_cycles, uint64_t{run.costs().tile_write_word} * ((width * bpp + 3) / 4 + width));
  }
}

void TileCache::write_back(RunContext& run) {
  const RunConfig& c = m_config;
  const unsigned width = unsigned(m_tile.x1 - m_tile.x0), rows = unsigned(m_tile.y1 - m_tile.y0);
  const unsigned bpp = bytes_per_pixel(c.color_format);
  for (unsigned r = 0; r < rows; ++r) {
    for (unsigned x = 0; x < width; ++x)
      store_pixel(c.color_format, m_row_bytes.data() + x * bpp,
                  pack_pixel(c.color_format, m_color[r * c.tile_width + x].pack()));
    const uint32_t address = c.color_base + ((m_row0 + r) * c.width + unsigned(m_tile.x0)) * bpp;
    if (!run.write(address, m_row_bytes.data(), width * bpp)) return;
    run.charge(run.result().tile_cycles, uint64_t{run.costs().tile_write_word} * ((width * bpp + 3) / 4));
  }
  for (unsigned r = 0; r < rows; ++r) {
    for (unsigned x = 0; x < width; ++x) {
      const unsigned i = r * c.tile_width + x;
      store_le32(m_row_bytes.data() + x * 4, m_depth[i] | uint32_t{m_stencil[i]} << 24);
    }
    const uint32_t address = c.depth_base + ((m_row0 + r) * c.width + unsigned(m_tile.x0)) * 4;
    if (!run.write(address, m_row_bytes.data(), width * 4)) return;
    run.charge(run.result().tile_cycles, uint64_t{run.costs().tile_write_word} * width);
  }
}

void TileCache::clear(RunContext& run, const ClearCommand& clear, const DrawState& state) {
  const Rgba8 color = quantise(clear.rgba);
  uint32_t channel_bits = 0;
  for (unsigned ch = 0; ch < 4; ++ch)
    if (clear.color_mask & (1u << ch)) channel_bits |= 0xffu << (8 * ch);
  const uint8_t stencil_mask = clear.stencil_write_mask;
  const bool clear_color = clear.color && channel_bits != 0;
  const bool clear_depth = clear.depth && clear.depth_write;
  const bool clear_stencil = clear.stencil && stencil_mask != 0;
  Rect area = m_tile;
  if (state.scissor) area = area.intersect(state.scissor_box);
  if (area.empty() || !(clear_color || clear_depth || clear_stencil)) return;
  for (int y = area.y0; y < area.y1; ++y) {
    for (int x = area.x0; x < area.x1; ++x) {
      const unsigned i = index(x, y);
      if (clear_color) m_color[i] = Rgba8::unpack((m_color[i].pack() & ~channel_bits) | (color.pack() & channel_bits));
      if (clear_depth) m_depth[i] = clear.depth_value;
      if (clear_stencil) m_stencil[i] = uint8_t((m_stencil[i] & ~stencil_mask) | (clear.stencil_value & stencil_mask));
    }
  }
  run.charge(run.result().tile_cycles,
             uint64_t{run.costs().tile_pixel_clear} * uint64_t(area.x1 - area.x0) * uint64_t(area.y1 - area.y0));
}

Rgba8 TileCache::quantise(Rgba8 c) const {
  return Rgba8::unpack(quantize_color(m_config.color_format, c.pack()));
}

}  // namespace tessera::raster
