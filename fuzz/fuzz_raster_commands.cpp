// Fuzz target: the rasterizer's command-list decoder and the pipeline behind
// it (tlm/raster/core), run by TileRasterizer::run over a memory image made
// by the fuzzer: the tile table, the command lists, the state blocks and
// the triangle records of command_format.h, all hand-built bytes.
//
// Input: a 15-byte header, then the memory image placed at address 0 of a
// 256 KiB system memory (the tile table is at address 0).
//   byte 0      flags: bit 0 rgba8888 (else rgb565), bits 1-2 reciprocal
//               method (mod 3), bit 3 a large screen (up to 520 pixels)
//   bytes 1-4   width, height (16 bits each): 1 + value mod 128 (mod 520 large)
//   bytes 5-6   tile width, tile height: 1 + value (1..256, raster.tile_*)
//   bytes 7-14  colour and depth buffer addresses (32 bits each, any value)
//
// Checks: run() returns (it never throws on bad input), its error is one of
// RasterError's codes, its counters agree with one another, and it writes
// only inside the two frame buffers (modulo 2^32, as the hardware adds).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "common/pixel_format.h"
#include "fuzz_support.h"
#include "raster/core/tile_rasterizer.h"

namespace {

using namespace tessera::raster;
using tessera::fuzz::fail;

constexpr uint32_t MEMORY_BYTES = 256 * 1024;

struct Region {
  uint32_t base = 0;
  uint64_t bytes = 0;
  bool holds(uint32_t address, unsigned size) const { return uint64_t{address - base} + size <= bytes; }
};

class FuzzPort : public RasterPort {
 public:
  FuzzPort() : memory(MEMORY_BYTES, 0) {}
  bool read(uint32_t address, void* data, unsigned bytes) override {
    if (!inside(address, bytes)) return false;
    std::memcpy(data, memory.data() + address, bytes);
    return true;
  }
  bool write(uint32_t address, const void* data, unsigned bytes) override {
    if (!color.holds(address, bytes) && !depth.holds(address, bytes))
      fail("a write of " + std::to_string(bytes) + " bytes at " + std::to_string(address) +
           " outside the frame buffers");
    if (!inside(address, bytes)) return false;
    std::memcpy(memory.data() + address, data, bytes);
    return true;
  }
  void cycles(uint64_t count) override { total_cycles += count; }

  std::vector<uint8_t> memory;
  Region color, depth;
  uint64_t total_cycles = 0;

 private:
  bool inside(uint32_t address, unsigned bytes) const { return uint64_t{address} + bytes <= memory.size(); }
};

}  // namespace

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tessera::fuzz::ByteReader header(data, size);
  const uint8_t flags = header.u8();
  const unsigned screen_limit = (flags & 8) ? 520 : 128;
  RunConfig config;
  config.color_format = (flags & 1) ? tessera::PixelFormat::rgba8888 : tessera::PixelFormat::rgb565;
  config.recip_method = static_cast<tessera::raster::RecipMethod>(((flags >> 1) & 3) % 3);
  config.width = 1 + header.u16() % screen_limit;
  config.height = 1 + header.u16() % screen_limit;
  config.tile_width = 1 + header.u8();
  config.tile_height = 1 + header.u8();
  config.tile_table = 0;
  config.color_base = header.u32();
  config.depth_base = header.u32();

  static FuzzPort port;
  std::fill(port.memory.begin(), port.memory.end(), 0);
  port.total_cycles = 0;
  const size_t image = header.remaining();
  if (image > MEMORY_BYTES) return 0;
  std::memcpy(port.memory.data(), data + (size - image), image);
  const uint64_t pixels = uint64_t{config.width} * config.height;
  port.color = {config.color_base, pixels * tessera::bytes_per_pixel(config.color_format)};
  port.depth = {config.depth_base, pixels * 4};

  TileRasterizer rasterizer(port);
  const RunResult result = rasterizer.run(config);

  if (static_cast<uint32_t>(result.error) > static_cast<uint32_t>(RasterError::bad_reciprocal))
    fail("an error code outside RasterError");
  if (result.error == RasterError::none && result.error_address != 0) fail("an error address without an error");
  if (result.fragments_written > result.fragments) fail("more fragments written than generated");
  const uint64_t tiles_x = (config.width + config.tile_width - 1) / config.tile_width;
  const uint64_t tiles_y = (config.height + config.tile_height - 1) / config.tile_height;
  if (result.tiles > tiles_x * tiles_y) fail("more tiles run than the screen has");
  if (result.setup_cycles + result.tile_cycles + result.fragment_cycles + result.texel_cycles != port.total_cycles)
    fail("the cycle buckets do not add up to the cycles reported");
  return 0;
}
