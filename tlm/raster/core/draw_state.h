// The GL state a tile's triangles and clears are drawn with: the StateBlock
// of the tile's last STATE command (command_format.h) as CommandDecoder
// decodes it, or GL's defaults, which every tile's list starts from
// (README.md, "Tile loop").
#pragma once

#include <cstdint>

#include "common/fixed_function.h"
#include "raster/command_format.h"
#include "raster/core/fragment_operations.h"
#include "raster/core/rect.h"
#include "raster/datapath/texel_address.h"

namespace tessera::raster {

struct DrawState {
  uint32_t address = 0;  // of the StateBlock; 0 while the defaults apply
  uint32_t flags = StateFlag::depth_write;
  FragmentOperationsState operations;
  bool scissor = false;
  Rect scissor_box;
  TextureState texture;
  unsigned log2_width = 0, log2_height = 0;  // as stored, checked at use
  TexFilter min_filter = TexFilter::nearest, mag_filter = TexFilter::nearest;
  TexEnv env = TexEnv::modulate;
  FogMode fog_mode = FogMode::exp;  // with StateFlag::fog, from the FogState
  Rgba8 fog_color;

  bool has(StateFlag flag) const { return (flags & flag) != 0; }
};

}  // namespace tessera::raster
