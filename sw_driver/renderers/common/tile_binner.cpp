#include "renderers/common/tile_binner.h"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

namespace tessera::renderers {

TileBinner::TileBinner(const TileGrid& grid) : m_grid(grid) {
  if (grid.width == 0 || grid.height == 0 || grid.tile_width == 0 || grid.tile_height == 0)
    throw std::invalid_argument("tile binner: screen " + std::to_string(grid.width) + "x" +
                                std::to_string(grid.height) + " in tiles of " + std::to_string(grid.tile_width) + "x" +
                                std::to_string(grid.tile_height) + ": no size may be zero");
}

TileRange TileBinner::tiles_of_pixels(int x0, int y0, int x1, int y1) const {
  const int w = static_cast<int>(m_grid.width), h = static_cast<int>(m_grid.height);
  if (x1 < x0 || y1 < y0 || x1 < 0 || y1 < 0 || x0 >= w || y0 >= h) return {};
  x0 = std::clamp(x0, 0, w - 1), x1 = std::clamp(x1, 0, w - 1);
  y0 = std::clamp(y0, 0, h - 1), y1 = std::clamp(y1, 0, h - 1);
  // Tile rows count from the top; GL rows from the bottom.
  TileRange range;
  range.x0 = static_cast<unsigned>(x0) / m_grid.tile_width;
  range.x1 = static_cast<unsigned>(x1) / m_grid.tile_width;
  range.y0 = static_cast<unsigned>(h - 1 - y1) / m_grid.tile_height;
  range.y1 = static_cast<unsigned>(h - 1 - y0) / m_grid.tile_height;
  return range;
}

uint32_t TileBinner::add(uint32_t state, const TileRange& tiles) {
  if (!tiles.empty() && (tiles.x1 >= m_grid.tiles_x() || tiles.y1 >= m_grid.tiles_y()))
    throw std::out_of_range("tile binner: tiles up to (" + std::to_string(tiles.x1) + ", " + std::to_string(tiles.y1) +
                            ") outside the grid of " + std::to_string(m_grid.tiles_x()) + "x" +
                            std::to_string(m_grid.tiles_y()));
  m_commands.push_back({state, tiles});
  return static_cast<uint32_t>(m_commands.size() - 1);
}

std::vector<std::vector<BinEntry>> TileBinner::bin() const {
  const unsigned tiles_x = m_grid.tiles_x();
  std::vector<std::vector<BinEntry>> lists(m_grid.tiles());
  std::vector<std::optional<uint32_t>> tile_state(lists.size());
  for (uint32_t number = 0; number < m_commands.size(); ++number) {
    const Command& command = m_commands[number];
    if (command.tiles.empty()) continue;
    for (unsigned ty = command.tiles.y0; ty <= command.tiles.y1; ++ty)
      for (unsigned tx = command.tiles.x0; tx <= command.tiles.x1; ++tx) {
        const unsigned tile = ty * tiles_x + tx;
        std::vector<BinEntry>& list = lists[tile];
        if (tile_state[tile] != command.state) {
          list.push_back({BinEntry::Kind::state, command.state});
          tile_state[tile] = command.state;
        }
        list.push_back({BinEntry::Kind::command, number});
      }
  }
  return lists;
}

}  // namespace tessera::renderers
