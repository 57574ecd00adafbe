// See tile_cache.h; memory layouts and the load rule are in README.md.
#include "raster/core/tile_cache.h"

#include <algorithm>

#include "common/little_endian.h"
#include "common/pixel_format.h"
#include "raster/datapath/batch.h"

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

namespace {

// The per-pixel conversions of a row, batch kernels (raster/datapath/
// batch.h) run in the widest variant the processor has: load_pixel and
// store_pixel of common/pixel_format.h through the word copies of
// little_endian.h, RGB565 through tile_cache.h's arithmetic, and the
// depth/stencil word (depth24 | stencil << 24) split and joined. The index
// is a size_t so that the byte addresses are affine in it, as the
// vectoriser needs.
struct UnpackRowKernel {
  TESSERA_BATCH_KERNEL void run(PixelFormat format, const uint8_t* bytes, uint32_t* color, unsigned width) {
    if (format == PixelFormat::rgba8888)
      rgba8888(bytes, color, width);
    else
      rgb565(bytes, color, width);
  }
  TESSERA_BATCH_KERNEL void rgba8888(const uint8_t* __restrict bytes, uint32_t* __restrict color, unsigned width) {
    for (size_t x = 0; x < width; ++x) color[x] = load_le32(bytes + 4 * x);
  }
  TESSERA_BATCH_KERNEL void rgb565(const uint8_t* __restrict bytes, uint32_t* __restrict color, unsigned width) {
    for (size_t x = 0; x < width; ++x) color[x] = unpack_rgb565(load_le16(bytes + 2 * x));
  }
};

struct PackRowKernel {
  TESSERA_BATCH_KERNEL void run(PixelFormat format, const uint32_t* color, uint8_t* bytes, unsigned width) {
    if (format == PixelFormat::rgba8888)
      rgba8888(color, bytes, width);
    else
      rgb565(color, bytes, width);
  }
  TESSERA_BATCH_KERNEL void rgba8888(const uint32_t* __restrict color, uint8_t* __restrict bytes, unsigned width) {
    for (size_t x = 0; x < width; ++x) store_le32(bytes + 4 * x, color[x]);
  }
  TESSERA_BATCH_KERNEL void rgb565(const uint32_t* __restrict color, uint8_t* __restrict bytes, unsigned width) {
    for (size_t x = 0; x < width; ++x) store_le16(bytes + 2 * x, pack_rgb565(color[x]));
  }
};

struct SplitDepthStencilKernel {
  TESSERA_BATCH_KERNEL void run(const uint8_t* bytes, uint32_t* depth, uint8_t* stencil, unsigned width) {
    loop(bytes, depth, stencil, width);
  }
  TESSERA_BATCH_KERNEL void loop(const uint8_t* __restrict bytes, uint32_t* __restrict depth,
                                 uint8_t* __restrict stencil, unsigned width) {
    for (size_t x = 0; x < width; ++x) {
      const uint32_t v = load_le32(bytes + x * 4);
      depth[x] = v & 0xffffff;
      stencil[x] = uint8_t(v >> 24);
    }
  }
};

struct JoinDepthStencilKernel {
  TESSERA_BATCH_KERNEL void run(const uint32_t* depth, const uint8_t* stencil, uint8_t* bytes, unsigned width) {
    loop(depth, stencil, bytes, width);
  }
  TESSERA_BATCH_KERNEL void loop(const uint32_t* __restrict depth, const uint8_t* __restrict stencil,
                                 uint8_t* __restrict bytes, unsigned width) {
    for (size_t x = 0; x < width; ++x) store_le32(bytes + x * 4, depth[x] | uint32_t{stencil[x]} << 24);
  }
};

struct QuantiseKernel {
  TESSERA_BATCH_KERNEL void run(uint32_t* rgba, unsigned count) { loop(rgba, count); }
  TESSERA_BATCH_KERNEL void loop(uint32_t* __restrict rgba, unsigned count) {
    for (unsigned i = 0; i < count; ++i) rgba[i] = unpack_rgb565(pack_rgb565(rgba[i]));
  }
};

void unpack_row(PixelFormat format, const uint8_t* bytes, uint32_t* color, unsigned width) {
  batch_detail::dispatch<UnpackRowKernel>(best_batch_isa(), format, bytes, color, width);
}

void pack_row(PixelFormat format, const uint32_t* color, uint8_t* bytes, unsigned width) {
  batch_detail::dispatch<PackRowKernel>(best_batch_isa(), format, color, bytes, width);
}

void split_depth_stencil(const uint8_t* bytes, uint32_t* depth, uint8_t* stencil, unsigned width) {
  batch_detail::dispatch<SplitDepthStencilKernel>(best_batch_isa(), bytes, depth, stencil, width);
}

void join_depth_stencil(const uint32_t* depth, const uint8_t* stencil, uint8_t* bytes, unsigned width) {
  batch_detail::dispatch<JoinDepthStencilKernel>(best_batch_isa(), depth, stencil, bytes, width);
}

}  // namespace

