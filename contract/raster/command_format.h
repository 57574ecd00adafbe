// The in-memory interface between the driver and the rasterizer (sort
// middle): the driver writes, in system memory, a tile table with one
// command list per tile, the triangle records and the state blocks they
// refer to, then starts the rasterizer, which walks the tiles in order
// (row-major from the TOP-LEFT tile), runs each tile's commands into its
// tile buffers and writes the finished tile to the frame buffer.
// All words are 32-bit little-endian. Coordinates are GL window
// coordinates: y = 0 is the BOTTOM row; the frame buffer's first row in
// memory is the TOP row (y = height - 1), as the display scans it.
#pragma once

#include <cstdint>

#include "common/fixed_function.h"

namespace tessera::raster {

// Tile table: tiles_x * tiles_y entries, row-major, tile (0, 0) at the top
// left of the screen; tiles_x = ceil(width / tile_width) etc.
struct TileEntry {
  uint32_t list_address;  // first command word
  uint32_t word_count;    // length of the list in words (0: the tile is left as it is in memory)
};

enum class Opcode : uint32_t {
  clear = 1,     // [op | mask << 8] [rgba8888] [depth24] [stencil | color_mask << 8 | depth_write << 12 |
                 // stencil_write_mask << 16]
                 //   mask bit 0 colour, bit 1 depth, bit 2 stencil; the scissor of the current state applies
  state = 2,     // [op] [address of a StateBlock]
  triangle = 3,  // [op] [address of a TriangleRecord]
};

// Triangle vertex as the driver's front end produced it (gl::ScreenVertex).
struct VertexRecord {
  uint32_t xy;     // x 9.4 in bits 0-15, y 9.4 in bits 16-31
  uint32_t z;      // 0.24 depth in bits 0-23
  uint32_t rgba;   // R bits 0-7, G 8-15, B 16-23, A 24-31 (0.8 each)
  float s_over_w;  // texture coordinates divided by w, and 1/w: IEEE 754 single
  float t_over_w;
  float inv_w;
};
struct TriangleRecord {
  VertexRecord v[3];  // v[2] is the provoking vertex for flat shading
};
static_assert(sizeof(TriangleRecord) == 72, "triangle records are 18 words");

// Fog (StateFlag::fog). A StateBlock with the fog flag is followed by a
// FogState, and every triangle record drawn with that state by a
// TriangleFog; without the flag neither is there, so a list without fog is
// word for word what it was before fog existed. The driver writes and the
// rasterizer reads the sizes of state_block_bytes and triangle_record_bytes.
struct FogState {
  uint32_t mode;   // FogMode in bits 0-1 (FOG_MODE_SHIFT)
  uint32_t color;  // fog colour R bits 0-7, G 8-15, B 16-23 (0.8; bits 24-31 unused)
};
struct TriangleFog {
  int32_t argument[3];  // per vertex v[k], the fog argument: signed 16.16 (common/fog.h)
};
static_assert(sizeof(FogState) == 8, "fog states are 2 words");
static_assert(sizeof(TriangleFog) == 12, "triangle fog records are 3 words");

// Texture units (StateFlag::texture_units): mipmaps, a second (third,
// fourth) unit and the environments beyond the block's 2-bit TexEnv field
// (ES 1.1 texturing, docs/es11_profile.md). A StateBlock with the flag is
// followed, after its FogState if it has one, by a TextureUnitsHeader and
// `count` TextureUnitState records, one per ENABLED texture unit in GL's
// order (a disabled unit passes its input through, so the driver leaves it
// out); the block's own texture flag and texture words are then ignored.
// Every triangle record drawn with that state is followed, after its
// TriangleFog if any, by count - 1 TriangleUnitCoords: the first enabled
// unit's coordinates are the VertexRecord's, each further unit's are in
// its record, in the order of the units. Lists without the flag are word
// for word what they were before the extension.
constexpr uint32_t MAX_TEXTURE_UNITS = 4;
struct TextureUnitsHeader {
  uint32_t count;  // bits 0-7: enabled units, 1 .. MAX_TEXTURE_UNITS (another count: RasterError::bad_texture)
};
struct TextureUnitState {
  uint32_t address;        // level 0's RGBA8 texels, row t = 0 first
  uint32_t size;           // log2 width bits 0-7, log2 height 8-15 (0..8), last level bits 16-23 (0: level 0 only)
  uint32_t level_table;    // with a last level L > 0: L words, the texel addresses of levels 1 .. L (level k is
                           // max(1, w >> k) x max(1, h >> k) texels); unused (not read) with L = 0
  uint32_t mode;           // filters, wraps, environment and base format at the UNIT_* shifts below
  uint32_t env_color;      // GL_TEXTURE_ENV_COLOR: R bits 0-7, G 8-15, B 16-23, A 24-31 (0.8)
  uint32_t combine_rgb;    // GL_COMBINE_RGB: function, three sources, three operands, scale (COMBINE_* shifts)
  uint32_t combine_alpha;  // GL_COMBINE_ALPHA: the same layout
};
struct TriangleUnitCoords {
  float s_over_w[3];  // per vertex v[k]: the unit's s / w and t / w (1 / w is the VertexRecord's)
  float t_over_w[3];
};
static_assert(sizeof(TextureUnitsHeader) == 4, "the texture units header is 1 word");
static_assert(sizeof(TextureUnitState) == 28, "texture unit states are 7 words");
static_assert(sizeof(TriangleUnitCoords) == 24, "a further unit's coordinates are 6 words");

// Fields of TextureUnitState::mode. The minification filter is the
// within-level filter (TexFilter) and the choice between levels beside it;
// the environment field is wider than the StateBlock's.
constexpr unsigned UNIT_MIN_FILTER_SHIFT = 0;    // TexFilter within a level, 1 bit
constexpr unsigned UNIT_MAG_FILTER_SHIFT = 1;    // TexFilter, 1 bit
constexpr unsigned UNIT_WRAP_S_SHIFT = 2;        // TexWrap, bits 2-3
constexpr unsigned UNIT_WRAP_T_SHIFT = 4;        // TexWrap, bits 4-5
constexpr unsigned UNIT_MIPMAP_SHIFT = 6;        // TexMipmap, between levels, bits 6-7
constexpr unsigned UNIT_ENV_SHIFT = 8;           // TexEnv, bits 8-11
constexpr unsigned UNIT_BASE_FORMAT_SHIFT = 12;  // TexBaseFormat: the texture's base format (table 3.15), bits 12-15
// Fields of TextureUnitState::combine_rgb and combine_alpha: source k at
// COMBINE_SOURCE_SHIFT + 4 k, operand k at COMBINE_OPERAND_SHIFT + 4 k.
constexpr unsigned COMBINE_FUNC_SHIFT = 0;      // CombineFunc, bits 0-3
constexpr unsigned COMBINE_SOURCE_SHIFT = 4;    // CombineSource, bits 4-5, 8-9, 12-13
constexpr unsigned COMBINE_OPERAND_SHIFT = 16;  // CombineOperand, bits 16-17, 20-21, 24-25
constexpr unsigned COMBINE_SCALE_SHIFT = 28;    // log2 of the scale (0, 1, 2), bits 28-29

// One half (RGB or alpha) of a unit's combiner: a combine word's fields
// (TextureUnitState::combine_rgb, combine_alpha) decoded, and encoded.
struct CombineStage {
  CombineFunc func = CombineFunc::modulate;
  CombineSource source[3] = {CombineSource::texture, CombineSource::previous, CombineSource::constant};
  CombineOperand operand[3] = {CombineOperand::src_color, CombineOperand::src_color, CombineOperand::src_alpha};
  unsigned scale_log2 = 0;  // 0 .. 3

