// What the GL front end's unit tests run on: a host that keeps system
// memory in a vector and answers the display's and the rasterizer's
// registers stands in for the simulated SoC, a renderer that records what
// it is given stands in for a back end, and the fixture GlApi makes a
// context over the two current for each test.
#pragma once

#include <GLES/gl.h>

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "device/app_environment.h"
#include "display/display_regs.h"
#include "gl/context.h"
#include "gl/runtime.h"
#include "raster/raster_regs.h"
#include "soc/memory_map.h"

namespace tessera::test {

class VectorHost : public HostApi {
 public:
  VectorHost() : m_memory(16u << 20, 0) {}
  void compute(Op, uint64_t count) override { m_operations += count; }
  void compute_cycles(uint64_t cycles) override { m_operations += cycles; }
  uint32_t read32(uint32_t address) override {
    if (memory_map::display_regs.contains(address)) {
      switch (address - memory_map::display_regs.base) {
        case display_regs::WIDTH: return 64;
        case display_regs::HEIGHT: return 48;
        case display_regs::FORMAT: return static_cast<uint32_t>(PixelFormat::rgb565);
        case display_regs::MODE: return 0;
        default: return 0;
      }
    }
    // The rasterizer covers the display, in tiles of 32x16 (the raster back end reads these).
    if (memory_map::raster_regs.contains(address)) {
      switch (address - memory_map::raster_regs.base) {
        case raster_regs::WIDTH: return 64;
        case raster_regs::HEIGHT: return 48;
        case raster_regs::TILE_WIDTH: return 32;
        case raster_regs::TILE_HEIGHT: return 16;
        default: return 0;
      }
    }
    uint32_t v = 0;
    std::memcpy(&v, at(address, 4), 4);
    return v;
  }
  uint16_t read16(uint32_t address) override {
    uint16_t v;
    std::memcpy(&v, at(address, 2), 2);
    return v;
  }
  uint8_t read8(uint32_t address) override { return *at(address, 1); }
  void write32(uint32_t address, uint32_t value) override {
    if (address < m_memory.size()) std::memcpy(at(address, 4), &value, 4);
  }
  void write16(uint32_t address, uint16_t value) override {
    if (address < m_memory.size()) std::memcpy(at(address, 2), &value, 2);
  }
  void write8(uint32_t address, uint8_t value) override {
    if (address < m_memory.size()) *at(address, 1) = value;
  }
  void read_words(uint32_t address, uint32_t* words, unsigned count) override {
    for (unsigned i = 0; i < count; ++i) words[i] = read32(address + 4 * i);
  }
  void write_words(uint32_t address, const uint32_t* words, unsigned count) override {
    for (unsigned i = 0; i < count; ++i) write32(address + 4 * i, words[i]);
  }
  const uint8_t* load_span(uint32_t address, unsigned size, unsigned count) override {
    return at(address, size * count);
  }
  uint8_t* store_span(uint32_t address, unsigned size, unsigned count) override { return at(address, size * count); }
  void wait_irq(unsigned) override {}
  bool irq_pending(unsigned) override { return false; }
  double now_seconds() const override { return 0; }
  double clock_hz() const override { return 192e6; }
  uint64_t operations() const { return m_operations; }

 private:
  uint8_t* at(uint32_t address, unsigned bytes) {
    if (static_cast<uint64_t>(address) + bytes > m_memory.size())
      throw std::out_of_range("test host: access outside memory");
    return m_memory.data() + address;
  }
  std::vector<uint8_t> m_memory;
  uint64_t m_operations = 0;
};

class RecordingRenderer : public gl::Renderer {
 public:
  const char* name() const override { return "recording"; }
  gl::RendererCapabilities capabilities() const override { return {12, 4}; }
  unsigned width() const override { return 64; }
  unsigned height() const override { return 48; }
  PixelFormat color_format() const override { return PixelFormat::rgb565; }
  void clear(const gl::ClearRequest&) override { ++clears; }
  void draw(const gl::RasterState& s, const gl::Triangle* t, size_t n) override {
    state = s;
    triangles.insert(triangles.end(), t, t + n);
  }
  void read_pixels(int, int, int w, int h, uint8_t* rgba) override {
    std::memset(rgba, 0x5a, static_cast<size_t>(w) * h * 4);
  }
  void finish() override {}
  void present() override {}
  std::vector<gl::Triangle> triangles;
  gl::RasterState state;  // of the last draw
  int clears = 0;
};

// A current GL context over the recording renderer, for each test.
class GlApi : public ::testing::Test {
 protected:
  void SetUp() override {
    env.host = &host;
    env.heap_base = 4u << 20;
    env.heap_end = 15u << 20;
    env.frames = 1000;
    gl::set_environment(&env);
    context = std::make_unique<gl::Context>(host, renderer);
    gl::set_current_context(context.get());
  }
  void TearDown() override {
    gl::set_current_context(nullptr);
    gl::set_environment(nullptr);
  }
  void draw_triangle(const float* positions) {
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, positions);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  VectorHost host;
  AppEnvironment env;
  RecordingRenderer renderer;
  std::unique_ptr<gl::Context> context;
};

}  // namespace tessera::test
