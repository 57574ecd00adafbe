// The tile loop and the dispatch of each tile's commands to the pipeline's
// stages, one file each (README.md in this folder walks them): command
// decode (command_decoder), the tile buffers (tile_cache), triangle setup
// (triangle_setup, refined_reciprocal), traversal (traversal) and shading
// (fragment_shader: interpolation, texture_sampler, fragment_operations).
// The stages share the port, the counters and the first error through
// RunContext.
#include "raster/core/tile_rasterizer.h"

#include <algorithm>

#include <cstddef>
#include <memory>

#include "common/little_endian.h"
#include "common/screen_size.h"
#include "raster/core/command_decoder.h"
#include "raster/core/draw_state.h"
#include "raster/core/fragment_shader.h"
#include "raster/core/run_context.h"
#include "raster/core/tile_cache.h"
#include "raster/core/traversal.h"
#include "raster/core/triangle_setup.h"

namespace tessera::raster {

namespace {

// 9.4 screen coordinates reach 511 + 15/16; edge_function.h is exact for
// pixels 0..512: screens up to MAX_SCREEN_SIZE (common/screen_size.h).

// One triangle through setup, traversal and shading. The texture's size is
// checked only when a textured triangle reaches the traversal.
void draw_triangle(RunContext& run, CommandDecoder& decoder, TileCache& tile, const DrawState& state,
                   uint32_t record_address, ShadingWorkspace& work) {
  TriangleVertices vertices;
  if (!decoder.read_triangle(record_address, state, vertices)) return;
  const bool smooth = state.has(StateFlag::polygon_smooth);
  const Rect box = traversal_box(vertices, smooth, tile.tile(), state);
  if (box.empty()) return;

  if (state.has(StateFlag::texture_units)) {
    // Each unit's size, and a last level no further than the 1 x 1 level.
    for (unsigned u = 0; u < state.unit_count; ++u) {
      const TextureUnitDraw& unit = state.unit[u];
      if (unit.log2_width > TEXTURE_MAX_LOG2 || unit.log2_height > TEXTURE_MAX_LOG2 ||
          unit.last_level > std::max(unit.log2_width, unit.log2_height))
        return run.fail(RasterError::bad_texture, state.address + texture_units_offset(state.flags) +
                                                      uint32_t{sizeof(TextureUnitsHeader)} +
                                                      uint32_t{sizeof(TextureUnitState)} * u +
                                                      static_cast<uint32_t>(offsetof(TextureUnitState, size)));
    }
  } else if (state.has(StateFlag::texture) &&
             (state.log2_width > TEXTURE_MAX_LOG2 || state.log2_height > TEXTURE_MAX_LOG2)) {
    return run.fail(RasterError::bad_texture,
                    state.address + static_cast<uint32_t>(offsetof(StateBlock, texture_size)));
  }

  TriangleSetup setup;
  if (!set_up_triangle(vertices, state, run.config().recip_method, setup)) {
    ++run.result().triangles_skipped;
    return;
  }
  ++run.result().triangles;
  run.charge(run.result().setup_cycles, run.costs().setup);

  FragmentShader shader(run, tile, state, work);
  traverse(run, setup, box, smooth, work, shader);
}

// One tile's command list, from GL's default state; the tile buffers are
// loaded at the first command that uses them (unless it overwrites them
// all) and written back at the end.
void run_tile(RunContext& run, TileCache& tile, const TileEntry& entry, ShadingWorkspace& work) {
  ++run.result().tiles;
  run.charge(run.result().tile_cycles, run.costs().tile_start);
  DrawState state;
  bool loaded = false;
  CommandDecoder decoder(run, entry);
  Command command;
  while (decoder.next(command)) {
    if (command.opcode == Opcode::state) {
      if (!decoder.read_state(command.pointer, state)) return;
    } else {
      if (!loaded) {
        if (!(command.opcode == Opcode::clear && tile.clears_whole_tile(command.clear, state))) tile.load(run);
        loaded = true;
        if (run.failed()) return;
      }
      if (command.opcode == Opcode::clear) {
        tile.clear(run, command.clear, state);
      } else {
        draw_triangle(run, decoder, tile, state, command.pointer, work);
      }
    }
    run.report_cycles();
  }
  if (loaded && !run.failed()) tile.write_back(run);
}

}  // namespace

TileRasterizer::TileRasterizer(RasterPort& port, const CycleCosts& costs) : m_port(port), m_costs(costs) {}

RunResult TileRasterizer::run(const RunConfig& config) {
  RunContext run(m_port, m_costs, config);
  const auto valid = [](unsigned v) { return v >= 1 && v <= MAX_SCREEN_SIZE; };
  if (!valid(config.width) || !valid(config.height) || !valid(config.tile_width) || !valid(config.tile_height))
    return run.result();
  const unsigned tiles_x = (config.width + config.tile_width - 1) / config.tile_width;
  const unsigned tiles_y = (config.height + config.tile_height - 1) / config.tile_height;
  TileCache tile(config);
  // Default-initialised: every array is written before it is read.
  const std::unique_ptr<ShadingWorkspace> work(new ShadingWorkspace);

  for (unsigned ty = 0; ty < tiles_y && !run.failed(); ++ty) {
    for (unsigned tx = 0; tx < tiles_x && !run.failed(); ++tx) {
      const uint32_t entry_address = config.tile_table + 8 * (ty * tiles_x + tx);
      uint8_t raw[8];
      if (!run.read(entry_address, raw, sizeof raw)) break;
      const TileEntry entry{load_le32(raw), load_le32(raw + 4)};
      if (entry.word_count == 0) continue;
      tile.select(tx, ty);
      m_port.tile_begins(tx, ty);
      run_tile(run, tile, entry, *work);
      run.report_cycles();
      m_port.tile_ends(tx, ty);
    }
  }
  run.report_cycles();
  return run.result();
}

}  // namespace tessera::raster
