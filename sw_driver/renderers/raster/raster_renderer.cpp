#include "renderers/raster/raster_renderer.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "costs/host_cost.h"
#include "gl/runtime.h"
#include "raster/command_format.h"
#include "raster/raster_regs.h"
#include "renderers/common/fog.h"
#include "renderers/common/texture_units.h"
#include "renderers/common/texturing.h"
#include "soc/irq_map.h"
#include "soc/memory_map.h"

namespace tessera::raster_backend {

namespace regs = raster_regs;
using raster::Opcode;
using raster::StateBlock;

namespace {

constexpr unsigned STM_WORDS = 8;  // STM with eight registers

// A StateBlock from the GL state, in command_format.h's encoding: the state
// already holds the hardware codes (common/fixed_function.def). The
// rasterizer has one texture unit: `unit` is the one drawn.
StateBlock encode_state(const gl::RasterState& s, const renderers::SingleTextureUnit& unit) {
  StateBlock b{};
  auto flag = [&](bool on, uint32_t bit) { b.flags |= on ? bit : 0u; };
  const gl::Texture& tex = unit.index >= 0 ? s.unit[unit.index].tex : gl::Texture{};
  const bool texture = unit.index >= 0 && tex.width > 0 && tex.height > 0;  // incomplete: texturing off (GL)
  flag(s.depth_test, raster::depth_test);
  flag(s.depth_write, raster::depth_write);
  flag(s.alpha_test, raster::alpha_test);
  flag(s.stencil_test, raster::stencil_test);
  flag(s.blend, raster::blend);
  flag(s.logic_op, raster::logic_op);
  flag(s.scissor_test, raster::scissor_test);
  flag(texture, raster::texture);
  flag(s.flat_shading, raster::flat_shading);
  flag(s.polygon_smooth, raster::polygon_smooth);
  flag(s.fog, raster::fog);
  b.depth_func = code_of(s.depth_func);
  b.alpha_func = code_of(s.alpha_func) | uint32_t{s.alpha_ref} << 8;
  b.stencil_func = code_of(s.stencil_func) | uint32_t{s.stencil_ref} << 8 | uint32_t{s.stencil_value_mask} << 16 |
                   uint32_t{s.stencil_write_mask} << 24;
  b.stencil_ops = code_of(s.stencil_fail) << raster::STENCIL_FAIL_SHIFT |
                  code_of(s.depth_fail) << raster::STENCIL_DEPTH_FAIL_SHIFT |
                  code_of(s.depth_pass) << raster::STENCIL_DEPTH_PASS_SHIFT;
  b.blend = code_of(s.blend_src) << raster::BLEND_SRC_SHIFT | code_of(s.blend_dst) << raster::BLEND_DST_SHIFT |
            code_of(s.logic_op_mode) << raster::BLEND_LOGIC_OP_SHIFT;
  for (unsigned i = 0; i < 4; ++i) b.color_mask |= s.color_mask[i] ? 1u << i : 0u;
  auto u16 = [](int v) { return static_cast<uint32_t>(std::clamp(v, 0, 0xFFFF)); };
  b.scissor_xy = u16(s.scissor_x) | u16(s.scissor_y) << 16;
  b.scissor_size = u16(s.scissor_width) | u16(s.scissor_height) << 16;
  if (texture) {
    auto log2 = [](unsigned v) {
      uint32_t n = 0;
      while ((1u << n) < v) ++n;
      return n;
    };
    b.texture_address = tex.address;
    b.texture_size = log2(tex.width) | log2(tex.height) << 8;
    b.texture_mode = code_of(tex.min_filter) << raster::TEXTURE_MIN_FILTER_SHIFT |
                     code_of(tex.mag_filter) << raster::TEXTURE_MAG_FILTER_SHIFT |
                     code_of(tex.wrap_s) << raster::TEXTURE_WRAP_S_SHIFT |
                     code_of(tex.wrap_t) << raster::TEXTURE_WRAP_T_SHIFT |
                     code_of(unit.env) << raster::TEXTURE_ENV_SHIFT;
  }
  return b;
}

// The FogState of a state with fog (zeros without, never written then).
raster::FogState encode_fog(const gl::RasterState& s) {
  raster::FogState f{};
  if (!s.fog) return f;
  f.mode = code_of(s.fog_mode) << raster::FOG_MODE_SHIFT;
  f.color = uint32_t{s.fog_color[0]} | uint32_t{s.fog_color[1]} << 8 | uint32_t{s.fog_color[2]} << 16;
  return f;
}

// A unit the rasterizer draws: enabled, with a complete texture.
bool textured(const gl::TextureUnit& unit) {
  return unit.enabled && unit.tex.width > 0 && unit.tex.height > 0;
}

// Whether `s` needs the texture units extension (command_format.h): more
// than one unit to draw, an environment the StateBlock's 2-bit field does
// not carry (BLEND, ADD, COMBINE), or a base format whose table 3.15 rules
// differ from RGBA's under the unit's environment. Otherwise the
// StateBlock's own texture words draw it, word for word as before.
bool needs_texture_units(const gl::RasterState& s) {
  unsigned units = 0;
  for (const gl::TextureUnit& unit : s.unit) {
    if (!textured(unit)) continue;
    ++units;
    gl::TexEnv code;
    if (!gl::hardware_tex_env(unit.env, &code) || renderers::env_needs_base_format(unit.tex, unit.env) ||
        unit.tex.min_mipmap != gl::MipmapFilter::none)
      return true;
  }
  return units > 1;
}

// The texture units extension of `s` (the block's own texture flag and
// words cleared, as the rasterizer ignores them then): one TextureUnitState
// per unit drawn, in GL's order; `index` gets the GL unit of each. Returns
// the count.
unsigned encode_texture_units(const gl::RasterState& s, StateBlock& block, raster::TextureUnitsHeader& header,
                              raster::TextureUnitState units[],
                              uint32_t (&level_tables)[raster::MAX_TEXTURE_UNITS][raster::MAX_TEXTURE_LEVEL],
                              int index[], unsigned hardware_units) {
  block.flags &= ~raster::texture;
  block.flags |= raster::texture_units;
  block.texture_address = block.texture_size = block.texture_mode = 0;
  const auto log2 = [](unsigned v) {
    uint32_t n = 0;
    while ((1u << n) < v) ++n;
    return n;
  };
  const auto stage = [](const gl::CombineStage& g) {
    raster::CombineStage c;
    c.func = g.func;
    for (unsigned k = 0; k < 3; ++k) {
      c.source[k] = g.source[k];
      c.operand[k] = g.operand[k];
    }
    c.scale_log2 = g.scale >= 4 ? 2 : g.scale >= 2 ? 1 : 0;
    return c.encode();
  };
  unsigned count = 0;
  for (unsigned u = 0; u < gl::MAX_TEXTURE_UNITS && count < hardware_units; ++u) {
    const gl::TextureUnit& unit = s.unit[u];
    if (!textured(unit)) continue;
    const gl::Texture& tex = unit.tex;
    raster::TextureUnitState& w = units[count];
    // A mipmapped texture (a complete chain: gl::Texture) carries its
    // levels in the unit's level table; another, level 0 alone.
    const uint32_t last_level =
        tex.min_mipmap == gl::MipmapFilter::none
            ? 0
            : std::min<uint32_t>(tex.levels > 0 ? tex.levels - 1 : 0, raster::MAX_TEXTURE_LEVEL);
    const TexMipmap mipmap = tex.min_mipmap == gl::MipmapFilter::none     ? TexMipmap::none
                             : tex.min_mipmap == gl::MipmapFilter::linear ? TexMipmap::linear
                                                                          : TexMipmap::nearest;
    for (uint32_t k = 1; k <= last_level; ++k) level_tables[count][k - 1] = tex.level[k].address;
    w.address = tex.address;
    w.size = log2(tex.width) | log2(tex.height) << 8 | last_level << 16;
    w.level_table = 0;  // the table's address, once flush lays the arena out
    w.mode = code_of(tex.min_filter) << raster::UNIT_MIN_FILTER_SHIFT |
             code_of(tex.mag_filter) << raster::UNIT_MAG_FILTER_SHIFT |
             code_of(tex.wrap_s) << raster::UNIT_WRAP_S_SHIFT | code_of(tex.wrap_t) << raster::UNIT_WRAP_T_SHIFT |
             code_of(mipmap) << raster::UNIT_MIPMAP_SHIFT | code_of(unit.env) << raster::UNIT_ENV_SHIFT |
             code_of(gl::tex_base_format(tex)) << raster::UNIT_BASE_FORMAT_SHIFT;
    w.env_color = uint32_t{unit.env_color[0]} | uint32_t{unit.env_color[1]} << 8 | uint32_t{unit.env_color[2]} << 16 |
                  uint32_t{unit.env_color[3]} << 24;
    w.combine_rgb = stage(unit.combine_rgb);
    w.combine_alpha = stage(unit.combine_alpha);
    index[count++] = static_cast<int>(u);
  }
  header.count = count;
  return count;
}

bool same(const StateBlock& a, const StateBlock& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// The first `bytes` of `object`, as words.
template <typename T>
void append_words(std::vector<uint32_t>& words, const T& object, uint32_t bytes) {
  const size_t at = words.size();
  words.resize(at + bytes / 4);
  std::memcpy(words.data() + at, &object, bytes);
}

raster::VertexRecord encode_vertex(const gl::ScreenVertex& v, int unit) {
  const gl::TexCoord st = unit >= 0 ? v.tex[unit] : gl::TexCoord{};
  auto q9_4 = [](int32_t c) { return static_cast<uint32_t>(std::clamp<int32_t>(c, 0, 0xFFFF)); };
  raster::VertexRecord r;
  r.xy = q9_4(v.x) | q9_4(v.y) << 16;
  r.z = v.z & 0xFFFFFF;
  r.rgba = uint32_t{v.r} | uint32_t{v.g} << 8 | uint32_t{v.b} << 16 | uint32_t{v.a} << 24;
  r.s_over_w = st.s * v.inv_w;
  r.t_over_w = st.t * v.inv_w;
  r.inv_w = v.inv_w;
  return r;
}

// The rasterizer's screen and tiles, from its registers; it must cover the
// display it draws into.
renderers::TileGrid read_grid(HostApi& host, const DisplayDriver& display) {
  auto reg = [&host](uint32_t offset) { return host.read32(memory_map::raster_regs.base + offset); };
  renderers::TileGrid grid;
  grid.width = reg(regs::WIDTH);
  grid.height = reg(regs::HEIGHT);
  if (grid.width != display.width() || grid.height != display.height())
    throw std::runtime_error("raster back end: the rasterizer covers " + std::to_string(grid.width) + "x" +
                             std::to_string(grid.height) + " pixels but the display shows " +
                             std::to_string(display.width()) + "x" + std::to_string(display.height()) +
                             ": it must cover the display it draws into");
  grid.tile_width = reg(regs::TILE_WIDTH);
  grid.tile_height = reg(regs::TILE_HEIGHT);
  return grid;
}

}  // namespace

RasterRenderer::RasterRenderer(AppEnvironment& env)
    : m_env(env), m_host(*env.host), m_display(env), m_binner(read_grid(m_host, m_display)) {
  // Depth 24 | stencil 8 << 24 per pixel (raster_regs.def, DEPTH_BASE).
  m_depth_buffer = gl::allocate(m_display.width() * m_display.height() * 4);
  m_last_draw_state = {encode_state(gl::RasterState{}, {}), raster::FogState{}, {}, {}, {}};
}

uint32_t RasterRenderer::reg(uint32_t offset) const {
  return memory_map::raster_regs.base + offset;
}

uint32_t RasterRenderer::add_state(const StateRecord& state) {
  costs::charge(m_host, costs::HostCost::raster_state_compare);
  if (m_states.empty() || !same(m_states.back().block, state.block) ||
      std::memcmp(&m_states.back().fog, &state.fog, sizeof state.fog) != 0 ||
      std::memcmp(&m_states.back().units_header, &state.units_header, sizeof state.units_header) != 0 ||
      std::memcmp(&m_states.back().units, &state.units, sizeof state.units) != 0 ||
      std::memcmp(&m_states.back().level_tables, &state.level_tables, sizeof state.level_tables) != 0)
    m_states.push_back(state);
  return static_cast<uint32_t>(m_states.size() - 1);
}

void RasterRenderer::clear(const gl::ClearRequest& request) {
  if (!request.color && !request.depth && !request.stencil) return;
  // The clear's scissor is that of the state current in its tile, so the
  // clear carries a state: the last draw state with the clear's scissor.
  StateRecord record = m_last_draw_state;
  StateBlock& block = record.block;
  block.flags = (block.flags & ~raster::scissor_test) | (request.scissor_test ? raster::scissor_test : uint32_t{0});
  auto u16 = [](int v) { return static_cast<uint32_t>(std::clamp(v, 0, 0xFFFF)); };
  block.scissor_xy = u16(request.scissor_x) | u16(request.scissor_y) << 16;
  block.scissor_size = u16(request.scissor_width) | u16(request.scissor_height) << 16;
  const uint32_t state = add_state(record);
  renderers::TileRange tiles;
  if (request.scissor_test) {
    if (request.scissor_width <= 0 || request.scissor_height <= 0) return;
    tiles =
        m_binner.tiles_of_pixels(request.scissor_x, request.scissor_y, request.scissor_x + request.scissor_width - 1,
                                 request.scissor_y + request.scissor_height - 1);
  } else {
    tiles = m_binner.tiles_of_pixels(0, 0, static_cast<int>(width()) - 1, static_cast<int>(height()) - 1);
  }
  ClearWords clear{};
  clear.words[0] = static_cast<uint32_t>(Opcode::clear) |
                   ((request.color ? 1u : 0u) | (request.depth ? 2u : 0u) | (request.stencil ? 4u : 0u)) << 8;
  clear.words[1] = uint32_t{request.rgba[0]} | uint32_t{request.rgba[1]} << 8 | uint32_t{request.rgba[2]} << 16 |
                   uint32_t{request.rgba[3]} << 24;
  clear.words[2] = request.depth_value & 0xFFFFFF;
  uint32_t color_mask = 0;
  for (unsigned i = 0; i < 4; ++i) color_mask |= request.color_mask[i] ? 1u << i : 0u;
  clear.words[3] = uint32_t{request.stencil_value} | color_mask << 8 | (request.depth_write ? 1u : 0u) << 12 |
                   uint32_t{request.stencil_write_mask} << 16;
  m_binner.add(state, tiles);
  m_commands.push_back({Opcode::clear, static_cast<uint32_t>(m_clears.size())});
  m_clears.push_back(clear);
  costs::charge(m_host, costs::HostCost::raster_clear);
}

void RasterRenderer::draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) {
  if (count == 0) return;
  // Several units, BLEND, ADD, COMBINE or a base format's rules: the texture
  // units extension (encode_texture_units); else the StateBlock's one texture.
  int unit_index[gl::MAX_TEXTURE_UNITS] = {-1, -1, -1, -1};
  unsigned units = 0;
  renderers::SingleTextureUnit unit;
  if (needs_texture_units(state)) {
    // The hardware's unit count, read when a state first needs the units
    // (so that runs without them make no extra register read).
    if (m_texture_units == 0)
      m_texture_units = std::clamp<uint32_t>(m_host.read32(reg(regs::TEXTURE_UNITS)), 1, raster::MAX_TEXTURE_UNITS);
    m_last_draw_state = {encode_state(state, {}), encode_fog(state)};
    units = encode_texture_units(state, m_last_draw_state.block, m_last_draw_state.units_header,
                                 m_last_draw_state.units, m_last_draw_state.level_tables, unit_index, m_texture_units);
    // The configuration keeps driver.texture_units within
    // raster.texture_units; a unit beyond the hardware's is reported, not
    // silently dropped.
    unsigned wanted = 0;
    for (const gl::TextureUnit& u : state.unit) wanted += textured(u) ? 1 : 0;
    if (wanted > units)
      m_unsupported.report(m_env, "more enabled texture units than the rasterizer has (TEXTURE_UNITS = " +
                                      std::to_string(m_texture_units) + ", raster.texture_units): drawn without them");
    unit.index = unit_index[0];
  } else {
    unit =
        renderers::single_texture_unit(state, [this](const std::string& what) { m_unsupported.report(m_env, what); });
    m_last_draw_state = {encode_state(state, unit), encode_fog(state)};
  }
  const uint32_t state_index = add_state(m_last_draw_state);
  // The fog argument in single precision (fog.h's _f forms: a multiply, an
  // add and a conversion per vertex on the ARM922T, no double).
  renderers::FogCoefficientsF fog;
  if (state.fog) fog = renderers::fog_coefficients_f(state);
  // Antialiased edges reach into the pixels next to the box; one pixel of
  // margin covers them and costs nothing for the tiles.
  constexpr int MARGIN = 1;
  uint64_t tiles_binned = 0;
  for (size_t i = 0; i < count; ++i) {
    const gl::Triangle& t = triangles[i];
    TriangleWords record{};
    record.state_flags = m_last_draw_state.block.flags;
    record.units = units;
    for (unsigned k = 0; k < 3; ++k) {
      record.record.v[k] = encode_vertex(t.v[k], unit.index);
      if (state.fog) record.fog.argument[k] = renderers::fog_argument_f(fog, t.v[k].fog, INT32_MAX);
      for (unsigned u = 1; u < units; ++u) {  // the further units' s/w and t/w
        const gl::TexCoord st = t.v[k].tex[unit_index[u]];
        record.unit_coords[u - 1].s_over_w[k] = st.s * t.v[k].inv_w;
        record.unit_coords[u - 1].t_over_w[k] = st.t * t.v[k].inv_w;
      }
    }
    const int32_t min_x = std::min({t.v[0].x, t.v[1].x, t.v[2].x}), max_x = std::max({t.v[0].x, t.v[1].x, t.v[2].x});
    const int32_t min_y = std::min({t.v[0].y, t.v[1].y, t.v[2].y}), max_y = std::max({t.v[0].y, t.v[1].y, t.v[2].y});
    const renderers::TileRange tiles = m_binner.tiles_of_pixels((min_x >> 4) - MARGIN, (min_y >> 4) - MARGIN,
                                                                (max_x >> 4) + MARGIN, (max_y >> 4) + MARGIN);
    m_binner.add(state_index, tiles);
    tiles_binned += tiles.count();
    m_commands.push_back({Opcode::triangle, static_cast<uint32_t>(m_triangles.size())});
    m_triangles.push_back(record);
  }
  costs::charge(m_host, costs::HostCost::raster_draw);
  costs::charge(m_host, costs::HostCost::raster_triangle, count);
  costs::charge(m_host, costs::HostCost::raster_triangle_texture_unit, count * units);
  if (state.fog) costs::charge(m_host, costs::HostCost::raster_triangle_fog, count);
  costs::charge(m_host, costs::HostCost::raster_triangle_tile, tiles_binned);
}

uint32_t RasterRenderer::arena(uint32_t bytes) {
  if (bytes > m_arena_bytes) {
    // The heap is a bump allocator: grow by doubling, the old arena is lost.
    uint32_t size = std::max<uint32_t>(m_arena_bytes * 2, 256u << 10);
    while (size < bytes) size *= 2;
    m_arena = gl::allocate(size, 64);
    m_arena_bytes = size;
  }
  return m_arena;
}

void RasterRenderer::write_block(uint32_t address, const uint32_t* words, size_t count) {
  for (size_t done = 0; done < count; done += STM_WORDS) {
    const unsigned n = static_cast<unsigned>(std::min<size_t>(STM_WORDS, count - done));
    m_host.write_words(address + static_cast<uint32_t>(4 * done), words + done, n);
    costs::charge(m_host, costs::HostCost::raster_block_write);
  }
}

void RasterRenderer::flush() {
  if (m_commands.empty()) return;
  const unsigned tiles = m_binner.grid().tiles();

  // Bin (common/tile_binner.h): each command goes to every tile of its box,
  // preceded by a STATE command where the tile's current state differs;
  // then each entry in command_format.h's words.
  const std::vector<std::vector<renderers::BinEntry>> bins = m_binner.bin();
  std::vector<std::vector<uint32_t>> lists(tiles);
  const uint32_t tile_table_bytes = tiles * sizeof(raster::TileEntry);
  // State blocks and triangle records, each as long as command_format.h
  // says for its flags, at these byte offsets; the level tables of the
  // texture unit states after the blocks (none without mipmaps).
  std::vector<uint32_t> state_words, record_words, state_offsets, record_offsets, table_words;
  std::vector<std::pair<size_t, uint32_t>> table_fixups;  // level_table's word in state_words, table offset
  for (const StateRecord& s : m_states) {
    state_offsets.push_back(static_cast<uint32_t>(4 * state_words.size()));
    append_words(state_words, s, raster::texture_units_offset(s.block.flags));  // the block and its FogState
    if (s.block.flags & raster::texture_units) {
      append_words(state_words, s.units_header, sizeof s.units_header);
      const size_t units_at = state_words.size();
      append_words(state_words, s.units, s.units_header.count * uint32_t{sizeof(raster::TextureUnitState)});
      for (uint32_t u = 0; u < s.units_header.count; ++u) {
        const uint32_t last_level = (s.units[u].size >> 16) & 0xff;
        if (last_level == 0) continue;
        table_fixups.emplace_back(
            units_at + (u * sizeof(raster::TextureUnitState) + offsetof(raster::TextureUnitState, level_table)) / 4,
            static_cast<uint32_t>(4 * table_words.size()));
        table_words.insert(table_words.end(), s.level_tables[u], s.level_tables[u] + last_level);
      }
    }
    assert(4 * state_words.size() - state_offsets.back() ==
           raster::state_block_bytes(s.block.flags, s.units_header.count));
  }
  for (const TriangleWords& t : m_triangles) {
    record_offsets.push_back(static_cast<uint32_t>(4 * record_words.size()));
    append_words(record_words, t, raster::triangle_unit_coords_offset(t.state_flags));  // the record and its fog
    if ((t.state_flags & raster::texture_units) && t.units > 1)
      append_words(record_words, t.unit_coords, (t.units - 1) * uint32_t{sizeof(raster::TriangleUnitCoords)});
  }
  const uint32_t states_bytes = static_cast<uint32_t>(4 * state_words.size());
  const uint32_t tables_bytes = static_cast<uint32_t>(4 * table_words.size());
  const uint32_t triangles_bytes = static_cast<uint32_t>(4 * record_words.size());
  uint64_t entries = 0;
  for (unsigned tile = 0; tile < tiles; ++tile) {
    std::vector<uint32_t>& list = lists[tile];
    for (const renderers::BinEntry& entry : bins[tile]) {
      if (entry.kind == renderers::BinEntry::Kind::state) {
        list.push_back(static_cast<uint32_t>(Opcode::state));
        list.push_back(entry.index);  // an index for now; addresses once the layout is known
      } else if (const Command& command = m_commands[entry.index]; command.opcode == Opcode::clear) {
        list.insert(list.end(), std::begin(m_clears[command.index].words), std::end(m_clears[command.index].words));
      } else {
        list.push_back(static_cast<uint32_t>(Opcode::triangle));
        list.push_back(command.index);
      }
    }
    entries += bins[tile].size();
  }
  costs::charge(m_host, costs::HostCost::raster_tile_entry, entries);

  // Layout in the arena: tile table, state blocks, level tables, triangle
  // records, lists.
  size_t list_words = 0;
  for (const auto& list : lists) list_words += list.size();
  const uint32_t total =
      tile_table_bytes + states_bytes + tables_bytes + triangles_bytes + static_cast<uint32_t>(4 * list_words);
  const uint32_t base = arena(total);
  const uint32_t tile_table = base;
  const uint32_t states = tile_table + tile_table_bytes;
  const uint32_t level_tables = states + states_bytes;
  const uint32_t records = level_tables + tables_bytes;
  for (const auto& [word, offset] : table_fixups) state_words[word] = level_tables + offset;
  uint32_t next_list = records + triangles_bytes;

  std::vector<uint32_t> table(2 * tiles, 0);
  for (unsigned tile = 0; tile < tiles; ++tile) {
    std::vector<uint32_t>& list = lists[tile];
    for (size_t i = 0; i < list.size();) {
      const Opcode op = static_cast<Opcode>(list[i] & 0xFF);  // a clear carries its mask in bits 8-10
      if (op == Opcode::clear) {
        i += 4;
        continue;
      }
      list[i + 1] = op == Opcode::state ? states + state_offsets[list[i + 1]] : records + record_offsets[list[i + 1]];
      i += 2;
    }
    table[2 * tile] = list.empty() ? 0 : next_list;
    table[2 * tile + 1] = static_cast<uint32_t>(list.size());
    write_block(next_list, list.data(), list.size());
    next_list += static_cast<uint32_t>(4 * list.size());
  }
  write_block(states, state_words.data(), state_words.size());
  if (!table_words.empty()) write_block(level_tables, table_words.data(), table_words.size());
  write_block(records, record_words.data(), record_words.size());
  write_block(tile_table, table.data(), table.size());

  run_rasterizer(tile_table);

  m_binner.clear();
  m_commands.clear();
  m_clears.clear();
  m_triangles.clear();
  m_states.clear();
}

void RasterRenderer::run_rasterizer(uint32_t tile_table) {
  m_host.write32(reg(regs::TILE_TABLE), tile_table);
  m_host.write32(reg(regs::COLOR_BASE), m_display.back_buffer());
  m_host.write32(reg(regs::DEPTH_BASE), m_depth_buffer);
  m_host.write32(reg(regs::FORMAT), static_cast<uint32_t>(m_display.format()));
  m_host.write32(reg(regs::IRQ_ENABLE), regs::IRQ_DONE | regs::IRQ_ERROR);
  m_host.write32(reg(regs::START), 1);
  for (;;) {
    m_host.wait_irq(irq_map::raster);
    const uint32_t pending = m_host.read32(reg(regs::IRQ_STATUS));
    m_host.write32(reg(regs::IRQ_STATUS), pending);
    if (pending & (regs::IRQ_DONE | regs::IRQ_ERROR)) break;
  }
  const uint32_t status = m_host.read32(reg(regs::STATUS));
  if (status & regs::STATUS_ERROR) {
    const uint32_t code = m_host.read32(reg(regs::ERROR_STATUS));
    const uint32_t address = m_host.read32(reg(regs::ERROR_ADDRESS));
    char where[16];
    std::snprintf(where, sizeof where, "0x%08x", static_cast<unsigned>(address));
    throw std::runtime_error("raster back end: the rasterizer stopped with error " + std::to_string(code) + " (" +
                             raster::error_name(code) + ") at " + where);
  }
}

void RasterRenderer::read_pixels(int x, int y, int width, int height, uint8_t* rgba) {
  flush();
  if (width <= 0 || height <= 0 || rgba == nullptr) return;
  std::memset(rgba, 0, size_t(width) * size_t(height) * 4);
  const int screen_w = static_cast<int>(m_display.width()), screen_h = static_cast<int>(m_display.height());
  const unsigned bpp = m_display.bytes_per_pixel();
  const int x0 = std::max(x, 0);
  const int x1 = static_cast<int>(std::min<int64_t>(int64_t{x} + width, screen_w));
  if (x0 >= x1) return;
  for (int row = 0; row < height; ++row) {
    const int64_t gy = int64_t{y} + row;
    if (gy < 0 || gy >= screen_h) continue;
    const uint32_t offset = static_cast<uint32_t>(screen_h - 1 - gy) * m_display.width() + static_cast<uint32_t>(x0);
    const uint8_t* p = m_host.load_span(m_display.back_buffer() + offset * bpp, bpp, static_cast<unsigned>(x1 - x0));
    uint8_t* out = rgba + (size_t(row) * size_t(width) + size_t(x0 - x)) * 4;
    for (int i = 0; i < x1 - x0; ++i, p += bpp, out += 4) {
      const uint32_t color = unpack_pixel(m_display.format(), load_pixel(m_display.format(), p));
      for (unsigned c = 0; c < 4; ++c) out[c] = static_cast<uint8_t>(color >> (8 * c));
    }
    costs::charge(m_host, costs::HostCost::raster_read_pixel, uint64_t(x1 - x0));
  }
}

void RasterRenderer::present() {
  flush();
  m_display.present();
  m_unsupported.new_frame();
}

}  // namespace tessera::raster_backend
