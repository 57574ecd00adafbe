// The study's frame for the array back ends without tiles of their own
// (ap-pixel, ap-object): the array's CUs as tiles of 8 x 36 pixels, as
// ap-tile draws it (24 x 4 CUs: 192 x 144), the display's size where the
// user set none.
#pragma once

#include <cstdint>

#include "config/config.h"

namespace tessera::renderers {

inline constexpr unsigned STUDY_TILE_WIDTH = 8, STUDY_TILE_HEIGHT = 36;

struct StudyFrame {
  uint64_t width, height;
};

inline StudyFrame study_frame(const Config& config) {
  return {config.get_uint("array.columns") * STUDY_TILE_WIDTH, config.get_uint("array.rows") * STUDY_TILE_HEIGHT};
}

}  // namespace tessera::renderers
