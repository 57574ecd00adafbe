// The `raster` back end: the GL front end's triangles drawn by the
// fixed-function tile rasterizer (tlm/raster). The driver does the sort-middle
// half of the work on the host: it records the frame's clears, state changes
// and triangles, and when the frame is needed (present, finish, read_pixels)
// bins them into one command list per tile, writes the lists, the triangle
// records, the state blocks and the tile table into system memory
// (raster/command_format.h) over the bus, starts the rasterizer and sleeps
// until its interrupt. Presenting then goes through the display driver, as
// for the arm back end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "device/app_environment.h"
#include "device/display_driver.h"
#include "gl/renderer.h"
#include "raster/command_format.h"
#include "renderers/backend_entry_points.h"
#include "renderers/common/tile_binner.h"
#include "renderers/common/unsupported_state.h"

namespace tessera::raster_backend {

class RasterRenderer : public gl::Renderer {
 public:
  explicit RasterRenderer(AppEnvironment& env);

  // One word per pixel: depth in bits 0-23, stencil in 24-31 (DEPTH_BASE in
  // raster_regs.def).

  const char* name() const override { return "tessera raster (fixed-function tile rasterizer)"; }
  gl::RendererCapabilities capabilities() const override { return backends::raster::CAPABILITIES; }
  unsigned width() const override { return m_display.width(); }
  unsigned height() const override { return m_display.height(); }
  PixelFormat color_format() const override { return m_display.format(); }
  void clear(const gl::ClearRequest& request) override;
  void draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) override;
  void read_pixels(int x, int y, int width, int height, uint8_t* rgba) override;
  void finish() override { flush(); }
  void present() override;

  // Runs the rasterizer over everything recorded since the last flush.
  void flush();

 private:
  // One recorded command, numbered in issue order as m_binner numbers it;
  // the binner keeps its state (into m_states) and its tile range.
  struct Command {
    raster::Opcode opcode;
    uint32_t index;  // into m_clears (clear) or m_triangles (triangle)
  };
  struct ClearWords {
    uint32_t words[4];
  };

  // A state block, the FogState that follows it in memory with
  // StateFlag::fog and the texture unit states with StateFlag::texture_units:
  // raster::state_block_bytes(block.flags, units_header.count) bytes are
  // written, the extensions in command_format.h's order.
  struct StateRecord {
    raster::StateBlock block;
    raster::FogState fog;
    // With StateFlag::texture_units: the header and its units (zeros without).
    raster::TextureUnitsHeader units_header{};
    raster::TextureUnitState units[raster::MAX_TEXTURE_UNITS]{};
    // Each unit's level table (the addresses of levels 1 .. its last level):
    // flush writes it into the arena after the state blocks and fills in
    // units[u].level_table.
    uint32_t level_tables[raster::MAX_TEXTURE_UNITS][raster::MAX_TEXTURE_LEVEL]{};
  };
  // A triangle record, its TriangleFog and its further units' coordinates:
  // raster::triangle_record_bytes(state_flags, units) bytes are written.
  struct TriangleWords {
    raster::TriangleRecord record;
    raster::TriangleFog fog;
    uint32_t state_flags;
    // With StateFlag::texture_units: the units after the first (`units` in all).
    uint32_t units = 0;
    raster::TriangleUnitCoords unit_coords[raster::MAX_TEXTURE_UNITS - 1]{};
  };
  // The extensions follow their blocks directly, as command_format.h lays them out.
  static_assert(offsetof(StateRecord, fog) == sizeof(raster::StateBlock), "FogState right after the block");
  static_assert(offsetof(TriangleWords, fog) == sizeof(raster::TriangleRecord), "TriangleFog right after the record");

  uint32_t add_state(const StateRecord& state);
  uint32_t arena(uint32_t bytes);
  void write_block(uint32_t address, const uint32_t* words, size_t count);
  void run_rasterizer(uint32_t tile_table);
  uint32_t reg(uint32_t offset) const;

  AppEnvironment& m_env;
  HostApi& m_host;
  DisplayDriver m_display;
  // What the rasterizer does not draw is reported
  // (renderers/common/texture_units.h).
  renderers::UnsupportedState m_unsupported{"raster"};
  renderers::TileBinner m_binner;  // the rasterizer's screen and tile size
  unsigned m_texture_units = 0;    // its TEXTURE_UNITS register, read at the first state that needs units
  uint32_t m_depth_buffer = 0;
  uint32_t m_arena = 0, m_arena_bytes = 0;

  std::vector<Command> m_commands;
  std::vector<StateRecord> m_states;
  std::vector<ClearWords> m_clears;
  std::vector<TriangleWords> m_triangles;
  StateRecord m_last_draw_state{};
};

}  // namespace tessera::raster_backend
