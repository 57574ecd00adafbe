// Tile loop, command decoding, triangle setup, traversal and the
// per-fragment pipeline of the tile rasterizer. Formats, rounding, the fill
// rule and the cycle costs are stated in README.md in this folder; the
// arithmetic of every per-pixel step is one of the bit-exact units of
// raster/datapath/ (edge_function, attribute_interpolator, texel_address,
// texture_env, reciprocal here; fragment_tests and blend_logic_op behind
// fragment_operations.h).
#include "raster/core/tile_rasterizer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "raster/core/fragment_operations.h"
#include "raster/datapath/attribute_interpolator.h"
#include "raster/datapath/edge_function.h"
#include "raster/datapath/texel_address.h"
#include "raster/datapath/texture_env.h"

namespace tessera::raster {

namespace {

__extension__ typedef __int128 int128;

// 9.4 screen coordinates reach 511 + 15/16; edge_function.h is exact for
// pixels 0..512.
constexpr unsigned MAX_SCREEN_SIZE = 512;
constexpr uint32_t CLEAR_WORDS = 4;
constexpr uint32_t STATE_WORDS = 2;
constexpr uint32_t TRIANGLE_WORDS = 2;
constexpr uint32_t STATE_BLOCK_BYTES = sizeof(StateBlock);
constexpr uint32_t TRIANGLE_RECORD_BYTES = sizeof(TriangleRecord);
constexpr uint32_t TEXTURE_SIZE_OFFSET = 40;  // StateBlock::texture_size, the address reported for a bad size
constexpr int64_t ATTRIBUTE_WORD_MAX = (int64_t{1} << 39) - 1;
constexpr unsigned NEWTON_STEPS = 2;
constexpr unsigned TEXCOORD_FRACTION_BITS = 24;  // texcoord_attr
constexpr double TEXCOORD_LIMIT = 32767.0;       // |s/w| after normalisation, inside q15.24

uint32_t load_le32(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

void store_le32(uint8_t* p, uint32_t v) {
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
  p[2] = uint8_t(v >> 16);
  p[3] = uint8_t(v >> 24);
}

float load_float(const uint8_t* p) {
  const uint32_t bits = load_le32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// A positive integer as f * 2^n with f in [1/2, 1), f held in Q30.
struct Normalised {
  uint64_t f_q30 = 0;
  int n = 0;
};

Normalised normalise(uint64_t v) {
  int n = 0;
  while (n < 64 && (v >> n) != 0) ++n;
  return {n <= 30 ? v << (30 - n) : v >> (n - 30), n};
}

// 1/v for v > 0: the reciprocal unit gives the seed from the top bits of the
// normalised operand, two Newton-Raphson steps y <- y (2 - f y) refine it.
// Result: 1/v = y * 2^-(30 + n). false when the unit flags its operand.
struct Reciprocal {
  uint64_t y = 0;
  int n = 0;
};

bool refined_reciprocal(uint64_t v, RecipMethod method, Reciprocal& out) {
  const Normalised norm = normalise(v);
  // Method 1 is a fixed-point table, accurate for small operands only: it
  // gets X in [8, 16); the floating-point tables get X in [512, 1024).
  const unsigned operand_bits = method == RecipMethod::method1 ? 8 : 14;
  const auto operand = static_cast<uint16_t>(norm.f_q30 >> (30 - operand_bits));
  const ReciprocalResult seed = reciprocal(v == 0 ? 0 : operand, method);
  if (seed.invalid_operand) return false;
  uint64_t y = uint64_t{seed.q5_16} << (10 + operand_bits);  // Q30 of 1/f
  for (unsigned step = 0; step < NEWTON_STEPS; ++step) {
    const uint64_t fy = (norm.f_q30 * y) >> 30;
    const uint64_t two = uint64_t{1} << 31;
    y = (y * (fy >= two ? 0 : two - fy)) >> 30;
  }
  out = {y, norm.n};
  return true;
}

// numerator / v with v's refined reciprocal, rounded to nearest (ties up).
int128 divide(int128 numerator, const Reciprocal& r, bool negative_divisor, int extra_shift = 0) {
  const int shift = 30 + r.n + extra_shift;
  int128 p = numerator * int128(r.y);
  if (negative_divisor) p = -p;
  return (p + (int128{1} << (shift - 1))) >> shift;
}

int64_t saturate_word(int128 v) {
  return int64_t(std::clamp<int128>(v, -ATTRIBUTE_WORD_MAX - 1, ATTRIBUTE_WORD_MAX));
}

// The GL state of a tile's commands, decoded once per STATE command.
struct DrawState {
  uint32_t address = 0;  // of the StateBlock; 0 while the defaults apply
  uint32_t flags = StateFlag::depth_write;
  FragmentOperationsState operations;
  bool scissor = false;
  int scissor_x0 = 0, scissor_y0 = 0, scissor_x1 = 0, scissor_y1 = 0;  // GL window, ends exclusive
  TextureState texture;
  unsigned log2_width = 0, log2_height = 0;  // as stored, checked at use
  TexFilter min_filter = TexFilter::nearest, mag_filter = TexFilter::nearest;
  TexEnv env = TexEnv::modulate;
};

DrawState decode_state(uint32_t address, const uint8_t* b) {
  const auto word = [b](unsigned i) { return load_le32(b + 4 * i); };
  DrawState s;
  s.address = address;
  s.flags = word(0);
  FragmentOperationsState& o = s.operations;
  o.depth_test = (s.flags & StateFlag::depth_test) != 0;
  o.depth_write = (s.flags & StateFlag::depth_write) != 0;
  o.alpha_test = (s.flags & StateFlag::alpha_test) != 0;
  o.stencil_test = (s.flags & StateFlag::stencil_test) != 0;
  o.blend = (s.flags & StateFlag::blend) != 0;
  o.logic_op = (s.flags & StateFlag::logic_op) != 0;
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
  s.scissor = (s.flags & StateFlag::scissor_test) != 0;
  const uint32_t xy = word(7), size = word(8);
  s.scissor_x0 = int16_t(xy & 0xffff);
  s.scissor_y0 = int16_t(xy >> 16);
  s.scissor_x1 = s.scissor_x0 + int(size & 0xffff);
  s.scissor_y1 = s.scissor_y0 + int(size >> 16);
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
  return s;
}

struct Rect {  // pixels x0 <= x < x1, y0 <= y < y1 (GL window coordinates)
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  Rect intersect(const Rect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
  bool contains(const Rect& o) const { return o.x0 >= x0 && o.y0 >= y0 && o.x1 <= x1 && o.y1 <= y1; }
};

struct Vertex {
  uint32_t x = 0, y = 0;  // 9.4 codes
  uint32_t z = 0;         // 0.24
  Rgba8 color;
  float s_over_w = 0, t_over_w = 0, inv_w = 0;
};

// Everything triangle setup hands to the traversal.
struct TriangleSetup {
  std::array<Edge, 3> edges;
  std::array<q5_16, 3> edge_recip;  // EASA: 1/(|dx| + |dy|) from the reciprocal unit
  std::array<AttributePlane, 4> color;
  AttributePlane depth;
  AttributePlane s, t, q;    // s/w, t/w, 1/w, normalised (README.md, "Texture coordinates")
  int ref_x = 0, ref_y = 0;  // the pixel the planes' start values belong to
  bool flat = false;
  // Gouraud colour seen in perspective: `color` holds c/w (normalised like
  // q) and each pixel divides by q, as GL interpolates (README.md, "Colour").
  bool perspective_color = false;
  Rgba8 flat_color;
};

class TileRun {
 public:
  TileRun(RasterPort& port, const CycleCosts& costs, const RunConfig& config)
      : m_port(port), m_costs(costs), m_config(config) {}

  RunResult execute();

 private:
  bool failed() const { return m_result.error != RasterError::none; }
  void fail(RasterError error, uint32_t address) {
    if (failed()) return;
    m_result.error = error;
    m_result.error_address = address;
  }
  bool read(uint32_t address, void* data, unsigned bytes, RasterError error = RasterError::bus_error);
  bool write(uint32_t address, const void* data, unsigned bytes);
  void charge(uint64_t& bucket, uint64_t cycles) {
    bucket += cycles;
    m_pending_cycles += cycles;
  }
  void report_cycles() {
    if (m_pending_cycles != 0) m_port.cycles(m_pending_cycles);
    m_pending_cycles = 0;
  }

  void run_tile(const TileEntry& entry);
  bool is_full_clear(uint32_t word0, uint32_t word3) const;
  void load_tile();
  void write_tile();
  void clear(const uint32_t* words);
  void draw_triangle(uint32_t record_address);
  bool setup(const std::array<Vertex, 3>& v, TriangleSetup& setup);
  void shade(const TriangleSetup& setup, int px, int py, unorm8 coverage);
  void texture_coords(attribute_sum s, attribute_sum t, attribute_sum q, q15_16& s_out, q15_16& t_out) const;
  Rgba8 perspective_color(const TriangleSetup& setup, int dx, int dy) const;
  bool sample_texture(const TriangleSetup& setup, int dx, int dy, Rgba8 fragment, Rgba8& out);

  unsigned index(int px, int py) const {  // tile buffer index of GL pixel (px, py)
    const unsigned row = m_config.height - 1 - unsigned(py);
    return (row - m_row0) * m_config.tile_width + (unsigned(px) - unsigned(m_tile.x0));
  }
  Rgba8 quantise(Rgba8 c) const { return Rgba8::unpack(quantize_color(m_config.color_format, c.pack())); }

  RasterPort& m_port;
  const CycleCosts& m_costs;
  const RunConfig& m_config;
  RunResult m_result;
  uint64_t m_pending_cycles = 0;

  Rect m_tile;          // GL window coordinates
  unsigned m_row0 = 0;  // first memory row (top) of the tile
  DrawState m_state;
  std::vector<Rgba8> m_color;
  std::vector<uint32_t> m_depth;  // 0.24
  std::vector<uint8_t> m_stencil;
  std::vector<uint8_t> m_row_bytes;
};

bool TileRun::read(uint32_t address, void* data, unsigned bytes, RasterError error) {
  if (!m_port.read(address, data, bytes)) {
    fail(error, address);
    return false;
  }
  m_result.bytes_read += bytes;
  return true;
}

bool TileRun::write(uint32_t address, const void* data, unsigned bytes) {
  if (!m_port.write(address, data, bytes)) {
    fail(RasterError::bus_error, address);
    return false;
  }
  m_result.bytes_written += bytes;
  return true;
}

RunResult TileRun::execute() {
  const RunConfig& c = m_config;
  const auto valid = [](unsigned v) { return v >= 1 && v <= MAX_SCREEN_SIZE; };
  if (!valid(c.width) || !valid(c.height) || !valid(c.tile_width) || !valid(c.tile_height)) return m_result;
  const unsigned tiles_x = (c.width + c.tile_width - 1) / c.tile_width;
  const unsigned tiles_y = (c.height + c.tile_height - 1) / c.tile_height;
  const size_t tile_pixels = size_t{c.tile_width} * c.tile_height;
  m_color.resize(tile_pixels);
  m_depth.resize(tile_pixels);
  m_stencil.resize(tile_pixels);
  m_row_bytes.resize(size_t{c.tile_width} * 4);

  for (unsigned ty = 0; ty < tiles_y && !failed(); ++ty) {
    for (unsigned tx = 0; tx < tiles_x && !failed(); ++tx) {
      const uint32_t entry_address = c.tile_table + 8 * (ty * tiles_x + tx);
      uint8_t raw[8];
      if (!read(entry_address, raw, sizeof raw)) break;
      const TileEntry entry{load_le32(raw), load_le32(raw + 4)};
      if (entry.word_count == 0) continue;
      m_row0 = ty * c.tile_height;
      const unsigned row1 = std::min(m_row0 + c.tile_height, c.height);
      m_tile = {int(tx * c.tile_width), int(c.height - row1), int(std::min((tx + 1) * c.tile_width, c.width)),
                int(c.height - m_row0)};
      run_tile(entry);
      report_cycles();
    }
  }
  report_cycles();
  return m_result;
}

// A clear of all three buffers with every write mask open, over the whole
// tile: the tile need not be loaded first.
bool TileRun::is_full_clear(uint32_t word0, uint32_t word3) const {
  const bool all = ((word0 >> 8) & 7) == 7 && ((word3 >> 8) & 15) == 15 && ((word3 >> 12) & 1) == 1 &&
                   ((word3 >> 16) & 0xff) == 0xff;
  const Rect scissor{m_state.scissor_x0, m_state.scissor_y0, m_state.scissor_x1, m_state.scissor_y1};
  return all && (!m_state.scissor || scissor.contains(m_tile));
}

void TileRun::run_tile(const TileEntry& entry) {
  ++m_result.tiles;
  charge(m_result.tile_cycles, m_costs.tile_start);
  m_state = DrawState{};
  bool loaded = false;
  for (uint32_t pos = 0; pos < entry.word_count && !failed(); report_cycles()) {
    const uint32_t address = entry.list_address + 4 * pos;
    uint8_t raw[4 * CLEAR_WORDS];
    if (!read(address, raw, 4)) return;
    const uint32_t opcode = load_le32(raw) & 0xff;
    uint32_t length = 0;
    switch (static_cast<Opcode>(opcode)) {
      case Opcode::clear: length = CLEAR_WORDS; break;
      case Opcode::state: length = STATE_WORDS; break;
      case Opcode::triangle: length = TRIANGLE_WORDS; break;
    }
    if (length == 0) return fail(RasterError::bad_opcode, address);
    if (entry.word_count - pos < length) return fail(RasterError::list_overrun, address);
    if (!read(address + 4, raw + 4, 4 * (length - 1))) return;
    uint32_t words[CLEAR_WORDS];
    for (uint32_t i = 0; i < length; ++i) words[i] = load_le32(raw + 4 * i);
    ++m_result.commands;
    charge(m_result.tile_cycles, m_costs.command);
    pos += length;

    if (static_cast<Opcode>(opcode) == Opcode::state) {
      uint8_t block[STATE_BLOCK_BYTES];
      if (!read(words[1], block, sizeof block)) return;
      m_state = decode_state(words[1], block);
      continue;
    }
    if (!loaded) {
      // The colour and depth/stencil tiles are loaded unless the first
      // command that touches them overwrites every bit of them.
      if (!(static_cast<Opcode>(opcode) == Opcode::clear && is_full_clear(words[0], words[3]))) load_tile();
      loaded = true;
      if (failed()) return;
    }
    if (static_cast<Opcode>(opcode) == Opcode::clear) {
      clear(words);
    } else {
      draw_triangle(words[1]);
    }
  }
  if (loaded && !failed()) write_tile();
}

void TileRun::load_tile() {
  const RunConfig& c = m_config;
  const unsigned width = unsigned(m_tile.x1 - m_tile.x0), rows = unsigned(m_tile.y1 - m_tile.y0);
  const unsigned bpp = bytes_per_pixel(c.color_format);
  for (unsigned r = 0; r < rows; ++r) {
    const unsigned row = m_row0 + r;
    const uint32_t color_address = c.color_base + (row * c.width + unsigned(m_tile.x0)) * bpp;
    if (!read(color_address, m_row_bytes.data(), width * bpp)) return;
    for (unsigned x = 0; x < width; ++x) {
      const uint8_t* p = m_row_bytes.data() + x * bpp;
      m_color[r * c.tile_width + x] = Rgba8::unpack(unpack_pixel(c.color_format, load_pixel(c.color_format, p)));
    }
    const uint32_t depth_address = c.depth_base + (row * c.width + unsigned(m_tile.x0)) * 4;
    if (!read(depth_address, m_row_bytes.data(), width * 4)) return;
    for (unsigned x = 0; x < width; ++x) {
      const uint32_t v = load_le32(m_row_bytes.data() + x * 4);
      m_depth[r * c.tile_width + x] = v & 0xffffff;
      m_stencil[r * c.tile_width + x] = uint8_t(v >> 24);
    }
    charge(m_result.tile_cycles, uint64_t{m_costs.tile_write_word} * ((width * bpp + 3) / 4 + width));
  }
}

void TileRun::write_tile() {
  const RunConfig& c = m_config;
  const unsigned width = unsigned(m_tile.x1 - m_tile.x0), rows = unsigned(m_tile.y1 - m_tile.y0);
  const unsigned bpp = bytes_per_pixel(c.color_format);
  for (unsigned r = 0; r < rows; ++r) {
    for (unsigned x = 0; x < width; ++x)
      store_pixel(c.color_format, m_row_bytes.data() + x * bpp,
                  pack_pixel(c.color_format, m_color[r * c.tile_width + x].pack()));
    const uint32_t address = c.color_base + ((m_row0 + r) * c.width + unsigned(m_tile.x0)) * bpp;
    if (!write(address, m_row_bytes.data(), width * bpp)) return;
    charge(m_result.tile_cycles, uint64_t{m_costs.tile_write_word} * ((width * bpp + 3) / 4));
  }
  for (unsigned r = 0; r < rows; ++r) {
    for (unsigned x = 0; x < width; ++x) {
      const unsigned i = r * c.tile_width + x;
      store_le32(m_row_bytes.data() + x * 4, m_depth[i] | uint32_t{m_stencil[i]} << 24);
    }
    const uint32_t address = c.depth_base + ((m_row0 + r) * c.width + unsigned(m_tile.x0)) * 4;
    if (!write(address, m_row_bytes.data(), width * 4)) return;
    charge(m_result.tile_cycles, uint64_t{m_costs.tile_write_word} * width);
  }
}

void TileRun::clear(const uint32_t* words) {
  const uint32_t mask = (words[0] >> 8) & 7;
  const Rgba8 color = quantise(Rgba8::unpack(words[1]));
  const uint32_t depth = words[2] & 0xffffff;
  const uint8_t stencil = uint8_t(words[3]);
  const uint32_t color_mask = (words[3] >> 8) & 15;
  const bool depth_write = ((words[3] >> 12) & 1) != 0;
  const uint8_t stencil_mask = uint8_t(words[3] >> 16);
  uint32_t channel_bits = 0;
  for (unsigned ch = 0; ch < 4; ++ch)
    if (color_mask & (1u << ch)) channel_bits |= 0xffu << (8 * ch);
  const bool clear_color = (mask & 1) && channel_bits != 0;
  const bool clear_depth = (mask & 2) && depth_write;
  const bool clear_stencil = (mask & 4) && stencil_mask != 0;
  Rect area = m_tile;
  if (m_state.scissor)
    area = area.intersect({m_state.scissor_x0, m_state.scissor_y0, m_state.scissor_x1, m_state.scissor_y1});
  if (area.empty() || !(clear_color || clear_depth || clear_stencil)) return;
  for (int y = area.y0; y < area.y1; ++y) {
    for (int x = area.x0; x < area.x1; ++x) {
      const unsigned i = index(x, y);
      if (clear_color) m_color[i] = Rgba8::unpack((m_color[i].pack() & ~channel_bits) | (color.pack() & channel_bits));
      if (clear_depth) m_depth[i] = depth;
      if (clear_stencil) m_stencil[i] = uint8_t((m_stencil[i] & ~stencil_mask) | (stencil & stencil_mask));
    }
  }
  charge(m_result.tile_cycles,
         uint64_t{m_costs.tile_pixel_clear} * uint64_t(area.x1 - area.x0) * uint64_t(area.y1 - area.y0));
}

void TileRun::draw_triangle(uint32_t record_address) {
  uint8_t raw[TRIANGLE_RECORD_BYTES];
  if (!read(record_address, raw, sizeof raw)) return;
  std::array<Vertex, 3> v;
  for (unsigned k = 0; k < 3; ++k) {
    const uint8_t* p = raw + 24 * k;
    const uint32_t xy = load_le32(p);
    v[k].x = xy & 0xffff;
    v[k].y = xy >> 16;
    v[k].z = load_le32(p + 4) & 0xffffff;
    v[k].color = Rgba8::unpack(load_le32(p + 8));
    v[k].s_over_w = load_float(p + 12);
    v[k].t_over_w = load_float(p + 16);
    v[k].inv_w = load_float(p + 20);
    if (v[k].x > q9_4::MAX_RAW || v[k].y > q9_4::MAX_RAW) {  // not a 9.4 coordinate
      ++m_result.triangles_skipped;
      return;
    }
  }
  const bool smooth = (m_state.flags & StateFlag::polygon_smooth) != 0;
  // Pixels whose centre (16 p + 8 in 9.4) can be inside; antialiasing also
  // reaches the pixels just outside the edges.
  const uint32_t min_x = std::min({v[0].x, v[1].x, v[2].x}), max_x = std::max({v[0].x, v[1].x, v[2].x});
  const uint32_t min_y = std::min({v[0].y, v[1].y, v[2].y}), max_y = std::max({v[0].y, v[1].y, v[2].y});
  const int margin = smooth ? 1 : 0;
  Rect box{(int(min_x) + 7) / 16 - margin, (int(min_y) + 7) / 16 - margin, (int(max_x) - 8) / 16 + 1 + margin,
           (int(max_y) - 8) / 16 + 1 + margin};
  if (int(max_x) < 8) box.x1 = margin;
  if (int(max_y) < 8) box.y1 = margin;
  box = box.intersect(m_tile);
  if (m_state.scissor)
    box = box.intersect({m_state.scissor_x0, m_state.scissor_y0, m_state.scissor_x1, m_state.scissor_y1});
  if (box.empty()) return;

  const bool texture = (m_state.flags & StateFlag::texture) != 0;
  if (texture && (m_state.log2_width > TEXTURE_MAX_LOG2 || m_state.log2_height > TEXTURE_MAX_LOG2))
    return fail(RasterError::bad_texture, m_state.address + TEXTURE_SIZE_OFFSET);

  TriangleSetup ts;
  if (!setup(v, ts)) {
    ++m_result.triangles_skipped;
    return;
  }
  ++m_result.triangles;
  charge(m_result.setup_cycles, m_costs.setup);

  uint64_t visited = 0;
  for (int py = box.y1 - 1; py >= box.y0 && !failed(); --py) {  // top row first, as memory
    for (int px = box.x0; px < box.x1 && !failed(); ++px) {
      ++visited;
      unorm8 coverage = unorm8::from_raw(255);
      bool inside = true;
      unorm8 edge_cov[3];
      for (unsigned k = 0; k < 3; ++k) {
        const EdgeEvaluation e = evaluate_edge(ts.edges[k], unsigned(px), unsigned(py), ts.edge_recip[k]);
        inside = inside && e.inside;
        edge_cov[k] = e.coverage;
      }
      if (smooth) {
        coverage = triangle_coverage(edge_cov[0], edge_cov[1], edge_cov[2]);
        if (coverage.raw == 0) continue;
      } else if (!inside) {
        continue;
      }
      ++m_result.fragments;
      shade(ts, px, py, coverage);
    }
  }
  charge(m_result.fragment_cycles, uint64_t{m_costs.fragment} * visited);
}

bool TileRun::setup(const std::array<Vertex, 3>& vin, TriangleSetup& ts) {
  const RecipMethod method = m_config.recip_method;
  const auto vx = [&](unsigned k) { return int64_t{vin[k].x}; };
  const auto vy = [&](unsigned k) { return int64_t{vin[k].y}; };
  // Twice the signed area, 9.4 x 9.4 = 8 fraction bits; > 0 is counter-clockwise.
  const int64_t area = (vx(1) - vx(0)) * (vy(2) - vy(0)) - (vx(2) - vx(0)) * (vy(1) - vy(0));
  const uint64_t magnitude = uint64_t(area < 0 ? -area : area);
  Reciprocal inv_area;
  if (!refined_reciprocal(magnitude, method, inv_area)) return false;  // zero area: operand 0

  // Edges oriented clockwise (interior on their right, E > 0; edge_function.h).
  const std::array<unsigned, 3> order = area > 0 ? std::array<unsigned, 3>{0, 2, 1} : std::array<unsigned, 3>{0, 1, 2};
  for (unsigned k = 0; k < 3; ++k) {
    const Vertex& a = vin[order[k]];
    const Vertex& b = vin[order[(k + 1) % 3]];
    ts.edges[k] = {q9_4::from_raw(a.x), q9_4::from_raw(a.y), q9_4::from_raw(b.x), q9_4::from_raw(b.y)};
    const q10_4 l1 = edge_l1_length(ts.edges[k]);
    // Crisu et al.: |dx| + |dy| < 2^-4 is culled, so 1/X <= 16.
    if (l1.raw == 0 || l1.raw > RECIP_OPERAND_MAX) return false;
    ts.edge_recip[k] = reciprocal_fixed(l1, method);
  }

  ts.ref_x = int(vin[0].x >> 4);
  ts.ref_y = int(vin[0].y >> 4);
  const int64_t ref_dx = 16 * ts.ref_x + 8 - vx(0), ref_dy = 16 * ts.ref_y + 8 - vy(0);
  const bool negative = area < 0;
  // Plane through the three vertex words (in the kind's fraction): gradient
  // = 16 N / area (N in word x 9.4 units), start at the reference pixel
  // centre; every quotient is one multiplication by the refined reciprocal.
  const auto plane = [&](AttributeKind kind, const std::array<int64_t, 3>& w) {
    const int128 nx = int128(w[1] - w[0]) * (vy(2) - vy(0)) - int128(w[2] - w[0]) * (vy(1) - vy(0));
    const int128 ny = int128(w[2] - w[0]) * (vx(1) - vx(0)) - int128(w[1] - w[0]) * (vx(2) - vx(0));
    const int64_t grad_x = saturate_word(divide(nx * 16, inv_area, negative));
    const int64_t grad_y = saturate_word(divide(ny * 16, inv_area, negative));
    const int64_t start = saturate_word(int128(w[0]) + divide(nx * ref_dx + ny * ref_dy, inv_area, negative));
    return attribute_plane_from_raw(kind, start, grad_x, grad_y);
  };

  ts.flat = (m_state.flags & StateFlag::flat_shading) != 0;
  ts.flat_color = vin[2].color;
  ts.depth = plane(AttributeKind::depth, {int64_t{vin[0].z} << 8, int64_t{vin[1].z} << 8, int64_t{vin[2].z} << 8});

  // 1/w of the vertices scaled by one power of two so that the largest lies
  // in [1/2, 1): every ratio a = (a/w) / (1/w) is unchanged and the scaling
  // is exact.
  const bool texture = (m_state.flags & StateFlag::texture) != 0;
  bool usable_w = true;
  double max_inv_w = 0;
  for (const Vertex& v : vin) {
    usable_w = usable_w && std::isfinite(v.inv_w) && v.inv_w > 0;
    max_inv_w = std::max(max_inv_w, double(v.inv_w));
  }
  int exponent = 0;
  std::frexp(max_inv_w, &exponent);
  const auto scaled = [&](float value) { return std::ldexp(double(value), -exponent); };
  std::array<int64_t, 3> q{};
  for (unsigned k = 0; k < 3 && usable_w; ++k)
    q[k] = std::llround(std::ldexp(scaled(vin[k].inv_w), TEXCOORD_FRACTION_BITS));
  if (usable_w) ts.q = plane(AttributeKind::texcoord, q);

  // Gouraud colours are perspective-correct (GL 1.5 equation 3.6) when the
  // vertices' 1/w differ; with equal 1/w (orthographic) c/w over 1/w is c,
  // and the plain planes give it without a division. A triangle without
  // usable 1/w keeps screen-linear colours rather than being lost.
  ts.perspective_color = !ts.flat && usable_w && !(vin[0].inv_w == vin[1].inv_w && vin[1].inv_w == vin[2].inv_w);
  if (!ts.flat) {
    for (unsigned ch = 0; ch < 4; ++ch) {
      const auto channel = [&](unsigned k) {
        const int64_t code = (vin[k].color.pack() >> (8 * ch)) & 0xff;
        // c/w in colour words: code * 2^16 * (q_k / 2^24), rounded.
        if (ts.perspective_color) return int64_t((int128(code) * q[k] + (int64_t{1} << 7)) >> 8);
        return code << 16;
      };
      ts.color[ch] = plane(AttributeKind::color, {channel(0), channel(1), channel(2)});
    }
  }

  if (texture) {
    if (!usable_w) return false;
    for (const Vertex& v : vin)
      if (!std::isfinite(v.s_over_w) || !std::isfinite(v.t_over_w)) return false;
    std::array<int64_t, 3> s, t;
    for (unsigned k = 0; k < 3; ++k) {
      const double values[3] = {scaled(vin[k].s_over_w), scaled(vin[k].t_over_w), scaled(vin[k].inv_w)};
      for (double value : values)
        if (std::fabs(value) > TEXCOORD_LIMIT) return false;
      s[k] = std::llround(std::ldexp(values[0], TEXCOORD_FRACTION_BITS));
      t[k] = std::llround(std::ldexp(values[1], TEXCOORD_FRACTION_BITS));
    }
    ts.s = plane(AttributeKind::texcoord, s);
    ts.t = plane(AttributeKind::texcoord, t);
  }
  return true;
}

// Perspective-correct Gouraud colour: c = (c/w) / (1/w) per channel, the
// c/w sum in colour words (16 fraction bits, scaled by the normalised q) and
// q with 24 fraction bits, divided by the refined reciprocal of q into
// colour words and converted by the interpolator's output rule.
Rgba8 TileRun::perspective_color(const TriangleSetup& ts, int dx, int dy) const {
  const attribute_sum q = attribute_at(ts.q, dx, dy);
  Reciprocal inv_q;
  refined_reciprocal(uint64_t(std::max<int64_t>(q.raw, 1)), m_config.recip_method, inv_q);
  const auto channel = [&](unsigned ch) {
    const int128 c = divide(attribute_at(ts.color[ch], dx, dy).raw, inv_q, false, -int(TEXCOORD_FRACTION_BITS));
    return attribute_to_color(
        attribute_sum{int64_t(std::clamp<int128>(c, -ATTRIBUTE_WORD_MAX - 1, ATTRIBUTE_WORD_MAX))});
  };
  return {channel(0), channel(1), channel(2), channel(3)};
}

// Perspective division: s = (s/w) / (1/w) from the interpolators' exact
// sums (24 fraction bits) to the q15.16 that texel addressing takes.
void TileRun::texture_coords(attribute_sum s, attribute_sum t, attribute_sum q, q15_16& s_out, q15_16& t_out) const {
  // 1/w is positive inside the triangle; the few pixels just outside an
  // antialiased edge may extrapolate it to zero or below.
  Reciprocal inv_q;
  refined_reciprocal(uint64_t(std::max<int64_t>(q.raw, 1)), m_config.recip_method, inv_q);
  const auto to_q15_16 = [&](attribute_sum v) {
    const int128 r = divide(v.raw, inv_q, false, -16);
    return q15_16{int64_t(std::clamp<int128>(r, q15_16::MIN_RAW, q15_16::MAX_RAW))};
  };
  s_out = to_q15_16(s);
  t_out = to_q15_16(t);
}

bool TileRun::sample_texture(const TriangleSetup& ts, int dx, int dy, Rgba8 fragment, Rgba8& out) {
  const AttributeEvaluation s = evaluate_attribute(ts.s, dx, dy);
  const AttributeEvaluation t = evaluate_attribute(ts.t, dx, dy);
  const AttributeEvaluation q = evaluate_attribute(ts.q, dx, dy);
  q15_16 sc, tc;
  texture_coords(s.value, t.value, q.value, sc, tc);
  TextureState tex = m_state.texture;
  tex.filter = m_state.mag_filter;
  if (m_state.min_filter != m_state.mag_filter) {
    // GL's scale factor rho from the texel-space differences to the next
    // pixel in x and in y (as Mesa does per quad); rho > 1 minifies.
    q15_16 sx, tx, sy, ty;
    texture_coords(s.value_next_x, t.value_next_x, q.value_next_x, sx, tx);
    texture_coords(s.value_next_y, t.value_next_y, q.value_next_y, sy, ty);
    const auto texel_delta = [](q15_16 a, q15_16 b, unsigned log2) { return int128(b.raw - a.raw) << log2; };
    const int128 dux = texel_delta(sc, sx, tex.log2_width), dvx = texel_delta(tc, tx, tex.log2_height);
    const int128 duy = texel_delta(sc, sy, tex.log2_width), dvy = texel_delta(tc, ty, tex.log2_height);
    const int128 rho2 = std::max(dux * dux + dvx * dvx, duy * duy + dvy * dvy);
    if (rho2 > (int128{1} << 32)) tex.filter = m_state.min_filter;
  }
  const TexelFootprint footprint = texel_lookup(tex, sc, tc);
  const unsigned fetches = tex.filter == TexFilter::linear ? 4 : 1;
  std::array<Rgba8, 4> texels;
  for (unsigned k = 0; k < fetches; ++k) {
    uint8_t raw[4];
    if (!read(footprint.address[k], raw, 4, RasterError::bad_texture)) return false;
    texels[k] = Rgba8::unpack(load_le32(raw));
  }
  for (unsigned k = fetches; k < 4; ++k) texels[k] = texels[0];
  m_result.texels += fetches;
  charge(m_result.texel_cycles, uint64_t{m_costs.texel} * fetches);
  out = texture_filter_env(m_state.env, texels, footprint.s.weight, footprint.t.weight, fragment).fragment;
  return true;
}

// One fragment through texturing, coverage and the per-fragment operations
// in GL order (the scissor already bounds the traversal).
void TileRun::shade(const TriangleSetup& ts, int px, int py, unorm8 coverage) {
  const int dx = px - ts.ref_x, dy = py - ts.ref_y;
  Rgba8 color = ts.flat_color;
  if (ts.perspective_color) {
    color = perspective_color(ts, dx, dy);
  } else if (!ts.flat) {
    color = {
        attribute_to_color(attribute_at(ts.color[0], dx, dy)), attribute_to_color(attribute_at(ts.color[1], dx, dy)),
        attribute_to_color(attribute_at(ts.color[2], dx, dy)), attribute_to_color(attribute_at(ts.color[3], dx, dy))};
  }
  if (m_state.flags & StateFlag::texture) {
    if (!sample_texture(ts, dx, dy, color, color)) return;
  }
  if (m_state.flags & StateFlag::polygon_smooth) color.a = unorm8::from_raw(div255_round(color.a.raw * coverage.raw));

  const unsigned i = index(px, py);
  const unorm24 depth = attribute_to_depth(attribute_at(ts.depth, dx, dy));
  const FragmentOperationsResult out = fragment_operations(
      m_state.operations, color, depth, m_color[i], unorm24::from_raw(m_depth[i]), stencil8::from_raw(m_stencil[i]));
  m_stencil[i] = out.stencil;
  if (out.depth_write) m_depth[i] = depth.raw;
  if (!out.pass) return;
  ++m_result.fragments_written;
  m_color[i] = quantise(out.color);
}

}  // namespace

TileRasterizer::TileRasterizer(RasterPort& port, const CycleCosts& costs) : m_port(port), m_costs(costs) {}

RunResult TileRasterizer::run(const RunConfig& config) {
  return TileRun(m_port, m_costs, config).execute();
}

}  // namespace tessera::raster
