// The tile cache (tlm/raster/core/tile_cache.h) on its own: a 10 x 6 frame
// in 4 x 4 tiles (three tiles across, two down, the right and bottom ones
// partial), tiles selected, loaded from and written back to a plain memory,
// and cleared. Expected values follow the memory layout and the clear rule
// of tlm/raster/core/README.md ("Tile loop", "Commands"): row 0 of memory
// is GL's top row, colour at color_base + (row * width + x) * bpp, the
// depth/stencil word depth24 | stencil << 24 at depth_base + (row * width
// + x) * 4.
#include <gtest/gtest.h>

#include "raster/core/tile_cache.h"
#include "raster_core_test_support.h"

using namespace tessera::raster;
using tessera::PixelFormat;
using tessera::raster::test::StageRun;

namespace {

constexpr uint32_t COLOR_BASE = 0x1000;
constexpr uint32_t DEPTH_BASE = 0x2000;
constexpr unsigned WIDTH = 10, HEIGHT = 6;

RunConfig frame(PixelFormat format = PixelFormat::rgba8888) {
  RunConfig c;
  c.width = WIDTH;
  c.height = HEIGHT;
  c.tile_width = 4;
  c.tile_height = 4;
  c.color_base = COLOR_BASE;
  c.depth_base = DEPTH_BASE;
  c.color_format = format;
  return c;
}

struct CacheBench : StageRun {
  explicit CacheBench(PixelFormat format = PixelFormat::rgba8888) : StageRun(0x4000, frame(format)), cache(config) {}
  TileCache cache;
};

// Memory row of GL row y.
unsigned memory_row(int y) {
  return HEIGHT - 1 - unsigned(y);
}

TEST(TileCache, SelectGivesTheTileInGlCoordinatesPartialAtTheEdges) {
  CacheBench b;
  // Tile (0, 0) is the top-left one: memory rows 0-3 are GL rows 5..2.
  b.cache.select(0, 0);
  EXPECT_EQ(b.cache.tile().x0, 0);
  EXPECT_EQ(b.cache.tile().y0, 2);
  EXPECT_EQ(b.cache.tile().x1, 4);
  EXPECT_EQ(b.cache.tile().y1, 6);
  // Tile (2, 1): columns 8-9 (10 = 3 x 4 - 2) and memory rows 4-5, GL rows 1..0.
  b.cache.select(2, 1);
  EXPECT_EQ(b.cache.tile().x0, 8);
  EXPECT_EQ(b.cache.tile().y0, 0);
  EXPECT_EQ(b.cache.tile().x1, 10);
  EXPECT_EQ(b.cache.tile().y1, 2);
  // Index: tile rows from the top, tile_width apart. (8, 1) is the tile's
  // first memory row and column, (9, 0) its second row's second pixel.
  EXPECT_EQ(b.cache.index(8, 1), 0u);
  EXPECT_EQ(b.cache.index(9, 0), 4u + 1u);
}

TEST(TileCache, LoadReadsOneRowAtATimeColourThenDepthStencil) {
  CacheBench b;
  b.costs.tile_write_word = 1;
  for (unsigned row = 0; row < HEIGHT; ++row)
    for (unsigned x = 0; x < WIDTH; ++x) {
      b.port.set_word(COLOR_BASE + (row * WIDTH + x) * 4, 0xaa000000 | row << 8 | x);
      b.port.set_word(DEPTH_BASE + (row * WIDTH + x) * 4, (0x70 + row) << 24 | 0x100000 * row | x);
    }
  b.cache.select(1, 0);  // x 4..7, GL y 2..5 (memory rows 0-3)
  b.cache.load(b.run);
  ASSERT_EQ(b.run.result().error, RasterError::none);
  // GL (5, 4) is memory row 1, column 5.
  const unsigned i = b.cache.index(5, 4);
  EXPECT_EQ(b.cache.color(i), 0xaa000105u);
  EXPECT_EQ(b.cache.depth(i), 0x100005u);
  EXPECT_EQ(b.cache.stencil(i), 0x71);
  const unsigned corner = b.cache.index(7, 2);  // memory row 3, column 7
  EXPECT_EQ(b.cache.color(corner), 0xaa000307u);
  EXPECT_EQ(b.cache.depth(corner), 0x300007u);
  EXPECT_EQ(b.cache.stencil(corner), 0x73);
  // Per row: its colour at column 4, then its depth/stencil.
  std::vector<uint32_t> expected;
  for (unsigned row = 0; row < 4; ++row) {
    expected.push_back(COLOR_BASE + (row * WIDTH + 4) * 4);
    expected.push_back(DEPTH_BASE + (row * WIDTH + 4) * 4);
  }
  EXPECT_EQ(b.port.reads, expected);
  EXPECT_EQ(b.run.result().bytes_read, 4u * (16 + 16));
  // 4 colour words and 4 depth words per row, a tile_write_word cycle each.
  EXPECT_EQ(b.run.result().tile_cycles, 4u * 8);
}

TEST(TileCache, Rgb565LoadsByBitReplicationAndWritesBackRounded) {
  CacheBench b(PixelFormat::rgb565);
  b.cache.select(2, 1);  // x 8..9, memory rows 4-5
  // Row 4: pure red (R5 = 31) and G6 = 32; row 5: pure blue, black.
  const auto put = [&](unsigned row, unsigned x, uint16_t v) {
    std::memcpy(b.port.memory.data() + COLOR_BASE + (row * WIDTH + x) * 2, &v, 2);
  };
  put(4, 8, 0xf800);
  put(4, 9, 0x0400);
  put(5, 8, 0x001f);
  put(5, 9, 0x0000);
  b.cache.load(b.run);
  // Expansion (v << 3) | (v >> 2) for 5 bits, (v << 2) | (v >> 4) for 6;
  // alpha reads 255. R5 31 -> 255; G6 32 -> 128 | 2 = 130 = 0x82.
  EXPECT_EQ(b.cache.color(b.cache.index(8, 1)), 0xff0000ffu);
  EXPECT_EQ(b.cache.color(b.cache.index(9, 1)), 0xff008200u);
  EXPECT_EQ(b.cache.color(b.cache.index(8, 0)), 0xffff0000u);
  EXPECT_EQ(b.cache.color(b.cache.index(9, 0)), 0xff000000u);

  // GL's unorm rule round(c (2^n - 1) / 255): R 255 -> 31, G 128 -> round(31.62)
  // = 32, B 0 -> 0: 31 << 11 | 32 << 5 = 0xfc00.
  b.cache.color(b.cache.index(8, 1)) = 0x000080ff;
  // R 4 -> round(0.486) = 0, G 2 -> round(0.494) = 0, B 5 -> round(0.608) = 1.
  b.cache.color(b.cache.index(9, 1)) = 0x00050204;
  b.cache.write_back(b.run);
  uint16_t v;
  std::memcpy(&v, b.port.memory.data() + COLOR_BASE + (4 * WIDTH + 8) * 2, 2);
  EXPECT_EQ(v, 0xfc00);
  std::memcpy(&v, b.port.memory.data() + COLOR_BASE + (4 * WIDTH + 9) * 2, 2);
  EXPECT_EQ(v, 0x0001);
  // quantise: what a 565 buffer keeps of a colour.
  EXPECT_EQ(b.cache.quantise(0x000080ff), 0xff0082ffu);
}

TEST(TileCache, WriteBackWritesColourRowsThenDepthStencilRows) {
  CacheBench b;
  b.cache.select(2, 1);  // x 8..9, GL y 0..1
  for (int y = 0; y < 2; ++y)
    for (int x = 8; x < 10; ++x) {
      const unsigned i = b.cache.index(x, y);
      b.cache.color(i) = 0xc0000000u | uint32_t(y) << 8 | uint32_t(x);
      b.cache.depth(i) = 0xabc000u | uint32_t(x);
      b.cache.stencil(i) = uint8_t(0x10 + y);
    }
  b.cache.write_back(b.run);
  ASSERT_EQ(b.run.result().error, RasterError::none);
  // GL (9, 1) is memory row 4; (8, 0) row 5.
  EXPECT_EQ(b.port.word(COLOR_BASE + (memory_row(1) * WIDTH + 9) * 4), 0xc0000109u);
  EXPECT_EQ(b.port.word(COLOR_BASE + (memory_row(0) * WIDTH + 8) * 4), 0xc0000008u);
  EXPECT_EQ(b.port.word(DEPTH_BASE + (memory_row(1) * WIDTH + 9) * 4), 0x11abc009u);
  EXPECT_EQ(b.port.word(DEPTH_BASE + (memory_row(0) * WIDTH + 8) * 4), 0x10abc008u);
  // Column 7 is the neighbouring tile's: untouched.
  EXPECT_EQ(b.port.word(COLOR_BASE + (memory_row(1) * WIDTH + 7) * 4), 0u);
  EXPECT_EQ(b.run.result().bytes_written, 2u * (8 + 8));
}

TEST(TileCache, WriteBackStopsAtARefusedRow) {
  CacheBench b;
  b.cache.select(0, 0);
  b.port.fail_begin = COLOR_BASE + (1 * WIDTH) * 4;  // memory row 1's colour
  b.port.fail_end = b.port.fail_begin + 4;
  b.cache.write_back(b.run);
  EXPECT_EQ(b.run.result().error, RasterError::bus_error);
  EXPECT_EQ(b.run.result().error_address, b.port.fail_begin);
  EXPECT_EQ(b.run.result().bytes_written, 16u);  // row 0's colour only
}

// Fills tile (0, 0) (x 0..3, GL y 2..5) with one colour, depth and stencil.
void fill(TileCache& cache, uint32_t color, uint32_t depth, uint8_t stencil) {
  for (int y = 2; y < 6; ++y)
    for (int x = 0; x < 4; ++x) {
      const unsigned i = cache.index(x, y);
      cache.color(i) = color;
      cache.depth(i) = depth;
      cache.stencil(i) = stencil;
    }
}

TEST(TileCache, ClearIsCutToTheScissorAndGoesThroughTheWriteMasks) {
  CacheBench b;
  b.costs.tile_pixel_clear = 2;
  b.cache.select(0, 0);
  fill(b.cache, 0x11223344, 0x555555, 0xaa);
  DrawState state;
  state.scissor = true;
  state.scissor_box = {1, 3, 3, 10};  // cut to the tile: x 1..2, y 3..5, 6 pixels
  ClearCommand clear;
  clear.color = clear.depth = clear.stencil = true;
  clear.rgba = Rgba8::unpack(0xddccbbaa);
  clear.color_mask = 9;       // R and A
  clear.depth_write = false;  // depth named but not writable: kept
  clear.depth_value = 0x123456;
  clear.stencil_value = 0x0f;
  clear.stencil_write_mask = 0x3c;
  b.cache.clear(b.run, clear, state);
  for (int y = 2; y < 6; ++y)
    for (int x = 0; x < 4; ++x) {
      const unsigned i = b.cache.index(x, y);
      const bool inside = x >= 1 && x < 3 && y >= 3;
      // R (bits 0-7) and A (24-31) from the clear: 0xdd2233aa.
      EXPECT_EQ(b.cache.color(i), inside ? 0xdd2233aau : 0x11223344u) << x << "," << y;
      EXPECT_EQ(b.cache.depth(i), 0x555555u) << x << "," << y;
      // (0xaa & ~0x3c) | (0x0f & 0x3c) = 0x82 | 0x0c.
      EXPECT_EQ(b.cache.stencil(i), inside ? 0x8e : 0xaa) << x << "," << y;
    }
  EXPECT_EQ(b.run.result().tile_cycles, 6u * 2);  // a tile_pixel_clear per pixel of the area
}

TEST(TileCache, ClearWithoutScissorCoversTheTileOnly) {
  CacheBench b;
  b.cache.select(0, 0);
  fill(b.cache, 0, 0, 0);
  ClearCommand clear;
  clear.depth = true;
  clear.depth_write = true;
  clear.depth_value = 0xfedcba;
  clear.color = true;  // with no channel writable: nothing
  clear.color_mask = 0;
  b.cache.clear(b.run, clear, DrawState{});
  for (int y = 2; y < 6; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(b.cache.depth(b.cache.index(x, y)), 0xfedcbau);
      EXPECT_EQ(b.cache.color(b.cache.index(x, y)), 0u);
      EXPECT_EQ(b.cache.stencil(b.cache.index(x, y)), 0);
    }
}

TEST(TileCache, OnlyAClearOfEveryBitOfTheTileSkipsTheLoad) {
  CacheBench b;
  b.cache.select(0, 0);  // x 0..3, y 2..5
  ClearCommand all;
  all.color = all.depth = all.stencil = true;
  all.color_mask = 15;
  all.depth_write = true;
  all.stencil_write_mask = 0xff;
  DrawState state;
  EXPECT_TRUE(b.cache.clears_whole_tile(all, state));
  state.scissor = true;
  state.scissor_box = {-5, 0, 4, 6};  // contains the tile
  EXPECT_TRUE(b.cache.clears_whole_tile(all, state));
  state.scissor_box = {0, 3, 4, 6};  // misses row 2
  EXPECT_FALSE(b.cache.clears_whole_tile(all, state));
  state.scissor = false;
  auto without = [&](auto change) {
    ClearCommand c = all;
    change(c);
    return b.cache.clears_whole_tile(c, state);
  };
  EXPECT_FALSE(without([](ClearCommand& c) { c.color = false; }));
  EXPECT_FALSE(without([](ClearCommand& c) { c.depth = false; }));
  EXPECT_FALSE(without([](ClearCommand& c) { c.stencil = false; }));
  EXPECT_FALSE(without([](ClearCommand& c) { c.color_mask = 7; }));
  EXPECT_FALSE(without([](ClearCommand& c) { c.depth_write = false; }));
  EXPECT_FALSE(without([](ClearCommand& c) { c.stencil_write_mask = 0x7f; }));
}

}  // namespace
