// How the tile rasterizer's functional core reaches system memory and
// reports its work. The SystemC module implements it over its bus socket
// (accumulating bus time); a plain vector implements it for native runs and
// tests. See README.md in this folder for the order of the accesses.
#pragma once

#include <cstdint>

namespace tessera::raster {

class RasterPort {
 public:
  virtual ~RasterPort() = default;
  virtual bool read(uint32_t address, void* data, unsigned bytes) = 0;         // false: bus error
  virtual bool write(uint32_t address, const void* data, unsigned bytes) = 0;  // false: bus error
  virtual void cycles(uint64_t count) = 0;  // rasterizer clock cycles of work done since the last call
  // Tile (x, y) of the grid begins (its table entry read) and ends (written
  // back, its cycles reported): for a timeline; nothing by default.
  virtual void tile_begins(unsigned /*x*/, unsigned /*y*/) {}
  virtual void tile_ends(unsigned /*x*/, unsigned /*y*/) {}
};

}  // namespace tessera::raster
