// Writes displayed frames as PNG files through OpenImageIO, and reads PNG
// files back (for tests and comparisons).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tessera {

// The PNG file of 8-bit RGBA pixels (row 0 at the top), in memory.
std::vector<unsigned char> encode_png(unsigned width, unsigned height, const std::vector<uint8_t>& rgba);
// Writes them as a PNG file, whole or not at all (tools/common/output_file.h).
// Throws std::runtime_error naming the file and the reason on failure.
void write_png(const std::string& path, unsigned width, unsigned height, const std::vector<uint8_t>& rgba);

struct Image {
  unsigned width = 0;
  unsigned height = 0;
  std::vector<uint8_t> rgba;
};
// Reads any image OpenImageIO knows as 8-bit RGBA, the values as stored
// (colour not multiplied by alpha). Throws on failure.
Image read_image(const std::string& path);

}  // namespace tessera
