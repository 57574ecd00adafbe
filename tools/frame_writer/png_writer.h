// Writes displayed frames as PNG files through libpng alone: soc_sim links
// this and not OpenImageIO, whose ~260 shared libraries cost a run about
// 0.3 s and 95 MiB before its first frame (issue 13, item 5). Reading
// images (any format) stays with OpenImageIO, in frame_writer.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tessera {

// The PNG file of 8-bit RGBA pixels (row 0 at the top), in memory: colour
// not multiplied by alpha, compression level 1, no row filter, and the
// chunks IHDR, oFFs (0, 0), IDAT, IEND: byte for byte what the earlier
// OpenImageIO writer produced with the same settings. Throws
// std::invalid_argument if `rgba` is not width x height x 4 bytes,
// std::runtime_error if libpng fails.
std::vector<unsigned char> encode_png(unsigned width, unsigned height, const std::vector<uint8_t>& rgba);
// Writes them as a PNG file, whole or not at all (tools/common/output_file.h).
// Throws std::runtime_error naming the file and the reason on failure.
void write_png(const std::string& path, unsigned width, unsigned height, const std::vector<uint8_t>& rgba);

}  // namespace tessera
