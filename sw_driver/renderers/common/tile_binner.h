// Sort-middle binning for the tile-based back ends (raster; ap-tile, whose
// 192x144 frame is 24 x 4 tiles of 8 x 36 pixels, one per CU, next): a
// frame's commands, recorded in the application's order with the tiles they
// touch and the state they need, become one list per tile that keeps that
// order and puts a STATE entry wherever the tile's current state changes.
// It knows nothing of any command format: a command is a number in issue
// order, a state an id the back end chooses; the back end encodes the lists.
// Plain C++, no SystemC and no host charges (the back end charges them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera::renderers {

// A screen of width x height pixels cut into tiles of tile_width x
// tile_height, numbered row by row from the top left (tile = ty * tiles_x()
// + tx). When a size is not a multiple of the tile's, the last column or
// row of tiles is partial.
struct TileGrid {
  unsigned width = 0, height = 0;
  unsigned tile_width = 0, tile_height = 0;

  unsigned tiles_x() const { return (width + tile_width - 1) / tile_width; }
  unsigned tiles_y() const { return (height + tile_height - 1) / tile_height; }
  unsigned tiles() const { return tiles_x() * tiles_y(); }
};

// The tiles [x0, x1] x [y0, y1], inclusive, tile row 0 at the top. The
// default range is empty.
struct TileRange {
  unsigned x0 = 1, y0 = 1, x1 = 0, y1 = 0;

  bool empty() const { return x1 < x0 || y1 < y0; }
  unsigned count() const { return empty() ? 0 : (x1 - x0 + 1) * (y1 - y0 + 1); }
  bool operator==(const TileRange& other) const {
    return x0 == other.x0 && y0 == other.y0 && x1 == other.x1 && y1 == other.y1;
  }
};

// One entry of a tile's list: the state the following commands need, or a
// command (its number in issue order, as TileBinner::add returned it).
struct BinEntry {
  enum class Kind : uint8_t { state, command };
  Kind kind;
  uint32_t index;

  bool operator==(const BinEntry& other) const { return kind == other.kind && index == other.index; }
};

class TileBinner {
 public:
  // Throws std::invalid_argument for a screen or tile size of zero.
  explicit TileBinner(const TileGrid& grid);

  const TileGrid& grid() const { return m_grid; }

  // The tiles that the pixels [x0, x1] x [y0, y1] (inclusive, in GL's window
  // coordinates: row 0 at the BOTTOM of the screen) touch. A box that
  // reaches past an edge (a triangle's bounding box with its margin) is
  // clamped to the screen and takes the tiles along that edge; a box wholly
  // off the screen, or inverted (x1 < x0 or y1 < y0), touches none.
  TileRange tiles_of_pixels(int x0, int y0, int x1, int y1) const;

  // Records the next command: it needs state `state` and goes to `tiles`
  // (an empty range: to no tile). Returns its number, from 0 in issue order.
  uint32_t add(uint32_t state, const TileRange& tiles);
  size_t commands() const { return m_commands.size(); }

  // One list per tile (index ty * tiles_x + tx): every command recorded
  // since the last clear() whose range holds the tile, in issue order, each
  // preceded by a STATE entry when its state differs from that of the
  // tile's previous command (always before the tile's first command).
  std::vector<std::vector<BinEntry>> bin() const;

  // Forgets the recorded commands (the next frame's numbers start at 0).
  void clear() { m_commands.clear(); }

 private:
  struct Command {
    uint32_t state;
    TileRange tiles;
  };

  TileGrid m_grid;
  std::vector<Command> m_commands;
};

}  // namespace tessera::renderers