void TileCache::quantise(uint32_t* rgba, unsigned count) const {
  if (m_config.color_format == PixelFormat::rgb565)
    batch_detail::dispatch<QuantiseKernel>(best_batch_isa(), rgba, count);
}

void TileCache::load(RunContext& run) {
  const RunConfig& c = m_config;
  const unsigned width = unsigned(m_tile.x1 - m_tile.x0), rows = unsigned(m_tile.y1 - m_tile.y0);
  const unsigned bpp = bytes_per_pixel(c.color_format);
  for (unsigned r = 0; r < rows; ++r) {
    const unsigned row = m_row0 + r;
    const uint32_t color_address = c.color_base + (row * c.width + unsigned(m_tile.x0)) * bpp;
    if (!run.read(color_address, m_row_bytes.data(), width * bpp)) return;
    unpack_row(c.color_format, m_row_bytes.data(), m_color.data() + r * c.tile_width, width);
    const uint32_t depth_address = c.depth_base + (row * c.width + unsigned(m_tile.x0)) * 4;
    if (!run.read(depth_address, m_row_bytes.data(), width * 4)) return;
    split_depth_stencil(m_row_bytes.data(), m_depth.data() + r * c.tile_width, m_stencil.data() + r * c.tile_width,
                        width);
    run.charge(run.result().tile_cycles, uint64_t{run.costs().tile_write_word} * ((width * bpp + 3) / 4 + width));
  }
}

void TileCache::write_back(RunContext& run) {
  const RunConfig& c = m_config;
  const unsigned width = unsigned(m_tile.x1 - m_tile.x0), rows = unsigned(m_tile.y1 - m_tile.y0);
  const unsigned bpp = bytes_per_pixel(c.color_format);
  for (unsigned r = 0; r < rows; ++r) {
    pack_row(c.color_format, m_color.data() + r * c.tile_width, m_row_bytes.data(), width);
    const uint32_t address = c.color_base + ((m_row0 + r) * c.width + unsigned(m_tile.x0)) * bpp;
    if (!run.write(address, m_row_bytes.data(), width * bpp)) return;
    run.charge(run.result().tile_cycles, uint64_t{run.costs().tile_write_word} * ((width * bpp + 3) / 4));
  }
  for (unsigned r = 0; r < rows; ++r) {
    join_depth_stencil(m_depth.data() + r * c.tile_width, m_stencil.data() + r * c.tile_width, m_row_bytes.data(),
                       width);
    const uint32_t address = c.depth_base + ((m_row0 + r) * c.width + unsigned(m_tile.x0)) * 4;
    if (!run.write(address, m_row_bytes.data(), width * 4)) return;
    run.charge(run.result().tile_cycles, uint64_t{run.costs().tile_write_word} * width);
  }
}

void TileCache::clear(RunContext& run, const ClearCommand& clear, const DrawState& state) {
  const uint32_t color = quantise(clear.rgba.pack());
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
  const unsigned width = unsigned(area.x1 - area.x0);
  const uint32_t color_bits = color & channel_bits;
  const uint8_t stencil_bits = uint8_t(clear.stencil_value & stencil_mask);
  for (int y = area.y0; y < area.y1; ++y) {
    const unsigned i0 = index(area.x0, y);  // the row's pixels are i0 .. i0 + width - 1
    if (clear_color) {
      uint32_t* row = m_color.data() + i0;
      if (channel_bits == 0xffffffffu)
        std::fill(row, row + width, color);
      else
        for (unsigned x = 0; x < width; ++x) row[x] = (row[x] & ~channel_bits) | color_bits;
    }
    if (clear_depth) std::fill(m_depth.data() + i0, m_depth.data() + i0 + width, clear.depth_value);
    if (clear_stencil) {
      uint8_t* row = m_stencil.data() + i0;
      for (unsigned x = 0; x < width; ++x) row[x] = uint8_t((row[x] & ~stencil_mask) | stencil_bits);
    }
  }
  run.charge(run.result().tile_cycles,
             uint64_t{run.costs().tile_pixel_clear} * uint64_t(area.x1 - area.x0) * uint64_t(area.y1 - area.y0));
}

}  // namespace tessera::raster
