// The GL state a tile's triangles and clears are drawn with: the StateBlock
// of the tile's last STATE command (command_format.h) as CommandDecoder
// decodes it, or GL's defaults, which every tile's list starts from
// (README.md, "Tile loop").
#pragma once

#include <array>
#include <cstdint>

#include "common/fixed_function.h"
#include "raster/command_format.h"
#include "raster/core/fragment_operations.h"
#include "raster/core/rect.h"
#include "raster/datapath/texel_address.h"
#include "raster/datapath/texture_combiner.h"

namespace tessera::raster {

// One enabled texture unit of a StateFlag::texture_units state
// (command_format.h, TextureUnitState), as CommandDecoder decodes it. The
// fields are the codes of common/fixed_function.def.
struct TextureUnitDraw {
  TextureState texture;                                         // level 0: address, log2 sizes (clamped to 8), wraps
  unsigned log2_width = 0, log2_height = 0;                     // as stored, checked at use
  unsigned last_level = 0;                                      // as stored, checked at use
  std::array<uint32_t, MAX_TEXTURE_LEVEL + 1> level_address{};  // level 0's is texture.base; up to last_level
  TexFilter min_filter = TexFilter::nearest, mag_filter = TexFilter::nearest;
  TexMipmap mipmap = TexMipmap::none;  // the UNIT_MIPMAP field, bits 6-7 of mode
  TextureUnitEnv env;  // environment, base format, env colour and combiner (datapath/texture_combiner.h)
};

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
  unsigned unit_count = 0;  // with StateFlag::texture_units, 1 .. MAX_TEXTURE_UNITS, else 0
  std::array<TextureUnitDraw, MAX_TEXTURE_UNITS> unit{};

  bool has(StateFlag flag) const { return (flags & flag) != 0; }
  // Fragments are textured: the block's texture flag, or texture units
  // (whose state replaces the block's texture words and flag).
  bool textured() const { return has(StateFlag::texture) || unit_count > 0; }
};

}  // namespace tessera::raster
