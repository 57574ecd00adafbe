// Command decode: one tile's command list (command_format.h) walked command
// by command, each fetched whole (its first word, then the rest in one
// access), checked (bad_opcode, list_overrun at the command word) and
// counted; and the StateBlocks and triangle records the commands point to,
// fetched and decoded into the state and vertices the other stages take.
// A fetch the port refuses is the run's bus_error (RunContext).
#pragma once

#include <array>
#include <cstdint>

#include "raster/command_format.h"
#include "raster/core/draw_state.h"
#include "raster/core/run_context.h"
#include "raster/datapath/fixed_point.h"

namespace tessera::raster {

struct ClearCommand {
  bool color = false, depth = false, stencil = false;  // the buffers the mask names
  Rgba8 rgba;
  uint32_t depth_value = 0;  // 0.24
  uint8_t stencil_value = 0;
  uint8_t color_mask = 0;  // bit 0 R .. bit 3 A writable
  bool depth_write = false;
  uint8_t stencil_write_mask = 0;
};

struct Command {
  Opcode opcode = Opcode::clear;
  ClearCommand clear;    // Opcode::clear
  uint32_t pointer = 0;  // Opcode::state: the StateBlock; Opcode::triangle: the TriangleRecord
};

// A vertex of a triangle record.
struct TriangleVertex {
  uint32_t x = 0, y = 0;  // 9.4 codes
  uint32_t z = 0;         // 0.24
  Rgba8 color;
  float s_over_w = 0, t_over_w = 0, inv_w = 0;
  int32_t fog = 0;  // the fog argument, 16.16 (a TriangleFog; 0 without fog)
  // With StateFlag::texture_units, unit u's s / w and t / w (unit 0's are
  // s_over_w and t_over_w above, repeated here); 0 for the other units.
  std::array<float, MAX_TEXTURE_UNITS> unit_s_over_w{}, unit_t_over_w{};
};
using TriangleVertices = std::array<TriangleVertex, 3>;

class CommandDecoder {
 public:
  CommandDecoder(RunContext& run, const TileEntry& entry) : m_run(run), m_entry(entry) {}

  // The list's next command; false at the end of the list, after an error
  // and when this command is one.
  bool next(Command& command);
  // The StateBlock at `address` (and its FogState with the fog flag, its
  // texture unit states with the texture_units flag); false when a fetch
  // fails or the unit count is not 1 .. MAX_TEXTURE_UNITS (bad_texture).
  bool read_state(uint32_t address, DrawState& state);
  // The triangle record at `address` (and its TriangleFog when `state` has
  // fog, its further units' coordinates with texture_units); false when its
  // fetch fails, or when a vertex is not a 9.4 coordinate (the triangle is
  // skipped and counted).
  bool read_triangle(uint32_t address, const DrawState& state, TriangleVertices& vertices);

 private:
  bool read_texture_units(uint32_t address, DrawState& state);

  RunContext& m_run;
  TileEntry m_entry;
  uint32_t m_position = 0;  // words of the list taken
};

}  // namespace tessera::raster
