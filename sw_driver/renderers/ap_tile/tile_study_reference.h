// The study's program's arithmetic (docs/spec/study_programs.md, "ap-tile
// as the study wrote it") in plain C++, on one CU's CMEM image laid out as
// StudyLayout says: every variable of the program is a CMEM variable here
// too, read and written statement by statement, so that the program can be
// checked against it on every CMEM byte (tests/sw_driver/renderers/
// ap_tile/). Every value wraps as the CU's 8-bit additions do.
#pragma once

#include <cstdint>

#include "renderers/ap_tile/tile_reference.h"
#include "renderers/ap_tile/tile_study.h"

namespace tessera::ap_tile {

// Runs `stage` (the entries are named as the tuned program's) on `cmem`.
void run_study_reference(TileStage stage, const StudyLayout& layout, uint8_t* cmem);

}  // namespace tessera::ap_tile