  // The word's fields cut to their codes' widths (bits between them ignored).
  static constexpr CombineStage decode(uint32_t word) {
    CombineStage s;
    s.func = from_code<CombineFunc>(word >> COMBINE_FUNC_SHIFT);
    for (unsigned k = 0; k < 3; ++k) {
      s.source[k] = from_code<CombineSource>(word >> (COMBINE_SOURCE_SHIFT + 4 * k));
      s.operand[k] = from_code<CombineOperand>(word >> (COMBINE_OPERAND_SHIFT + 4 * k));
    }
    s.scale_log2 = (word >> COMBINE_SCALE_SHIFT) & 3;
    return s;
  }
  constexpr uint32_t encode() const {
    uint32_t word = code_of(func) << COMBINE_FUNC_SHIFT | (scale_log2 & 3) << COMBINE_SCALE_SHIFT;
    for (unsigned k = 0; k < 3; ++k)
      word |= code_of(source[k]) << (COMBINE_SOURCE_SHIFT + 4 * k) | code_of(operand[k])
                                                                         << (COMBINE_OPERAND_SHIFT + 4 * k);
    return word;
  }
};

// Levels of a 256 x 256 texture: 0 (256 x 256) to 8 (1 x 1).
constexpr uint32_t MAX_TEXTURE_LEVEL = 8;

// Flags of StateBlock::flags.
enum StateFlag : uint32_t {
  depth_test = 1u << 0,
  depth_write = 1u << 1,
  alpha_test = 1u << 2,
  stencil_test = 1u << 3,
  blend = 1u << 4,
  logic_op = 1u << 5,
  scissor_test = 1u << 6,
  texture = 1u << 7,
  flat_shading = 1u << 8,
  polygon_smooth = 1u << 9,  // antialiased edges from normalised edge functions (EASA)
  fog = 1u << 10,            // a FogState follows the block, a TriangleFog each triangle record
  texture_units = 1u << 11,  // TextureUnitsHeader and unit states follow, TriangleUnitCoords each record
};

// Compare functions, stencil ops, blend factors, logic ops, texture filters,
// wraps and environments are the hardware codes of common/fixed_function.def
// (CompareFunc, StencilOp, BlendFactor, LogicOp, TexFilter, TexWrap, TexEnv;
// TexMipmap in the texture unit states),
// at the positions below. The rasterizer cuts each field to the width of its
// code (a code without an entry does what the table says); the bits between
// fields are reserved and ignored.
struct StateBlock {
  uint32_t flags;
  uint32_t depth_func;       // CompareFunc
  uint32_t alpha_func;       // CompareFunc in bits 0-7, alpha reference 0.8 in bits 8-15
  uint32_t stencil_func;     // CompareFunc bits 0-7, ref 8-15, value mask 16-23, write mask 24-31
  uint32_t stencil_ops;      // StencilOp: fail bits 0-7, depth fail 8-15, depth pass 16-23
  uint32_t blend;            // BlendFactor: source bits 0-7, destination 8-15; LogicOp bits 16-19
  uint32_t color_mask;       // bits 0-3: R, G, B, A writable
  uint32_t scissor_xy;       // x bits 0-15, y bits 16-31 (GL window coordinates)
  uint32_t scissor_size;     // width bits 0-15, height bits 16-31
  uint32_t texture_address;  // RGBA8 texels, row t = 0 first
  uint32_t texture_size;     // log2 width bits 0-7, log2 height 8-15 (0..8: 1..256 texels)
  uint32_t texture_mode;     // TexFilter: min bit 0, mag bit 1; TexWrap: s bits 2-3, t 4-5; TexEnv bits 8-9
};
static_assert(sizeof(StateBlock) == 48, "state blocks are 12 words");

// Bytes of a state block with `flags` (and `units` texture unit states
// with StateFlag::texture_units) and of a triangle record drawn with it:
// the one place the extensions' sizes and order are stated.
constexpr uint32_t fog_state_offset() {
  return uint32_t{sizeof(StateBlock)};
}
constexpr uint32_t texture_units_offset(uint32_t flags) {
  return fog_state_offset() + ((flags & StateFlag::fog) != 0 ? uint32_t{sizeof(FogState)} : 0u);
}
constexpr uint32_t state_block_bytes(uint32_t flags, uint32_t units = 0) {
  return texture_units_offset(flags) +
         ((flags & StateFlag::texture_units) != 0
              ? uint32_t{sizeof(TextureUnitsHeader)} + units * uint32_t{sizeof(TextureUnitState)}
              : 0u);
}
constexpr uint32_t triangle_fog_offset() {
  return uint32_t{sizeof(TriangleRecord)};
}
constexpr uint32_t triangle_unit_coords_offset(uint32_t state_flags) {
  return triangle_fog_offset() + ((state_flags & StateFlag::fog) != 0 ? uint32_t{sizeof(TriangleFog)} : 0u);
}
constexpr uint32_t triangle_record_bytes(uint32_t state_flags, uint32_t units = 0) {
  return triangle_unit_coords_offset(state_flags) + ((state_flags & StateFlag::texture_units) != 0 && units > 1
                                                         ? (units - 1) * uint32_t{sizeof(TriangleUnitCoords)}
                                                         : 0u);
}

// Positions of the codes in their StateBlock words (the compare functions
// sit at bit 0 of depth_func, alpha_func and stencil_func).
constexpr unsigned STENCIL_FAIL_SHIFT = 0, STENCIL_DEPTH_FAIL_SHIFT = 8, STENCIL_DEPTH_PASS_SHIFT = 16;
constexpr unsigned BLEND_SRC_SHIFT = 0, BLEND_DST_SHIFT = 8, BLEND_LOGIC_OP_SHIFT = 16;
constexpr unsigned FOG_MODE_SHIFT = 0;
constexpr unsigned TEXTURE_MIN_FILTER_SHIFT = 0, TEXTURE_MAG_FILTER_SHIFT = 1, TEXTURE_WRAP_S_SHIFT = 2,
                   TEXTURE_WRAP_T_SHIFT = 4, TEXTURE_ENV_SHIFT = 8;

// A table of fixed_function.def that outgrows its field here needs a new
// StateBlock layout (and the driver's and the rasterizer's versions of it).
static_assert(FixedFunction<CompareFunc>::BITS <= 8, "compare function codes fit bits 0-7");
static_assert(FixedFunction<StencilOp>::BITS <= 8, "stencil op codes fit 8-bit fields");
static_assert(FixedFunction<BlendFactor>::BITS <= 8, "blend factor codes fit 8-bit fields");
static_assert(FixedFunction<LogicOp>::BITS <= 4, "logic op codes fit bits 16-19");
static_assert(TEXTURE_MIN_FILTER_SHIFT + FixedFunction<TexFilter>::BITS <= TEXTURE_MAG_FILTER_SHIFT &&
                  TEXTURE_MAG_FILTER_SHIFT + FixedFunction<TexFilter>::BITS <= TEXTURE_WRAP_S_SHIFT,
              "filter codes fit bits 0 and 1");
static_assert(TEXTURE_WRAP_S_SHIFT + FixedFunction<TexWrap>::BITS <= TEXTURE_WRAP_T_SHIFT &&
                  TEXTURE_WRAP_T_SHIFT + FixedFunction<TexWrap>::BITS <= TEXTURE_ENV_SHIFT,
              "wrap codes fit bits 2-3 and 4-5");
// The StateBlock's 2-bit environment field carries REPLACE, MODULATE and
// DECAL only; BLEND, ADD and COMBINE take the texture units extension (its
// code 3 is reserved: the rasterizer passes the fragment through, as before).
constexpr uint32_t TEXTURE_ENV_BITS = 2;
static_assert(code_of(TexEnv::replace) < (1u << TEXTURE_ENV_BITS) &&
                  code_of(TexEnv::modulate) < (1u << TEXTURE_ENV_BITS) &&
                  code_of(TexEnv::decal) < (1u << TEXTURE_ENV_BITS),
              "the StateBlock's environment codes fit bits 8-9");
static_assert(FixedFunction<FogMode>::BITS <= 2, "fog mode codes fit bits 0-1 of FogState::mode");
static_assert(FixedFunction<TexFilter>::BITS <= 1 && FixedFunction<TexWrap>::BITS <= 2 &&
                  FixedFunction<TexMipmap>::BITS <= 2 && FixedFunction<TexEnv>::BITS <= 4 &&
                  FixedFunction<TexBaseFormat>::BITS <= 4,
              "unit filter, wrap, mipmap, environment and base format codes fit their TextureUnitState::mode fields");
static_assert(FixedFunction<CombineFunc>::BITS <= 4 && FixedFunction<CombineSource>::BITS <= 2 &&
                  FixedFunction<CombineOperand>::BITS <= 2,
              "combiner codes fit their combine_rgb and combine_alpha fields");

// ERROR_STATUS codes. On an error the rasterizer stops the run, sets
// STATUS.error and IRQ_STATUS.error, and leaves the tiles not yet written
// as they were in memory.
enum class RasterError : uint32_t {
  none = 0,
  bus_error = 1,     // a fetch or a tile write got an error response (ERROR_ADDRESS: the address)
  bad_opcode = 2,    // unknown command word (ERROR_ADDRESS: its address)
  list_overrun = 3,  // a command runs past its tile's word_count
  bad_texture = 4,   // texture size above 256 (log2 > 8), texels outside memory, a unit count not 1 .. 4,
                     // or a last level beyond the texture's 1 x 1 level
  bad_reciprocal =
      5,  // reciprocal operand 0 or above 2^14 - 1 reached the unit: the triangle is skipped, counted, not fatal
};

// The name of an ERROR_STATUS code, for messages of the model and the driver.
inline const char* error_name(uint32_t code) {
  switch (static_cast<RasterError>(code)) {
    case RasterError::none: return "none";
    case RasterError::bus_error: return "bus_error";
    case RasterError::bad_opcode: return "bad_opcode";
    case RasterError::list_overrun: return "list_overrun";
    case RasterError::bad_texture: return "bad_texture";
    case RasterError::bad_reciprocal: return "bad_reciprocal";
  }
  return "unknown";
}
inline const char* error_name(RasterError error) {
  return error_name(static_cast<uint32_t>(error));
}

}  // namespace tessera::raster
