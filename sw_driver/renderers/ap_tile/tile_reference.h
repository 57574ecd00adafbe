// The ap-tile array program's arithmetic in plain C++, on one CU's CMEM
// image laid out as CmemLayout says: the reference the program is checked
// against bit for bit (tests/sw_driver/renderers/ap_tile/), and the
// functional code the speed benchmark runs natively. Every value wraps as
// the CU's 8-bit additions do.
#pragma once

#include <cstdint>

#include "renderers/ap_tile/tile_setup.h"

namespace tessera::ap_tile {

// The program's entries, in the order the host runs a pass.
enum class TileStage { fill, depth, colour, texcoord, clear_colour, clear_depth };

// The program's label for each stage ("fill", ..., "clear_depth").
const char* stage_entry(TileStage stage);

// Runs `stage` on `cmem` (one CU's CMEM, at least the layout's extent).
void run_reference(TileStage stage, const CmemLayout& layout, uint8_t* cmem);

// A pass as the host runs it: fill, depth, colour, texcoord.
void run_reference_pass(const CmemLayout& layout, uint8_t* cmem);

}  // namespace tessera::ap_tile
