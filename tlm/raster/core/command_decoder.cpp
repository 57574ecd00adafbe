// See command_decoder.h; the command words are those of command_format.h.
#include "raster/core/command_decoder.h"

#include <algorithm>

#include "raster/core/little_endian.h"

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
  s.env = from_code<TexEnv>(mode >> TEXTURE_ENV_SHIFT);
  if (s.has(StateFlag::fog)) {
    uint8_t f[sizeof(FogState)];
    if (!m_run.read(address + uint32_t{sizeof(StateBlock)}, f, sizeof f)) return false;
    s.fog_mode = from_code<FogMode>(load_le32(f) >> FOG_MODE_SHIFT);
    s.fog_color = Rgba8::unpack(load_le32(f + 4));
  }
  state = s;
  return true;
}

bool CommandDecoder::read_triangle(uint32_t address, const DrawState& state, TriangleVertices& vertices) {
  uint8_t raw[sizeof(TriangleRecord) + sizeof(TriangleFog)];
  static_assert(sizeof raw >= triangle_record_bytes(StateFlag::fog), "room for the fog extension");
  if (!m_run.read(address, raw, triangle_record_bytes(state.flags))) return false;
  const bool fog = state.has(StateFlag::fog);
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
    v.fog = fog ? int32_t(load_le32(raw + sizeof(TriangleRecord) + 4 * k)) : 0;
    if (v.x > q9_4::MAX_RAW || v.y > q9_4::MAX_RAW) {  // not a 9.4 coordinate
      ++m_run.result().triangles_skipped;
      return false;
    }
  }
  return true;
}

}  // namespace tessera::raster
