// See command_decoder.h; the command words are those of command_format.h.
#include "raster/core/command_decoder.h"

#include <algorithm>

#include "common/little_endian.h"

namespace tessera::raster {

namespace {

constexpr uint32_t CLEAR_WORDS = 4;
constexpr uint32_t STATE_WORDS = 2;
constexpr uint32_t TRIANGLE_WORDS = 2;
constexpr uint32_t VERTEX_RECORD_BYTES = sizeof(VertexRecord);

ClearCommand decode_clear(const uint32_t* words) {
  ClearCommand c;
  c.color = ((words[0] >> 8) & 1) != 0;
  c.depth = ((words[0] >> 9) & 1) != 0;
  c.stencil = ((words[0] >> 10) & 1) != 0;
  c.rgba = Rgba8::unpack(words[1]);
  c.depth_value = words[2] & 0xffffff;
  c.stencil_value = uint8_t(words[3]);
  c.color_mask = uint8_t((words[3] >> 8) & 15);
  c.depth_write = ((words[3] >> 12) & 1) != 0;
  c.stencil_write_mask = uint8_t(words[3] >> 16);
  return c;
}

}  // namespace

bool CommandDecoder::next(Command& command) {
  if (m_position >= m_entry.word_count || m_run.failed()) return false;
  const uint32_t address = m_entry.list_address + 4 * m_position;
  uint8_t raw[4 * CLEAR_WORDS];
  if (!m_run.read(address, raw, 4)) return false;
  const uint32_t opcode = load_le32(raw) & 0xff;
  uint32_t length = 0;
  switch (static_cast<Opcode>(opcode)) {
    case Opcode::clear: length = CLEAR_WORDS; break;
    case Opcode::state: length = STATE_WORDS; break;
    case Opcode::triangle: length = TRIANGLE_WORDS; break;
  }
  if (length == 0) {
    m_run.fail(RasterError::bad_opcode, address);
    return false;
  }
  if (m_entry.word_count - m_position < length) {
    m_run.fail(RasterError::list_overrun, address);
    return false;
  }
  if (!m_run.read(address + 4, raw + 4, 4 * (length - 1))) return false;
  uint32_t words[CLEAR_WORDS];
  for (uint32_t i = 0; i < length; ++i) words[i] = load_le32(raw + 4 * i);
  ++m_run.result().commands;
  m_run.charge(m_run.result().tile_cycles, m_run.costs().command);
  m_position += length;

  command.opcode = static_cast<Opcode>(opcode);
  if (command.opcode == Opcode::clear) {
    command.clear = decode_clear(words);
  } else {
    command.pointer = words[1];
  }
  return true;
}

bool CommandDecoder::read_state(uint32_t address, DrawState& state) {
  uint8_t b[sizeof(StateBlock)];
  if (!m_run.read(address, b, sizeof b)) return false;
  const auto word = [&b](unsigned i) { return load_le32(b + 4 * i); };
  DrawState s;
  s.address = address;
  s.flags = word(0);
  FragmentOperationsState& o = s.operations;
  o.depth_test = s.has(StateFlag::depth_test);
  o.depth_write = s.has(StateFlag::depth_write);
  o.alpha_test = s.has(StateFlag::alpha_test);
  o.stencil_test = s.has(StateFlag::stencil_test);
  o.blend = s.has(StateFlag::blend);
  o.logic_op = s.has(StateFlag::logic_op);
  const uint32_t alpha = word(2), stencil = word(3), ops = word(4), blend = word(5);
  o.depth_func = from_code<CompareFunc>(word(1));
  o.alpha_func = from_code<CompareFunc>(alpha);
  o.alpha_ref = uint8_t(alpha >> 8);
  o.stencil_func = from_code<CompareFunc>(stencil);
  o.stencil_ref = uint8_t(stencil >> 8);
  o.stencil_value_mask = uint8_t(stencil >> 16);
  o.stencil_write_mask = uint8_t(stencil >> 24);
  o.stencil_fail = from_code<StencilOp>(ops >> STENCIL_FAIL_SHIFT);
  o.depth_fail = from_code<StencilOp>(ops >> STENCIL_DEPTH_FAIL_SHIFT);
  o.depth_pass = from_code<StencilOp>(ops >> STENCIL_DEPTH_PASS_SHIFT);
  o.blend_src = from_code<BlendFactor>(blend >> BLEND_SRC_SHIFT);
  o.blend_dst = from_code<BlendFactor>(blend >> BLEND_DST_SHIFT);
  o.logic_op_mode = from_code<LogicOp>(blend >> BLEND_LOGIC_OP_SHIFT);
  o.color_mask = uint8_t(word(6) & 15);
  s.scissor = s.has(StateFlag::scissor_test);
  const uint32_t xy = word(7), size = word(8);
  s.scissor_box.x0 = int16_t(xy & 0xffff);
  s.scissor_box.y0 = int16_t(xy >> 16);
  s.scissor_box.x1 = s.scissor_box.x0 + int(size & 0xffff);
  s.scissor_box.y1 = s.scissor_box.y0 + int(size >> 16);
  const uint32_t tex_size = word(10), mode = word(11);
  s.log2_width = tex_size & 0xff;
  s.log2_height = (tex_size >> 8) & 0xff;
  s.texture.base = word(9);
  s.texture.log2_width = uint8_t(std::min(s.log2_width, TEXTURE_MAX_LOG2));
  s.texture.log2_height = uint8_t(std::min(s.log2_height, TEXTURE_MAX_LOG2));
  s.texture.wrap_s = from_code<TexWrap>(mode >> TEXTURE_WRAP_S_SHIFT);
  s.texture.wrap_t = from_code<TexWrap>(mode >> TEXTURE_WRAP_T_SHIFT);
  s.min_filter = from_code<TexFilter>(mode >> TEXTURE_MIN_FILTER_SHIFT);
  s.mag_filter = from_code<TexFilter>(mode >> TEXTURE_MAG_FILTER_SHIFT);
  // The block's 2-bit field: REPLACE, MODULATE, DECAL; its reserved code 3
  // passes the fragment through (an unknown TexEnv code).
  const uint32_t env = (mode >> TEXTURE_ENV_SHIFT) & ((1u << TEXTURE_ENV_BITS) - 1);
  s.env = from_code<TexEnv>(env == 3 ? field_mask<TexEnv>() : env);
  if (s.has(StateFlag::fog)) {
    uint8_t f[sizeof(FogState)];
    if (!m_run.read(address + fog_state_offset(), f, sizeof f)) return false;
    s.fog_mode = from_code<FogMode>(load_le32(f) >> FOG_MODE_SHIFT);
    s.fog_color = Rgba8::unpack(load_le32(f + 4));
  }
  if (s.has(StateFlag::texture_units) && !read_texture_units(address + texture_units_offset(s.flags), s)) return false;
  state = s;
  return true;
}

bool CommandDecoder::read_texture_units(uint32_t address, DrawState& s) {
  uint8_t h[sizeof(TextureUnitsHeader)];
  if (!m_run.read(address, h, sizeof h)) return false;
  const uint32_t count = load_le32(h) & 0xff;
  if (count < 1 || count > std::min(m_run.config().texture_units, MAX_TEXTURE_UNITS)) {
    m_run.fail(RasterError::bad_texture, address);
    return false;
  }
  uint8_t b[MAX_TEXTURE_UNITS * sizeof(TextureUnitState)];
  const uint32_t units_address = address + uint32_t{sizeof(TextureUnitsHeader)};
  if (!m_run.read(units_address, b, count * uint32_t{sizeof(TextureUnitState)})) return false;
  s.unit_count = count;
  for (uint32_t u = 0; u < count; ++u) {
    const uint8_t* p = b + sizeof(TextureUnitState) * u;
    const auto word = [p](unsigned i) { return load_le32(p + 4 * i); };
    TextureUnitDraw& d = s.unit[u];
    const uint32_t size = word(1), mode = word(3);
    d.log2_width = size & 0xff;
    d.log2_height = (size >> 8) & 0xff;
    d.last_level = (size >> 16) & 0xff;
    d.texture.base = word(0);
    d.texture.log2_width = uint8_t(std::min(d.log2_width, TEXTURE_MAX_LOG2));
    d.texture.log2_height = uint8_t(std::min(d.log2_height, TEXTURE_MAX_LOG2));
    d.texture.wrap_s = from_code<TexWrap>(mode >> UNIT_WRAP_S_SHIFT);
    d.texture.wrap_t = from_code<TexWrap>(mode >> UNIT_WRAP_T_SHIFT);
    d.min_filter = from_code<TexFilter>(mode >> UNIT_MIN_FILTER_SHIFT);
    d.mag_filter = from_code<TexFilter>(mode >> UNIT_MAG_FILTER_SHIFT);
    d.mipmap = from_code<TexMipmap>(mode >> UNIT_MIPMAP_SHIFT);
    d.env.env = from_code<TexEnv>(mode >> UNIT_ENV_SHIFT);
    d.env.base_format = from_code<TexBaseFormat>(mode >> UNIT_BASE_FORMAT_SHIFT);
    d.env.env_color = Rgba8::unpack(word(4));
    d.env.rgb = CombineStage::decode(word(5));
    d.env.alpha = CombineStage::decode(word(6));
    d.level_address = {};
    d.level_address[0] = d.texture.base;
    // The level table, read only when the size is one the core can use (a
    // bad size or last level fails the run when a triangle uses the unit).
    const unsigned max_level = std::max(d.log2_width, d.log2_height);
    if (d.last_level > 0 && d.log2_width <= TEXTURE_MAX_LOG2 && d.log2_height <= TEXTURE_MAX_LOG2 &&
        d.last_level <= max_level) {
      uint8_t table[4 * MAX_TEXTURE_LEVEL];
      if (!m_run.read(word(2), table, 4 * d.last_level)) return false;
      for (unsigned k = 1; k <= d.last_level; ++k) d.level_address[k] = load_le32(table + 4 * (k - 1));
    }
  }
  return true;
}

bool CommandDecoder::read_triangle(uint32_t address, const DrawState& state, TriangleVertices& vertices) {
  uint8_t raw[sizeof(TriangleRecord) + sizeof(TriangleFog) + (MAX_TEXTURE_UNITS - 1) * sizeof(TriangleUnitCoords)];
  static_assert(sizeof raw >= triangle_record_bytes(StateFlag::fog | StateFlag::texture_units, MAX_TEXTURE_UNITS),
                "room for the fog and texture unit extensions");
  if (!m_run.read(address, raw, triangle_record_bytes(state.flags, state.unit_count))) return false;
  const bool fog = state.has(StateFlag::fog);
  const uint8_t* unit_coords = raw + triangle_unit_coords_offset(state.flags);
  for (unsigned k = 0; k < 3; ++k) {
    const uint8_t* p = raw + VERTEX_RECORD_BYTES * k;
    TriangleVertex& v = vertices[k];
    const uint32_t xy = load_le32(p);
    v.x = xy & 0xffff;
    v.y = xy >> 16;
    v.z = load_le32(p + 4) & 0xffffff;
    v.color = Rgba8::unpack(load_le32(p + 8));
    v.s_over_w = load_float(p + 12);
    v.t_over_w = load_float(p + 16);
    v.inv_w = load_float(p + 20);
    v.fog = fog ? int32_t(load_le32(raw + triangle_fog_offset() + 4 * k)) : 0;
    v.unit_s_over_w = {};
    v.unit_t_over_w = {};
    if (state.unit_count > 0) {
      v.unit_s_over_w[0] = v.s_over_w;
      v.unit_t_over_w[0] = v.t_over_w;
    }
    for (unsigned u = 1; u < state.unit_count; ++u) {
      const uint8_t* c = unit_coords + sizeof(TriangleUnitCoords) * (u - 1);
      v.unit_s_over_w[u] = load_float(c + 4 * k);
      v.unit_t_over_w[u] = load_float(c + 12 + 4 * k);
    }
    if (v.x > q9_4::MAX_RAW || v.y > q9_4::MAX_RAW) {  // not a 9.4 coordinate
      ++m_run.result().triangles_skipped;
      return false;
    }
  }
  return true;
}

}  // namespace tessera::raster
