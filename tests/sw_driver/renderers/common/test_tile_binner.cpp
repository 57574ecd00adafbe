// Unit tests of the tile binner (sw_driver/renderers/common/tile_binner.h):
// the tiles a pixel box touches on the raster back end's 320x240 screen in
// 32x16 tiles, on ap-tile's 192x144 screen in 8x36 tiles (24 x 4, one per
// CU) and on screens that are not a multiple of the tile; and the per-tile
// lists: issue order, STATE entries where a tile's state changes, empty and
// single-tile cases. Expected ranges are worked out by hand from the
// definition (GL row y is picture row height-1-y; tile = row / tile size).
#include <gtest/gtest.h>

#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderers/common/tile_binner.h"

namespace tessera::renderers {

void PrintTo(const BinEntry& entry, std::ostream* out) {
  *out << (entry.kind == BinEntry::Kind::state ? "STATE " : "CMD ") << entry.index;
}
void PrintTo(const TileRange& range, std::ostream* out) {
  if (range.empty())
    *out << "(empty)";
  else
    *out << "(" << range.x0 << ", " << range.y0 << ")-(" << range.x1 << ", " << range.y1 << ")";
}

namespace {

constexpr TileGrid RASTER{320, 240, 32, 16};
constexpr TileGrid AP_TILE{192, 144, 8, 36};

BinEntry state(uint32_t id) {
  return {BinEntry::Kind::state, id};
}
BinEntry command(uint32_t number) {
  return {BinEntry::Kind::command, number};
}
TileRange tiles(unsigned x0, unsigned y0, unsigned x1, unsigned y1) {
  TileRange range;
  range.x0 = x0, range.y0 = y0, range.x1 = x1, range.y1 = y1;
  return range;
}
using List = std::vector<BinEntry>;

TEST(TileGrid, CountsTilesRoundingPartialOnesUp) {
  EXPECT_EQ(RASTER.tiles_x(), 10u);
  EXPECT_EQ(RASTER.tiles_y(), 15u);
  EXPECT_EQ(RASTER.tiles(), 150u);
  EXPECT_EQ(AP_TILE.tiles_x(), 24u);
  EXPECT_EQ(AP_TILE.tiles_y(), 4u);
  EXPECT_EQ(AP_TILE.tiles(), 96u);  // one per CU
  const TileGrid odd{100, 50, 32, 16};
  EXPECT_EQ(odd.tiles_x(), 4u);  // 32, 32, 32, 4 columns
  EXPECT_EQ(odd.tiles_y(), 4u);  // 16, 16, 16, 2 lines
  const TileGrid one{5, 3, 8, 36};
  EXPECT_EQ(one.tiles(), 1u);
}

TEST(TileRange, EmptyAndCount) {
  EXPECT_TRUE(TileRange{}.empty());
  EXPECT_EQ(TileRange{}.count(), 0u);
  EXPECT_FALSE(tiles(3, 2, 3, 2).empty());
  EXPECT_EQ(tiles(3, 2, 3, 2).count(), 1u);
  EXPECT_EQ(tiles(0, 0, 23, 3).count(), 96u);
  EXPECT_TRUE(tiles(4, 0, 3, 0).empty());
}

TEST(TileBinner, ZeroSizesAreRejected) {
  EXPECT_THROW(TileBinner(TileGrid{0, 240, 32, 16}), std::invalid_argument);
  EXPECT_THROW(TileBinner(TileGrid{320, 0, 32, 16}), std::invalid_argument);
  EXPECT_THROW(TileBinner(TileGrid{320, 240, 0, 16}), std::invalid_argument);
  EXPECT_THROW(TileBinner(TileGrid{320, 240, 32, 0}), std::invalid_argument);
}

TEST(TileBinner, WholeScreenTouchesEveryTile) {
  EXPECT_EQ(TileBinner(RASTER).tiles_of_pixels(0, 0, 319, 239), tiles(0, 0, 9, 14));
  EXPECT_EQ(TileBinner(AP_TILE).tiles_of_pixels(0, 0, 191, 143), tiles(0, 0, 23, 3));
}

// GL's row 0 is the bottom of the screen; tile row 0 is the top.
TEST(TileBinner, CornerPixelsTakeTheCornerTiles) {
  const TileBinner raster(RASTER);
  EXPECT_EQ(raster.tiles_of_pixels(0, 0, 0, 0), tiles(0, 14, 0, 14));        // bottom left
  EXPECT_EQ(raster.tiles_of_pixels(319, 0, 319, 0), tiles(9, 14, 9, 14));    // bottom right
  EXPECT_EQ(raster.tiles_of_pixels(0, 239, 0, 239), tiles(0, 0, 0, 0));      // top left
  EXPECT_EQ(raster.tiles_of_pixels(319, 239, 319, 239), tiles(9, 0, 9, 0));  // top right
  const TileBinner ap(AP_TILE);
  EXPECT_EQ(ap.tiles_of_pixels(0, 0, 0, 0), tiles(0, 3, 0, 3));
  EXPECT_EQ(ap.tiles_of_pixels(191, 0, 191, 0), tiles(23, 3, 23, 3));
  EXPECT_EQ(ap.tiles_of_pixels(0, 143, 0, 143), tiles(0, 0, 0, 0));
  EXPECT_EQ(ap.tiles_of_pixels(191, 143, 191, 143), tiles(23, 0, 23, 0));
}

TEST(TileBinner, TileEdgesFallWhereTheTileSizeSays) {
  const TileBinner ap(AP_TILE);
  // Columns of 8: pixels 7 and 8 are in columns 0 and 1.
  EXPECT_EQ(ap.tiles_of_pixels(7, 0, 7, 0).x0, 0u);
  EXPECT_EQ(ap.tiles_of_pixels(8, 0, 8, 0).x0, 1u);
  EXPECT_EQ(ap.tiles_of_pixels(183, 0, 183, 0).x0, 22u);
  EXPECT_EQ(ap.tiles_of_pixels(184, 0, 184, 0).x0, 23u);
  // Rows of 36 from the top: GL row 108 is picture row 35 (tile row 0),
  // GL row 107 picture row 36 (tile row 1); GL rows 0..35 are tile row 3.
  EXPECT_EQ(ap.tiles_of_pixels(0, 108, 0, 108).y0, 0u);
  EXPECT_EQ(ap.tiles_of_pixels(0, 107, 0, 107).y0, 1u);
  EXPECT_EQ(ap.tiles_of_pixels(0, 35, 0, 35).y0, 3u);
  EXPECT_EQ(ap.tiles_of_pixels(0, 36, 0, 36).y0, 2u);
  // A box across one vertical and one horizontal tile edge: four tiles.
  EXPECT_EQ(ap.tiles_of_pixels(7, 107, 8, 108), tiles(0, 0, 1, 1));
  // A box inside one CU's tile: that tile only.
  EXPECT_EQ(ap.tiles_of_pixels(17, 40, 22, 70), tiles(2, 2, 2, 2));
}

TEST(TileBinner, BoxesReachingPastAnEdgeAreClampedToIt) {
  const TileBinner raster(RASTER);
  // A triangle's box with its one-pixel margin at the screen's corners.
  EXPECT_EQ(raster.tiles_of_pixels(-1, -1, 10, 10), tiles(0, 14, 0, 14));
  EXPECT_EQ(raster.tiles_of_pixels(310, 230, 320, 240), tiles(9, 0, 9, 0));
  EXPECT_EQ(raster.tiles_of_pixels(-1000, -1000, 1000, 1000), tiles(0, 0, 9, 14));
  const TileBinner ap(AP_TILE);
  EXPECT_EQ(ap.tiles_of_pixels(-5, 100, 3, 200), tiles(0, 0, 0, 1));
}

// A triangle wholly off the screen (possible with a viewport that reaches
// past it: GL clips to the view volume, not to the screen) draws nothing, so
// it goes to no tile, whatever side of the screen it is on; so does a
// scissor box off the screen.
TEST(TileBinner, BoxesWhollyOffTheScreenTouchNothing) {
  for (const TileGrid& grid : {RASTER, AP_TILE, TileGrid{100, 50, 32, 16}}) {
    const TileBinner binner(grid);
    const int w = static_cast<int>(grid.width), h = static_cast<int>(grid.height);
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    EXPECT_TRUE(binner.tiles_of_pixels(-20, 10, -1, 20).empty());        // left
    EXPECT_TRUE(binner.tiles_of_pixels(w, 10, w + 20, 20).empty());      // right
    EXPECT_TRUE(binner.tiles_of_pixels(10, -20, 20, -1).empty());        // below
    EXPECT_TRUE(binner.tiles_of_pixels(10, h, 20, h + 20).empty());      // above
    EXPECT_TRUE(binner.tiles_of_pixels(-20, -20, -1, -1).empty());       // bottom left
    EXPECT_TRUE(binner.tiles_of_pixels(w, h, w + 5, h + 5).empty());     // top right
    EXPECT_TRUE(binner.tiles_of_pixels(-20, h, -1, h + 20).empty());     // top left
    EXPECT_TRUE(binner.tiles_of_pixels(w, -20, w + 20, -1).empty());     // bottom right
    EXPECT_TRUE(binner.tiles_of_pixels(-100, -5, w + 100, -1).empty());  // wide, below
    // One pixel inside is enough.
    EXPECT_FALSE(binner.tiles_of_pixels(-20, -20, 0, 0).empty());
    EXPECT_FALSE(binner.tiles_of_pixels(w - 1, h - 1, w + 20, h + 20).empty());
  }
  TileBinner raster(RASTER);
  raster.add(0, raster.tiles_of_pixels(-50, 100, -10, 120));
  raster.add(0, raster.tiles_of_pixels(400, 100, 420, 120));
  for (const List& list : raster.bin()) EXPECT_TRUE(list.empty());
}

TEST(TileBinner, InvertedBoxesTouchNothing) {
  const TileBinner raster(RASTER);
  EXPECT_TRUE(raster.tiles_of_pixels(10, 0, 9, 5).empty());
  EXPECT_TRUE(raster.tiles_of_pixels(0, 10, 5, 9).empty());
}

// The raster back end bins a scissored clear by its scissor box.
TEST(TileBinner, ScissorBoxes) {
  const TileBinner raster(RASTER);
  // x 40..69, GL y 20..29 = picture rows 210..219: columns 1..2, row 13.
  EXPECT_EQ(raster.tiles_of_pixels(40, 20, 40 + 30 - 1, 20 + 10 - 1), tiles(1, 13, 2, 13));
  // One pixel.
  EXPECT_EQ(raster.tiles_of_pixels(64, 224, 64, 224), tiles(2, 0, 2, 0));
  // A scissor larger than the screen clears every tile.
  EXPECT_EQ(raster.tiles_of_pixels(-10, -10, 400, 300), tiles(0, 0, 9, 14));
}

TEST(TileBinner, ScreensThatAreNotAMultipleOfTheTile) {
  const TileBinner odd(TileGrid{100, 50, 32, 16});
  EXPECT_EQ(odd.tiles_of_pixels(0, 0, 99, 49), tiles(0, 0, 3, 3));
  // Column 3 holds pixels 96..99; the last (partial) tile row holds
  // picture rows 48 and 49, which are GL rows 1 and 0.
  EXPECT_EQ(odd.tiles_of_pixels(96, 0, 99, 1), tiles(3, 3, 3, 3));
  EXPECT_EQ(odd.tiles_of_pixels(95, 2, 95, 2), tiles(2, 2, 2, 2));
  EXPECT_EQ(odd.tiles_of_pixels(90, 40, 200, 100), tiles(2, 0, 3, 0));
  // A screen smaller than one tile has one tile.
  const TileBinner small(TileGrid{5, 3, 8, 36});
  EXPECT_EQ(small.tiles_of_pixels(-1, -1, 5, 3), tiles(0, 0, 0, 0));
}

TEST(TileBinner, NoCommandsNoEntries) {
  const TileBinner raster(RASTER);
  const auto lists = raster.bin();
  ASSERT_EQ(lists.size(), 150u);
  for (const List& list : lists) EXPECT_TRUE(list.empty());
}

TEST(TileBinner, SingleTileCommandGoesToThatTileOnly) {
  TileBinner ap(AP_TILE);
  EXPECT_EQ(ap.add(7, ap.tiles_of_pixels(17, 40, 22, 70)), 0u);
  EXPECT_EQ(ap.commands(), 1u);
  const auto lists = ap.bin();
  ASSERT_EQ(lists.size(), 96u);
  const unsigned tile = 2 * 24 + 2;
  for (unsigned t = 0; t < lists.size(); ++t)
    EXPECT_EQ(lists[t], t == tile ? (List{state(7), command(0)}) : List{}) << "tile " << t;
}

TEST(TileBinner, EveryCommandInIssueOrderWithOneStatePerChange) {
  TileBinner binner(TileGrid{64, 16, 32, 16});  // two tiles: A (left), B (right)
  binner.add(0, tiles(0, 0, 1, 0));             // 0: both
  binner.add(0, tiles(1, 0, 1, 0));             // 1: B, same state
  binner.add(1, tiles(1, 0, 1, 0));             // 2: B, new state
  binner.add(0, tiles(0, 0, 1, 0));             // 3: both, back to state 0
  binner.add(0, tiles(0, 0, 0, 0));             // 4: A
  const auto lists = binner.bin();
  ASSERT_EQ(lists.size(), 2u);
  EXPECT_EQ(lists[0], (List{state(0), command(0), command(3), command(4)}));
  EXPECT_EQ(lists[1], (List{state(0), command(0), command(1), state(1), command(2), state(0), command(3)}));
}

// A scissored clear carries a state of its own (its scissor): the tiles it
// touches change state twice, the others once.
TEST(TileBinner, ScissoredClearThenDraw) {
  TileBinner raster(RASTER);
  raster.add(5, raster.tiles_of_pixels(40, 20, 69, 29));  // clear: tiles (1..2, 13)
  raster.add(6, raster.tiles_of_pixels(0, 0, 319, 239));  // full-screen triangle
  const auto lists = raster.bin();
  for (unsigned ty = 0; ty < 15; ++ty)
    for (unsigned tx = 0; tx < 10; ++tx) {
      const bool cleared = ty == 13 && (tx == 1 || tx == 2);
      EXPECT_EQ(lists[ty * 10 + tx],
                cleared ? (List{state(5), command(0), state(6), command(1)}) : (List{state(6), command(1)}))
          << "tile " << tx << ", " << ty;
    }
}

TEST(TileBinner, StateIsTrackedPerTile) {
  TileBinner ap(AP_TILE);
  // State 1 in CU tile 0 only; state 2 everywhere; state 1 again everywhere.
  ap.add(1, tiles(0, 0, 0, 0));
  ap.add(2, tiles(0, 0, 23, 3));
  ap.add(2, tiles(5, 1, 5, 1));
  ap.add(1, tiles(0, 0, 23, 3));
  const auto lists = ap.bin();
  EXPECT_EQ(lists[0], (List{state(1), command(0), state(2), command(1), state(1), command(3)}));
  EXPECT_EQ(lists[24 + 5], (List{state(2), command(1), command(2), state(1), command(3)}));
  EXPECT_EQ(lists[95], (List{state(2), command(1), state(1), command(3)}));
  size_t entries = 0;
  for (const List& list : lists) entries += list.size();
  EXPECT_EQ(entries, 2u + 2 * 96 + 1 + 2 * 96);
}

TEST(TileBinner, EmptyRangesGoNowhereButKeepTheirNumber) {
  TileBinner binner(RASTER);
  EXPECT_EQ(binner.add(0, TileRange{}), 0u);
  EXPECT_EQ(binner.add(0, binner.tiles_of_pixels(5, 5, 4, 4)), 1u);
  EXPECT_EQ(binner.add(3, tiles(0, 0, 0, 0)), 2u);
  const auto lists = binner.bin();
  EXPECT_EQ(lists[0], (List{state(3), command(2)}));
  for (unsigned t = 1; t < lists.size(); ++t) EXPECT_TRUE(lists[t].empty());
}

TEST(TileBinner, RangesOutsideTheGridAreRejected) {
  TileBinner ap(AP_TILE);
  EXPECT_THROW(ap.add(0, tiles(0, 0, 24, 0)), std::out_of_range);
  EXPECT_THROW(ap.add(0, tiles(0, 0, 0, 4)), std::out_of_range);
  EXPECT_EQ(ap.commands(), 0u);
}

TEST(TileBinner, ClearStartsTheNextFrame) {
  TileBinner binner(TileGrid{32, 16, 32, 16});
  binner.add(4, tiles(0, 0, 0, 0));
  EXPECT_EQ(binner.bin()[0], (List{state(4), command(0)}));
  binner.clear();
  EXPECT_EQ(binner.commands(), 0u);
  EXPECT_TRUE(binner.bin()[0].empty());
  // The next frame's lists start with their state again, and numbers from 0.
  EXPECT_EQ(binner.add(4, tiles(0, 0, 0, 0)), 0u);
  EXPECT_EQ(binner.bin()[0], (List{state(4), command(0)}));
}

}  // namespace
}  // namespace tessera::renderers
