// Reads images back through OpenImageIO (for tests and comparisons); writes
// PNG files through png_writer.h (libpng alone), which it includes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "png_writer.h"

namespace tessera {

struct Image {
  unsigned width = 0;
  unsigned height = 0;
  std::vector<uint8_t> rgba;
};
// Reads any image OpenImageIO knows as 8-bit RGBA, the values as stored
// (colour not multiplied by alpha). Throws on failure.
Image read_image(const std::string& path);

}  // namespace tessera
