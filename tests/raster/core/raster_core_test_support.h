// What the tests of the rasterizer's functional core share: the plain
// memory that stands for system memory behind the RasterPort, the run a
// stage is tested in, and the StateBlock words the driver writes for GL's
// default state.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "common/fixed_function.h"
#include "raster/command_format.h"
#include "raster/core/raster_port.h"
#include "raster/core/run_context.h"

namespace tessera::raster::test {

// RasterPort over a byte vector; accesses that touch [fail_begin, fail_end)
// or leave the memory get an error response. Every read address is kept,
// so that a test can check which words a stage fetched.
class VectorPort : public RasterPort {
 public:
  explicit VectorPort(size_t size) : memory(size, 0) {}
  bool read(uint32_t address, void* data, unsigned bytes) override {
    if (!ok(address, bytes)) return false;
    std::memcpy(data, memory.data() + address, bytes);
    reads.push_back(address);
    return true;
  }
  bool write(uint32_t address, const void* data, unsigned bytes) override {
    if (!ok(address, bytes)) return false;
    std::memcpy(memory.data() + address, data, bytes);
    return true;
  }
  void cycles(uint64_t count) override { total_cycles += count; }

  uint32_t word(uint32_t address) const {
    uint32_t v;
    std::memcpy(&v, memory.data() + address, 4);
    return v;
  }
  void set_word(uint32_t address, uint32_t v) { std::memcpy(memory.data() + address, &v, 4); }
  void set_words(uint32_t address, std::initializer_list<uint32_t> words) {
    for (uint32_t w : words) {
      set_word(address, w);
      address += 4;
    }
  }

  std::vector<uint8_t> memory;
  uint32_t fail_begin = 0, fail_end = 0;
  uint64_t total_cycles = 0;
  std::vector<uint32_t> reads;  // the address of every read that succeeded, in order

 private:
  bool ok(uint32_t address, unsigned bytes) const {
    const uint64_t end = uint64_t{address} + bytes;
    if (end > memory.size()) return false;
    return end <= fail_begin || address >= fail_end;
  }
};

// What a stage is tested in: a VectorPort of `memory_bytes`, the default
// cycle costs, a configuration (which a test may change before the stage
// reads it) and the RunContext over them.
struct StageRun {
  StageRun(size_t memory_bytes, const RunConfig& run_config)
      : port(memory_bytes), config(run_config), run(port, costs, config) {}
  VectorPort port;
  CycleCosts costs;
  RunConfig config;
  RunContext run;
};

// StateBlock::blend with the logic op COPY.
inline uint32_t blend_codes(BlendFactor src, BlendFactor dst) {
  return code_of(src) << BLEND_SRC_SHIFT | code_of(dst) << BLEND_DST_SHIFT |
         code_of(LogicOp::copy) << BLEND_LOGIC_OP_SHIFT;
}

// GL's defaults as the driver writes them in a StateBlock.
inline StateBlock default_state() {
  StateBlock s{};
  s.flags = depth_write;
  s.depth_func = code_of(CompareFunc::less);
  s.alpha_func = code_of(CompareFunc::always);
  s.stencil_func = code_of(CompareFunc::always) | 0xffu << 16 | 0xffu << 24;
  s.blend = blend_codes(BlendFactor::one, BlendFactor::zero);
  s.color_mask = 15;
  return s;
}

}  // namespace tessera::raster::test
