// Unit tests of the tile rasterizer's functional core: command lists built by
// hand in a plain memory, results checked against independent references
// (edge functions with the GL fill rule, barycentric colours, the texture's
// own texels) and against the error contract of command_format.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "raster/core/tile_rasterizer.h"
#include "raster/datapath/texture_combiner.h"
#include "raster_core_test_support.h"

using namespace tessera::raster;
using tessera::BlendFactor;
using tessera::code_of;
using tessera::CombineFunc;
using tessera::CombineOperand;
using tessera::CombineSource;
using tessera::CompareFunc;
using tessera::FogMode;
using tessera::LogicOp;
using tessera::TexEnv;
using tessera::TexFilter;
using tessera::TexWrap;
using tessera::raster::test::blend_codes;
using tessera::raster::test::default_state;
using tessera::raster::test::VectorPort;

namespace {

constexpr uint32_t TILE_TABLE = 0x1000;
constexpr uint32_t COLOR_BASE = 0x10000;
constexpr uint32_t DEPTH_BASE = 0x40000;
constexpr uint32_t DATA_BASE = 0x80000;
constexpr uint32_t TEXTURE_BASE = 0x180000;
constexpr uint32_t MEMORY_SIZE = 0x200000;

// Flags and codes as the driver writes them.
constexpr uint32_t CLEAR_ALL = 1 | 7u << 8;
constexpr uint32_t CLEAR_MASKS = 15u << 8 | 1u << 12 | 0xffu << 16;

VertexRecord vertex(double x, double y, uint32_t rgba = 0xffffffff, uint32_t z = 0, float s = 0, float t = 0,
                    float w = 1) {
  VertexRecord v{};
  v.xy = uint32_t(std::lround(x * 16)) | uint32_t(std::lround(y * 16)) << 16;
  v.z = z;
  v.rgba = rgba;
  v.s_over_w = s / w;
  v.t_over_w = t / w;
  v.inv_w = 1 / w;
  return v;
}

// A frame: one command list per tile; every command goes to every tile (no
// binning), so the rasterizer's own bounding-box test is exercised too.
class Frame {
 public:
  Frame(VectorPort& port, unsigned width, unsigned height, bool rgba8888 = true) : m_port(port) {
    config.width = width;
    config.height = height;
    config.tile_table = TILE_TABLE;
    config.color_base = COLOR_BASE;
    config.depth_base = DEPTH_BASE;
    config.color_format = rgba8888 ? tessera::PixelFormat::rgba8888 : tessera::PixelFormat::rgb565;
    tiles_x = (width + config.tile_width - 1) / config.tile_width;
    tiles_y = (height + config.tile_height - 1) / config.tile_height;
    lists.resize(tiles_x * tiles_y);
  }
  uint32_t put(const void* data, unsigned bytes) {
    const uint32_t address = m_next;
    std::memcpy(m_port.memory.data() + address, data, bytes);
    m_next += (bytes + 3) & ~3u;
    return address;
  }
  void all(std::initializer_list<uint32_t> words) {
    for (auto& list : lists) list.insert(list.end(), words);
  }
  void clear(uint32_t rgba, uint32_t depth = 0xffffff, uint32_t stencil = 0) {
    all({CLEAR_ALL, rgba, depth, stencil | CLEAR_MASKS});
  }
  void state(const StateBlock& s) {
    const uint32_t a = put(&s, sizeof s);
    all({uint32_t(Opcode::state), a});
  }
  void triangle(const VertexRecord& a, const VertexRecord& b, const VertexRecord& c) {
    const TriangleRecord t{{a, b, c}};
    const uint32_t address = put(&t, sizeof t);
    all({uint32_t(Opcode::triangle), address});
  }
  // A state with the fog flag and its FogState right after the block.
  void fog_state(StateBlock s, const FogState& fog) {
    s.flags |= StateFlag::fog;
    struct {
      StateBlock block;
      FogState fog;
    } words{s, fog};
    static_assert(sizeof words == state_block_bytes(StateFlag::fog), "block and fog words");
    const uint32_t a = put(&words, sizeof words);
    all({uint32_t(Opcode::state), a});
  }
  // A triangle record followed by its TriangleFog (drawn with a fog state).
  void fog_triangle(const VertexRecord& a, const VertexRecord& b, const VertexRecord& c, const TriangleFog& fog) {
    struct {
      TriangleRecord record;
      TriangleFog fog;
    } words{{{a, b, c}}, fog};
    static_assert(sizeof words == triangle_record_bytes(StateFlag::fog), "record and fog words");
    const uint32_t address = put(&words, sizeof words);
    all({uint32_t(Opcode::triangle), address});
  }
  // Writes the lists and the tile table; word_count_extra lengthens none.
  void finish() {
    for (size_t i = 0; i < lists.size(); ++i) {
      const uint32_t address = put(lists[i].data(), unsigned(lists[i].size() * 4));
      m_port.set_word(TILE_TABLE + 8 * uint32_t(i), address);
      m_port.set_word(TILE_TABLE + 8 * uint32_t(i) + 4, uint32_t(lists[i].size()));
    }
  }
  uint32_t list_address(size_t tile) const { return m_port.word(TILE_TABLE + 8 * uint32_t(tile)); }
  // Colour of GL pixel (x, y).
  uint32_t pixel(unsigned x, unsigned y) const {
    return m_port.word(COLOR_BASE + ((config.height - 1 - y) * config.width + x) * 4);
  }
  uint32_t depth_word(unsigned x, unsigned y) const {
    return m_port.word(DEPTH_BASE + ((config.height - 1 - y) * config.width + x) * 4);
  }

  RunConfig config;
  unsigned tiles_x = 0, tiles_y = 0;
  std::vector<std::vector<uint32_t>> lists;

 private:
  VectorPort& m_port;
  uint32_t m_next = DATA_BASE;
};

RunResult run(VectorPort& port, const RunConfig& config) {
  TileRasterizer rasterizer(port);
  const RunResult r = rasterizer.run(config);
  EXPECT_EQ(r.setup_cycles + r.tile_cycles + r.fragment_cycles + r.texel_cycles, port.total_cycles);
  return r;
}

// Independent coverage reference: GL window coordinates, 9.4 vertices,
// centre (x + 1/2, y + 1/2). With the triangle turned counter-clockwise, a
// sample is inside if it is strictly left of every edge, or on an edge that
// is a left edge (going down) or a bottom edge (going +x) -- the rule Mesa
// applies to window-system drawables.
bool reference_inside(const VertexRecord (&v)[3], unsigned px, unsigned py) {
  int64_t x[3], y[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = v[k].xy & 0xffff;
    y[k] = v[k].xy >> 16;
  }
  const int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  if (area == 0) return false;
  int order[3] = {0, 1, 2};
  if (area < 0) std::swap(order[1], order[2]);
  const int64_t sx = 16 * px + 8, sy = 16 * py + 8;
  for (int k = 0; k < 3; ++k) {
    const int a = order[k], b = order[(k + 1) % 3];
    const int64_t dx = x[b] - x[a], dy = y[b] - y[a];
    const int64_t cross = dx * (sy - y[a]) - dy * (sx - x[a]);
    if (cross < 0) return false;
    if (cross == 0 && !(dy < 0 || (dy == 0 && dx > 0))) return false;
  }
  return true;
}

TEST(TileRasterizer, ClearAndTriangleCoverageMatchEdgeFunctionReference) {
  const VertexRecord shapes[][3] = {
      {vertex(3.3, 2.7), vertex(70.9, 10.2), vertex(20.1, 45.6)},         // counter-clockwise
      {vertex(80.5, 40.5), vertex(40.5, 40.5), vertex(40.5, 4.5)},        // clockwise, edges through centres
      {vertex(10.5, 30.5), vertex(90.5, 30.5), vertex(50.5, 30.5 + 16)},  // horizontal edge on centres
      {vertex(0, 0), vertex(95.9375, 0.0625), vertex(1, 47.9375)},        // screen-sized
  };
  for (const auto& tri : shapes) {
    VectorPort port(MEMORY_SIZE);
    Frame frame(port, 96, 48);
    frame.clear(0xff000000);
    frame.triangle(tri[0], tri[1], tri[2]);
    frame.finish();
    const RunResult r = run(port, frame.config);
    ASSERT_EQ(r.error, RasterError::none);
    EXPECT_EQ(r.tiles, 9u);
    uint64_t covered = 0, mismatches = 0;
    for (unsigned y = 0; y < 48; ++y) {
      for (unsigned x = 0; x < 96; ++x) {
        const bool expected = reference_inside(tri, x, y);
        covered += expected;
        mismatches += (frame.pixel(x, y) == 0xffffffffu) != expected;
        EXPECT_EQ(frame.depth_word(x, y), 0xffffffu);  // depth test off: the clear stays
      }
    }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(r.fragments, covered);
    EXPECT_EQ(r.fragments_written, covered);
  }
}

// A grid of quads (two triangles each, jittered inner vertices) across tile
// borders drawn with additive blending: every pixel inside the grid's outer
// rectangle is drawn exactly once.
TEST(TileRasterizer, SharedEdgesDrawnOnceAcrossTiles) {
  VectorPort port(MEMORY_SIZE);
  Frame frame(port, 96, 48);
  frame.clear(0);
  StateBlock s = default_state();
  s.flags |= blend;
  s.blend = blend_codes(BlendFactor::one, BlendFactor::one);
  frame.state(s);
  constexpr int NX = 7, NY = 4;
  const double x0 = 2.3, x1 = 93.7, y0 = 1.8, y1 = 45.2;
  double gx[NX + 1][NY + 1], gy[NX + 1][NY + 1];
  for (int i = 0; i <= NX; ++i) {
    for (int j = 0; j <= NY; ++j) {
      const bool inner_x = i > 0 && i<NX, inner_y = j> 0 && j < NY;
      gx[i][j] = x0 + (x1 - x0) * i / NX + (inner_x ? ((i * 7 + j * 3) % 5 - 2) * 0.8125 : 0);
      gy[i][j] = y0 + (y1 - y0) * j / NY + (inner_y ? ((i * 5 + j * 11) % 7 - 3) * 0.5 : 0);
      if (i == 3 && inner_y) gx[i][j] = 32.5;  // a vertical edge through pixel centres
    }
  }
  for (int i = 0; i < NX; ++i) {
    for (int j = 0; j < NY; ++j) {
      const auto v = [&](int a, int b) { return vertex(gx[a][b], gy[a][b], 0x01010101); };
      frame.triangle(v(i, j), v(i + 1, j), v(i + 1, j + 1));
      frame.triangle(v(i, j), v(i + 1, j + 1), v(i, j + 1));
    }
  }
  frame.finish();
  const RunResult r = run(port, frame.config);
  ASSERT_EQ(r.error, RasterError::none);
  for (unsigned y = 0; y < 48; ++y) {
    for (unsigned x = 0; x < 96; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;
      const bool inside = cx > x0 && cx < x1 && cy > y0 && cy < y1;
      EXPECT_EQ(frame.pixel(x, y), inside ? 0x01010101u : 0u) << "pixel " << x << "," << y;
    }
  }
}

TEST(TileRasterizer, DepthTestIsOrderIndependent) {
  std::vector<uint32_t> images[2];
  for (int order = 0; order < 2; ++order) {
    VectorPort port(MEMORY_SIZE);
    Frame frame(port, 96, 48);
    frame.clear(0xff000000);
    StateBlock s = default_state();
    s.flags |= depth_test;
    frame.state(s);
    // Two slanted triangles that cross each other.
    const VertexRecord a[3] = {vertex(5, 5, 0xff0000ff, 0x100000), vertex(90, 10, 0xff0000ff, 0xf00000),
                               vertex(40, 44, 0xff0000ff, 0x800000)};
    const VertexRecord b[3] = {vertex(8, 40, 0xff00ff00, 0xe00000), vertex(85, 42, 0xff00ff00, 0x200000),
                               vertex(50, 2, 0xff00ff00, 0x700000)};
    if (order == 0) {
      frame.triangle(a[0], a[1], a[2]);
      frame.triangle(b[0], b[1], b[2]);
    } else {
      frame.triangle(b[0], b[1], b[2]);
      frame.triangle(a[0], a[1], a[2]);
    }
    frame.finish();
    ASSERT_EQ(run(port, frame.config).error, RasterError::none);
    for (unsigned y = 0; y < 48; ++y)
      for (unsigned x = 0; x < 96; ++x) images[order].push_back(frame.pixel(x, y));
  }
  EXPECT_EQ(images[0], images[1]);
  EXPECT_NE(std::count(images[0].begin(), images[0].end(), 0xff0000ffu), 0);
  EXPECT_NE(std::count(images[0].begin(), images[0].end(), 0xff00ff00u), 0);
}

TEST(TileRasterizer, GouraudMatchesBarycentricColours) {
  VectorPort port(MEMORY_SIZE);
  Frame frame(port, 96, 48);
  frame.clear(0);
  const double px[3] = {4.5, 91.5, 30.5}, py[3] = {3.5, 3.5, 44.5};
  const uint32_t rgba[3] = {0xff0000ff, 0x8000ff00, 0x40ff0000};
  const VertexRecord tri[3] = {vertex(px[0], py[0], rgba[0]), vertex(px[1], py[1], rgba[1]),
                               vertex(px[2], py[2], rgba[2])};
  frame.triangle(tri[0], tri[1], tri[2]);
  frame.finish();
  ASSERT_EQ(run(port, frame.config).error, RasterError::none);
  const double area = (px[1] - px[0]) * (py[2] - py[0]) - (px[2] - px[0]) * (py[1] - py[0]);
  int worst = 0;
  for (unsigned y = 0; y < 48; ++y) {
    for (unsigned x = 0; x < 96; ++x) {
      if (!reference_inside(tri, x, y)) continue;
      const double cx = x + 0.5, cy = y + 0.5;
      const double b1 = ((cx - px[0]) * (py[2] - py[0]) - (px[2] - px[0]) * (cy - py[0])) / area;
      const double b2 = ((px[1] - px[0]) * (cy - py[0]) - (cx - px[0]) * (py[1] - py[0])) / area;
      const double b0 = 1 - b1 - b2;
      const uint32_t got = frame.pixel(x, y);
      for (int ch = 0; ch < 4; ++ch) {
        const auto c = [&](int k) { return double((rgba[k] >> (8 * ch)) & 0xff); };
        const int expected = int(std::lround(b0 * c(0) + b1 * c(1) + b2 * c(2)));
        worst = std::max(worst, std::abs(int((got >> (8 * ch)) & 0xff) - expected));
      }
    }
  }
  EXPECT_LE(worst, 1);
  // The vertex that lies on a pixel centre covered by the fill rule gets its
  // own colour exactly.
  EXPECT_TRUE(reference_inside(tri, 4, 3));
  EXPECT_EQ(frame.pixel(4, 3), rgba[0]);
}

void put_texture(VectorPort& port, unsigned w, unsigned h) {
  for (unsigned j = 0; j < h; ++j)
    for (unsigned i = 0; i < w; ++i) port.set_word(TEXTURE_BASE + (j * w + i) * 4, 0xff000000u | j << 8 | i);
}

TEST(TileRasterizer, TextureNearestRepeat) {
  VectorPort port(MEMORY_SIZE);
  put_texture(port, 4, 4);
  Frame frame(port, 96, 48);
  frame.clear(0);
  StateBlock s = default_state();
  s.flags |= texture;
  s.texture_address = TEXTURE_BASE;
  s.texture_size = 2 | 2u << 8;
  s.texture_mode = code_of(TexEnv::replace) << TEXTURE_ENV_SHIFT;  // nearest, repeat
  frame.state(s);
  // Quad [16, 48) x [8, 24): s from 0 to 2, t from 0 to 1.
  const VertexRecord a = vertex(16, 8, ~0u, 0, 0, 0), b = vertex(48, 8, ~0u, 0, 2, 0), c = vertex(48, 24, ~0u, 0, 2, 1),
                     d = vertex(16, 24, ~0u, 0, 0, 1);
  frame.triangle(a, b, c);
  frame.triangle(a, c, d);
  frame.finish();
  const RunResult r = run(port, frame.config);
  ASSERT_EQ(r.error, RasterError::none);
  EXPECT_EQ(r.texels, 32u * 16u);
  for (unsigned y = 8; y < 24; ++y) {
    for (unsigned x = 16; x < 48; ++x) {
      const unsigned i = unsigned(std::floor((x - 16 + 0.5) / 32 * 2 * 4)) % 4;
      const unsigned j = unsigned(std::floor((y - 8 + 0.5) / 16 * 4)) % 4;
      EXPECT_EQ(frame.pixel(x, y), 0xff000000u | j << 8 | i) << x << "," << y;
    }
  }
}

// A texel fetch that fails in the middle of a triangle (the shader takes
// the triangle's fragments as one batch): the run stops at that fragment,
// which is counted with those before it in the traversal's order, their
// texels and the pixels visited up to it are counted too, and the error is
// the failing texel's address. A 1 x 16 texture, t falling from 1 at the
// top row to 0 at the bottom, its rows 8 and above refused: the rows 46 to
// 40 fetch rows 0 to 7, row 39 fails at its first fragment.
TEST(TileRasterizer, TexelFetchFailingMidTriangleStopsAtThatFragment) {
  VectorPort port(MEMORY_SIZE);
  put_texture(port, 1, 16);
  port.fail_begin = TEXTURE_BASE + 8 * 4;
  port.fail_end = TEXTURE_BASE + 16 * 4;
  Frame frame(port, 96, 48);
  frame.clear(0);
  StateBlock s = default_state();
  s.flags |= texture;
  s.texture_address = TEXTURE_BASE;
  s.texture_size = 0 | 4u << 8;
  s.texture_mode = code_of(TexEnv::replace) << TEXTURE_ENV_SHIFT;  // nearest, repeat
  frame.state(s);
  const VertexRecord tri[3] = {vertex(2, 33, ~0u, 0, 0, 1), vertex(30, 33, ~0u, 0, 0, 1), vertex(2, 47, ~0u, 0, 0, 0)};
  frame.triangle(tri[0], tri[1], tri[2]);
  frame.finish();
  const RunResult r = run(port, frame.config);
  EXPECT_EQ(r.error, RasterError::bad_texture);
  EXPECT_EQ(r.error_address, TEXTURE_BASE + 8 * 4);
  // The box is x 2..29, y 33..46; the rows above 39 are drawn whole.
  uint64_t before = 0;
  for (unsigned y = 40; y <= 46; ++y)
    for (unsigned x = 2; x < 30; ++x) before += reference_inside(tri, x, y);
  unsigned first = 2;
  while (!reference_inside(tri, first, 39)) ++first;
  EXPECT_EQ(r.fragments, before + 1);
  EXPECT_EQ(r.texels, before);  // nearest: one each
  EXPECT_EQ(r.fragment_cycles, 7u * 28u + (first - 2 + 1));
  EXPECT_GT(before, 40u);
}

// Perspective: 1/w varies across the quad; s must follow (s/w)/(1/w), not
// the affine interpolation.
TEST(TileRasterizer, TextureCoordinatesArePerspectiveCorrect) {
  VectorPort port(MEMORY_SIZE);
  put_texture(port, 256, 1);
  Frame frame(port, 96, 48);
  frame.clear(0);
  StateBlock s = default_state();
  s.flags |= texture;
  s.texture_address = TEXTURE_BASE;
  s.texture_size = 8;
  s.texture_mode = code_of(TexEnv::replace) << TEXTURE_ENV_SHIFT |
                   code_of(TexWrap::clamp_to_edge) << TEXTURE_WRAP_S_SHIFT |
                   code_of(TexWrap::clamp_to_edge) << TEXTURE_WRAP_T_SHIFT;  // nearest
  frame.state(s);
  const float w_left = 1, w_right = 4;
  const VertexRecord a = vertex(0, 0, ~0u, 0, 0, 0.5f, w_left), b = vertex(96, 0, ~0u, 0, 1, 0.5f, w_right),
                     c = vertex(96, 48, ~0u, 0, 1, 0.5f, w_right), d = vertex(0, 48, ~0u, 0, 0, 0.5f, w_left);
  frame.triangle(a, b, c);
  frame.triangle(a, c, d);
  frame.finish();
  ASSERT_EQ(run(port, frame.config).error, RasterError::none);
  unsigned off_by_more = 0;
  for (unsigned x = 0; x < 96; ++x) {
    const double f = (x + 0.5) / 96;
    const double sv = (f / w_right) / ((1 - f) / w_left + f / w_right);
    const int expected = std::min(255, int(std::floor(sv * 256)));
    const int got = int(frame.pixel(x, 20) & 0xff);
    off_by_more += std::abs(got - expected) > 1;
  }
  EXPECT_EQ(off_by_more, 0u);
}

// Gouraud colours in perspective follow (c/w)/(1/w) too (GL 1.5 eq. 3.6,
// as Mesa does): red from 0 at the near edge to 255 at the far one is well
// below the affine ramp in the middle of the quad.
TEST(TileRasterizer, GouraudColoursArePerspectiveCorrect) {
  VectorPort port(MEMORY_SIZE);
  Frame frame(port, 96, 48);
  frame.clear(0);
  const float w_left = 1, w_right = 4;
  const uint32_t black = 0xff000000u, red = 0xff0000ffu;
  const VertexRecord a = vertex(0, 0, black, 0, 0, 0, w_left), b = vertex(96, 0, red, 0, 0, 0, w_right),
                     c = vertex(96, 48, red, 0, 0, 0, w_right), d = vertex(0, 48, black, 0, 0, 0, w_left);
  frame.triangle(a, b, c);
  frame.triangle(a, c, d);
  frame.finish();
  ASSERT_EQ(run(port, frame.config).error, RasterError::none);
  int worst = 0;
  for (unsigned y : {5u, 20u, 40u}) {
    for (unsigned x = 0; x < 96; ++x) {
      const double f = (x + 0.5) / 96;
      const double r = 255 * (f / w_right) / ((1 - f) / w_left + f / w_right);
      worst = std::max(worst, std::abs(int(frame.pixel(x, y) & 0xff) - int(std::lround(r))));
    }
  }
  EXPECT_LE(worst, 1);
  // The affine ramp would give 128 at the middle; the perspective one 52.
  EXPECT_NEAR(int(frame.pixel(48, 20) & 0xff), 52, 1);
}

// Fog, exp mode, on a quad seen in perspective: the fog argument is
// interpolated as a/w over 1/w (as Mesa interpolates its fog coordinate),
// then f = 2^-a and C = f Cf + (1 - f) Cfog, computed here in double from
// GL's formulas; within 1 code (the factor's 0.82 and the blend's rounding
// over |Cf - Cfog| = 255, and the perspective division).
TEST(TileRasterizer, FogIsPerFragmentAndPerspectiveCorrect) {
  VectorPort port(MEMORY_SIZE);
  Frame frame(port, 96, 48);
  frame.clear(0);
  FogState fog{};
  fog.mode = code_of(FogMode::exp) << FOG_MODE_SHIFT;
  fog.color = 0x000000ffu;  // red fog
  frame.fog_state(default_state(), fog);
  const float w_left = 1, w_right = 4;
  const double a_left = 0.25, a_right = 3.0;  // fog arguments, 2^-a
  const int32_t fa = int32_t(std::lround(a_left * 65536)), fb = int32_t(std::lround(a_right * 65536));
  const uint32_t white = 0xffffffffu;
  const VertexRecord a = vertex(0, 0, white, 0, 0, 0, w_left), b = vertex(96, 0, white, 0, 0, 0, w_right),
                     c = vertex(96, 48, white, 0, 0, 0, w_right), d = vertex(0, 48, white, 0, 0, 0, w_left);
  frame.fog_triangle(a, b, c, TriangleFog{{fa, fb, fb}});
  frame.fog_triangle(a, c, d, TriangleFog{{fa, fb, fa}});
  frame.finish();
  ASSERT_EQ(run(port, frame.config).error, RasterError::none);
  int worst = 0;
  for (unsigned y : {5u, 20u, 40u}) {
    for (unsigned x = 0; x < 96; ++x) {
      const double t = (x + 0.5) / 96;
      const double argument = ((1 - t) * a_left / w_left + t * a_right / w_right) / ((1 - t) / w_left + t / w_right);
      const double f = std::exp2(-argument);
      const uint32_t p = frame.pixel(x, y);
      worst = std::max(worst, std::abs(int((p >> 8) & 0xff) - int(std::lround(255 * f))));  // green: 255 f
      EXPECT_EQ(p & 0xff, 0xffu);                                                           // red stays 255
      EXPECT_EQ(p >> 24, 0xffu);                                                            // alpha is not fogged
    }
  }
  EXPECT_LE(worst, 1);
}

// A run without the fog flag reads no fog words: a fog state's extension
// and a fog record's are only read under the flag (state_block_bytes and
// triangle_record_bytes of 0 are the plain sizes).
TEST(TileRasterizer, FogExtensionsOnlyWithTheFlag) {
  EXPECT_EQ(state_block_bytes(0), sizeof(StateBlock));
  EXPECT_EQ(triangle_record_bytes(0), sizeof(TriangleRecord));
  EXPECT_EQ(state_block_bytes(StateFlag::fog), sizeof(StateBlock) + 8);
  EXPECT_EQ(triangle_record_bytes(StateFlag::fog), sizeof(TriangleRecord) + 12);
}

TEST(TileRasterizer, BlendingSourceAlpha) {
  VectorPort port(MEMORY_SIZE);
  Frame frame(port, 96, 48);
  frame.clear(0xff0064c8);  // r 200, g 100, b 0, a 255
  StateBlock s = default_state();
  s.flags |= blend;
  s.blend = blend_codes(BlendFactor::src_alpha, BlendFactor::one_minus_src_alpha);
  frame.state(s);
  frame.triangle(vertex(10, 10, 0x80ff0000), vertex(60, 10, 0x80ff0000), vertex(10, 40, 0x80ff0000));
  frame.finish();
  ASSERT_EQ(run(port, frame.config).error, RasterError::none);
  const auto mul = [](unsigned a, unsigned b) { return unsigned(std::lround(a * b / 255.0)); };
  const unsigned r = mul(0, 128) + mul(200, 127), g = mul(0, 128) + mul(100, 127), b = mul(255, 128) + mul(0, 127),
                 a = std::min(255u, mul(128, 128) + mul(255, 127));
  EXPECT_EQ(frame.pixel(20, 20), r | g << 8 | b << 16 | a << 24);
  EXPECT_EQ(frame.pixel(80, 40), 0xff0064c8u);
}

TEST(TileRasterizer, Rgb565FrameBufferRoundTrips) {
  VectorPort port(MEMORY_SIZE);
  Frame frame(port, 96, 48, false);
  frame.clear(0xff336699);  // r 0x99, g 0x66, b 0x33
  frame.finish();
  ASSERT_EQ(run(port, frame.config).error, RasterError::none);
  uint16_t v;
  std::memcpy(&v, port.memory.data() + COLOR_BASE + 2 * (5 * 96 + 7), 2);
  const auto q = [](unsigned c, unsigned max) { return unsigned(std::lround(c * double(max) / 255)); };
  EXPECT_EQ(v, q(0x99, 31) << 11 | q(0x66, 63) << 5 | q(0x33, 31));
}

// Errors: the run stops; tiles before the failing one are written, the
// failing tile and those after it are left as they were.
struct ErrorCase {
  VectorPort port{MEMORY_SIZE};
  Frame frame{port, 96, 48};
  static constexpr uint32_t SENTINEL = 0x5a5a5a5a;
  static constexpr size_t BAD_TILE = 4;

  ErrorCase() {
    for (uint32_t a = COLOR_BASE; a < COLOR_BASE + 96 * 48 * 4; a += 4) port.set_word(a, SENTINEL);
    frame.clear(0xff112233);
  }
  RunResult run_and_check_tiles(size_t written_tiles) {
    const RunResult r = run(port, frame.config);
    for (size_t t = 0; t < frame.lists.size(); ++t) {
      const unsigned x = unsigned(t % 3) * 32 + 5, row = unsigned(t / 3) * 16 + 3;
      EXPECT_EQ(frame.pixel(x, 47 - row), t < written_tiles ? 0xff112233u : SENTINEL) << "tile " << t;
    }
    return r;
  }
};

TEST(TileRasterizer, ListOverrunStopsTheRun) {
  ErrorCase c;
  c.frame.lists[ErrorCase::BAD_TILE].push_back(uint32_t(Opcode::triangle));  // its address word is missing
  c.frame.finish();
  const RunResult r = c.run_and_check_tiles(ErrorCase::BAD_TILE);
  EXPECT_EQ(r.error, RasterError::list_overrun);
  EXPECT_EQ(r.error_address, c.frame.list_address(ErrorCase::BAD_TILE) + 16);
  EXPECT_EQ(r.tiles, ErrorCase::BAD_TILE + 1);
}

TEST(TileRasterizer, BadOpcodeStopsTheRun) {
  ErrorCase c;
  c.frame.lists[ErrorCase::BAD_TILE].push_back(0x55);
  c.frame.finish();
  const RunResult r = c.run_and_check_tiles(ErrorCase::BAD_TILE);
  EXPECT_EQ(r.error, RasterError::bad_opcode);
  EXPECT_EQ(r.error_address, c.frame.list_address(ErrorCase::BAD_TILE) + 16);
}

TEST(TileRasterizer, BusErrorOnARecordStopsTheRun) {
  ErrorCase c;
  const uint32_t bad = 0x1f0000;
  c.port.fail_begin = bad;
  c.port.fail_end = bad + 0x100;
  c.frame.lists[ErrorCase::BAD_TILE].insert(c.frame.lists[ErrorCase::BAD_TILE].end(),
                                            {uint32_t(Opcode::triangle), bad + 8});
  c.frame.finish();
  const RunResult r = c.run_and_check_tiles(ErrorCase::BAD_TILE);
  EXPECT_EQ(r.error, RasterError::bus_error);
  EXPECT_EQ(r.error_address, bad + 8);
}

TEST(TileRasterizer, BusErrorOnTileWriteBack) {
  ErrorCase c;
  c.frame.finish();
  // The first colour row of tile 4 (tile row 1, column 1) fails.
  const uint32_t row_address = COLOR_BASE + (16 * 96 + 32) * 4;
  c.port.fail_begin = row_address;
  c.port.fail_end = row_address + 4;
  const RunResult r = c.run_and_check_tiles(ErrorCase::BAD_TILE);
  EXPECT_EQ(r.error, RasterError::bus_error);
  EXPECT_EQ(r.error_address, row_address);
}

TEST(TileRasterizer, BadTextureSizeAndTexelsOutsideMemory) {
  for (int kind = 0; kind < 2; ++kind) {
    ErrorCase c;
    StateBlock s = default_state();
    s.flags |= texture;
    s.texture_address = kind == 0 ? TEXTURE_BASE : MEMORY_SIZE - 64;
    s.texture_size = kind == 0 ? (9 | 2u << 8) : (4 | 4u << 8);
    const uint32_t state_address = c.frame.put(&s, sizeof s);
    const TriangleRecord t{{vertex(34, 20, ~0u, 0, 0, 0), vertex(60, 20, ~0u, 0, 1, 0), vertex(34, 30, ~0u, 0, 0, 1)}};
    const uint32_t record = c.frame.put(&t, sizeof t);
    c.frame.lists[ErrorCase::BAD_TILE].insert(
        c.frame.lists[ErrorCase::BAD_TILE].end(),
        {uint32_t(Opcode::state), state_address, uint32_t(Opcode::triangle), record});
    c.frame.finish();
    const RunResult r = c.run_and_check_tiles(ErrorCase::BAD_TILE);
    EXPECT_EQ(r.error, RasterError::bad_texture);
    if (kind == 0) {
      EXPECT_EQ(r.error_address, state_address + 40);
    } else {
      EXPECT_GE(r.error_address, MEMORY_SIZE - 4);
    }
  }
}

// The texture unit extension's sizes (command_format.h): the header and
// seven words per unit after the fog words; six words per further unit
// after the triangle's fog words.
TEST(TileRasterizer, TextureUnitExtensionSizes) {
  EXPECT_EQ(state_block_bytes(StateFlag::texture_units, 2), sizeof(StateBlock) + 4 + 2 * 28);
  EXPECT_EQ(state_block_bytes(StateFlag::texture_units | StateFlag::fog, 1), sizeof(StateBlock) + 8 + 4 + 28);
  EXPECT_EQ(texture_units_offset(StateFlag::fog | StateFlag::texture_units), sizeof(StateBlock) + 8);
  EXPECT_EQ(triangle_record_bytes(StateFlag::texture_units, 1), sizeof(TriangleRecord));
  EXPECT_EQ(triangle_record_bytes(StateFlag::texture_units, 3), sizeof(TriangleRecord) + 2 * 24);
  EXPECT_EQ(triangle_record_bytes(StateFlag::texture_units | StateFlag::fog, 2), sizeof(TriangleRecord) + 12 + 24);
  EXPECT_EQ(triangle_record_bytes(0, 3), sizeof(TriangleRecord));  // units only count with the flag
}

// Two texture units (ES 1.1 section 3.7.12): unit 0 MODULATEs the flat
// fragment colour with a 4 x 4 texture at its own coordinates, unit 1 ADDs
// a 2 x 2 texture at coordinates of its own (from the TriangleUnitCoords)
// to that result; both nearest, repeat. Each pixel is worked out here from
// the texel the pixel centre falls in and the table 3.16 formulas, with
// products divided by 255 and rounded to nearest.
TEST(TileRasterizer, TwoTextureUnitsModulateThenAdd) {
  VectorPort port(MEMORY_SIZE);
  constexpr uint32_t TEXTURE1 = TEXTURE_BASE + 0x1000;
  const auto texel0 = [](unsigned i, unsigned j) {
    return (40 + 50 * i) | (200 - 40 * j) << 8 | 128u << 16 | 255u << 24;
  };
  const auto texel1 = [](unsigned i, unsigned j) { return 30 * i | 10u << 8 | (70 * j) << 16 | 128u << 24; };
  for (unsigned j = 0; j < 4; ++j)
    for (unsigned i = 0; i < 4; ++i) port.set_word(TEXTURE_BASE + (j * 4 + i) * 4, texel0(i, j));
  for (unsigned j = 0; j < 2; ++j)
    for (unsigned i = 0; i < 2; ++i) port.set_word(TEXTURE1 + (j * 2 + i) * 4, texel1(i, j));
  Frame frame(port, 96, 48);
  frame.clear(0);
  StateBlock s = default_state();
  s.flags |= StateFlag::texture_units;
  struct {
    StateBlock block;
    TextureUnitsHeader header;
    TextureUnitState unit[2];
  } words{s, {2}, {}};
  words.unit[0].address = TEXTURE_BASE;
  words.unit[0].size = 2 | 2u << 8;
  words.unit[0].mode = code_of(TexEnv::modulate) << UNIT_ENV_SHIFT;  // nearest, repeat, RGBA
  words.unit[1].address = TEXTURE1;
  words.unit[1].size = 1 | 1u << 8;
  words.unit[1].mode = code_of(TexEnv::add) << UNIT_ENV_SHIFT;
  static_assert(sizeof words == state_block_bytes(StateFlag::texture_units, 2), "block and two units");
  const uint32_t state_address = frame.put(&words, sizeof words);
  frame.all({uint32_t(Opcode::state), state_address});
  // Quad [16, 48) x [8, 24): unit 0 s 0..1, t 0..1; unit 1 s 0..2, t 1..0.
  const uint32_t colour = 200 | 100u << 8 | 255u << 16 | 255u << 24;
  const VertexRecord a = vertex(16, 8, colour, 0, 0, 0), b = vertex(48, 8, colour, 0, 1, 0),
                     c = vertex(48, 24, colour, 0, 1, 1), d = vertex(16, 24, colour, 0, 0, 1);
  const auto triangle = [&](const VertexRecord& p, const VertexRecord& q, const VertexRecord& r) {
    struct {
      TriangleRecord record;
      TriangleUnitCoords unit1;
    } t{{{p, q, r}}, {}};
    const VertexRecord* v[3] = {&p, &q, &r};
    for (unsigned k = 0; k < 3; ++k) {
      t.unit1.s_over_w[k] = 2 * v[k]->s_over_w;
      t.unit1.t_over_w[k] = 1 - v[k]->t_over_w;
    }
    static_assert(sizeof t == triangle_record_bytes(StateFlag::texture_units, 2), "record and unit 1");
    frame.all({uint32_t(Opcode::triangle), frame.put(&t, sizeof t)});
  };
  triangle(a, b, c);
  triangle(a, c, d);
  frame.finish();
  const RunResult r = run(port, frame.config);
  ASSERT_EQ(r.error, RasterError::none);
  EXPECT_EQ(r.texels, 2u * 32u * 16u);  // one nearest fetch per unit and pixel
  const auto mul = [](uint32_t x, uint32_t y) { return uint32_t(std::lround(x * y / 255.0)); };
  const uint32_t f[4] = {200, 100, 255, 255};
  for (unsigned y = 8; y < 24; ++y) {
    for (unsigned x = 16; x < 48; ++x) {
      const double u = (x - 16 + 0.5) / 32, v = (y - 8 + 0.5) / 16;
      const uint32_t t0 = texel0(unsigned(u * 4), unsigned(v * 4));
      const uint32_t t1 = texel1(unsigned(u * 2 * 2) % 2, unsigned((1 - v) * 2));
      uint32_t want = 0;
      for (unsigned ch = 0; ch < 4; ++ch) {
        const uint32_t modulated = mul(f[ch], (t0 >> (8 * ch)) & 0xff);
        const uint32_t t = (t1 >> (8 * ch)) & 0xff;
        want |= (ch < 3 ? std::min<uint32_t>(modulated + t, 255) : mul(modulated, t)) << (8 * ch);
      }
      EXPECT_EQ(frame.pixel(x, y), want) << x << "," << y;
    }
  }
}

// Four units (MAX_TEXTURE_UNITS), each a 1 x 1 texture, chained: REPLACE;
// COMBINE ADD(previous, texture) with alpha REPLACE(primary alpha); BLEND
// with its env colour; COMBINE INTERPOLATE(previous, primary, constant
// alpha) with alpha MODULATE(previous, texture). GL_PREVIOUS is the unit
// before's result and GL_PRIMARY_COLOR the interpolated colour throughout;
// the pixels are worked out here from table 3.16 and 3.17's formulas.
TEST(TileRasterizer, FourTextureUnitsChainPreviousAndPrimary) {
  VectorPort port(MEMORY_SIZE);
  const uint32_t texel[4] = {0x40a01060u, 0xff103070u, 0x80ff4000u, 0x40000000u};  // A B G R
  for (unsigned u = 0; u < 4; ++u) port.set_word(TEXTURE_BASE + 0x100 * u, texel[u]);
  Frame frame(port, 64, 32);
  frame.clear(0);
  StateBlock s = default_state();
  s.flags |= StateFlag::texture_units;
  struct {
    StateBlock block;
    TextureUnitsHeader header;
    TextureUnitState unit[4];
  } words{s, {4}, {}};
  const auto stage = [](CombineFunc f, CombineSource s0, CombineOperand o0, CombineSource s1, CombineOperand o1,
                        CombineSource s2, CombineOperand o2) {
    CombineStage c;
    c.func = f;
    c.source[0] = s0, c.source[1] = s1, c.source[2] = s2;
    c.operand[0] = o0, c.operand[1] = o1, c.operand[2] = o2;
    return c.encode();
  };
  using S = CombineSource;
  using O = CombineOperand;
  const TexEnv envs[4] = {TexEnv::replace, TexEnv::combine, TexEnv::blend, TexEnv::combine};
  for (unsigned u = 0; u < 4; ++u) {
    words.unit[u].address = TEXTURE_BASE + 0x100 * u;
    words.unit[u].mode = code_of(envs[u]) << UNIT_ENV_SHIFT;
  }
  words.unit[1].combine_rgb =
      stage(CombineFunc::add, S::previous, O::src_color, S::texture, O::src_color, S::texture, O::src_color);
  words.unit[1].combine_alpha =
      stage(CombineFunc::replace, S::primary_color, O::src_alpha, S::texture, O::src_alpha, S::texture, O::src_alpha);
  const uint32_t c2 = 0x00204060u, c3 = 0x50000000u;  // env colours: unit 2's colour, unit 3's alpha 80
  words.unit[2].env_color = c2;
  words.unit[3].env_color = c3;
  words.unit[3].combine_rgb = stage(CombineFunc::interpolate, S::previous, O::src_color, S::primary_color, O::src_color,
                                    S::constant, O::src_alpha);
  words.unit[3].combine_alpha =
      stage(CombineFunc::modulate, S::previous, O::src_alpha, S::texture, O::src_alpha, S::texture, O::src_alpha);
  frame.all({uint32_t(Opcode::state), frame.put(&words, sizeof words)});
  const uint32_t primary = 0xc8326496u;  // R 150, G 100, B 50, A 200
  struct {
    TriangleRecord record;
    TriangleUnitCoords units[3];
  } t{{{vertex(4, 4, primary), vertex(60, 4, primary), vertex(4, 28, primary)}}, {}};
  frame.all({uint32_t(Opcode::triangle), frame.put(&t, sizeof t)});
  frame.finish();
  ASSERT_EQ(run(port, frame.config).error, RasterError::none);

  const auto ch = [](uint32_t c, unsigned k) { return (c >> (8 * k)) & 0xff; };
  const auto div = [](uint32_t x) { return uint32_t(std::lround(x / 255.0)); };
  uint32_t want = 0;
  for (unsigned k = 0; k < 4; ++k) {
    uint32_t c = ch(texel[0], k);                                               // REPLACE
    c = k < 3 ? std::min<uint32_t>(c + ch(texel[1], k), 255) : ch(primary, 3);  // ADD / primary alpha
    c = k < 3 ? div(c * (255 - ch(texel[2], k)) + ch(c2, k) * ch(texel[2], k))  // BLEND colour
              : div(c * ch(texel[2], 3));                                       // BLEND alpha
    c = k < 3 ? div(c * ch(c3, 3) + ch(primary, k) * (255 - ch(c3, 3))) : div(c * ch(texel[3], 3));
    want |= c << (8 * k);
  }
  unsigned drawn = 0;
  for (unsigned y = 0; y < 32; ++y)
    for (unsigned x = 0; x < 64; ++x)
      if (frame.pixel(x, y) != 0) {
        ++drawn;
        EXPECT_EQ(frame.pixel(x, y), want) << x << "," << y;
      }
  EXPECT_GT(drawn, 500u);
}

// A texture unit state with a unit count of 0 or 5 stops the run at its
// header; a unit whose size is above 256 or whose last level is beyond the
// 1 x 1 level stops it at that unit's size word when a triangle uses it.
TEST(TileRasterizer, BadTextureUnitCountSizeAndLastLevel) {
  struct Case {
    uint32_t count, size;
    bool at_header;
  };
  for (const Case k : {Case{0, 2 | 2u << 8, true}, Case{5, 2 | 2u << 8, true}, Case{2, 9 | 2u << 8, false},
                       Case{2, 2 | 3u << 8 | 4u << 16, false}}) {
    ErrorCase c;
    StateBlock s = default_state();
    s.flags |= StateFlag::texture_units;
    struct {
      StateBlock block;
      TextureUnitsHeader header;
      TextureUnitState unit[2];
    } words{s, {k.count}, {}};
    words.unit[0].address = TEXTURE_BASE;
    words.unit[0].size = 2 | 2u << 8;
    words.unit[1].address = TEXTURE_BASE;
    words.unit[1].size = k.size;
    const uint32_t state_address = c.frame.put(&words, sizeof words);
    struct {
      TriangleRecord record;
      TriangleUnitCoords unit1;
    } t{{{vertex(34, 20, ~0u, 0, 0, 0), vertex(60, 20, ~0u, 0, 1, 0), vertex(34, 30, ~0u, 0, 0, 1)}}, {}};
    const uint32_t record = c.frame.put(&t, sizeof t);
    c.frame.lists[ErrorCase::BAD_TILE].insert(
        c.frame.lists[ErrorCase::BAD_TILE].end(),
        {uint32_t(Opcode::state), state_address, uint32_t(Opcode::triangle), record});
    c.frame.finish();
    const RunResult r = c.run_and_check_tiles(ErrorCase::BAD_TILE);
    EXPECT_EQ(r.error, RasterError::bad_texture) << k.count << " " << k.size;
    EXPECT_EQ(r.error_address, k.at_header ? state_address + 48 : state_address + 48 + 4 + 28 + 4)
        << k.count << " " << k.size;
  }
}

// A 64 x 64 mipmapped texture whose levels 0 .. 6 are each one colour, and
// a state with one texture unit that samples it (REPLACE, repeat); the
// level table follows the unit record.
constexpr uint32_t LEVEL_COLORS[7] = {0xff0000ffu, 0xff00ff00u, 0xffff0000u, 0xff00ffffu,
                                      0xffff00ffu, 0xffffff00u, 0xff808080u};

uint32_t level_address(unsigned k) {
  uint32_t address = TEXTURE_BASE;
  for (unsigned i = 0; i < k; ++i) address += (64u >> i) * (64u >> i) * 4;
  return address;
}

void put_mipmaps(VectorPort& port) {
  for (unsigned k = 0; k <= 6; ++k)
    for (uint32_t i = 0; i < (64u >> k) * (64u >> k); ++i) port.set_word(level_address(k) + 4 * i, LEVEL_COLORS[k]);
}

void mipmap_state(Frame& frame, TexFilter min, TexFilter mag, tessera::TexMipmap mipmap, unsigned last_level,
                  uint32_t table_override = 0) {
  uint32_t table[6];
  for (unsigned k = 1; k <= 6; ++k) table[k - 1] = level_address(k);
  const uint32_t table_address = table_override != 0 ? table_override : frame.put(table, sizeof table);
  StateBlock s = default_state();
  s.flags |= StateFlag::texture_units;
  struct {
    StateBlock block;
    TextureUnitsHeader header;
    TextureUnitState unit;
  } words{s, {1}, {}};
  words.unit.address = TEXTURE_BASE;
  words.unit.size = 6 | 6u << 8 | last_level << 16;
  words.unit.level_table = table_address;
  words.unit.mode = code_of(min) << UNIT_MIN_FILTER_SHIFT | code_of(mag) << UNIT_MAG_FILTER_SHIFT |
                    code_of(mipmap) << UNIT_MIPMAP_SHIFT | code_of(TexEnv::replace) << UNIT_ENV_SHIFT;
  static_assert(sizeof words == state_block_bytes(StateFlag::texture_units, 1), "block, header and one unit");
  const uint32_t a = frame.put(&words, sizeof words);
  frame.all({uint32_t(Opcode::state), a});
}

// Strips 16 x 16 pixels at x = 16 k, y 8 .. 24, each with s from 0 to
// s_end[k] and t from 0 to 1/8: rho = 64 s_end / 16 texels per pixel along
// x (along y 0.5), so lambda = log2(4 s_end).
constexpr double STRIP_S_END[6] = {0.125, 0.5, 1.0, 2.0, 0.75, 16.0};  // rho 0.5, 2, 4, 8, 3, 64

void mipmap_strips(Frame& frame) {
  for (unsigned k = 0; k < 6; ++k) {
    const double x0 = 16.0 * k, x1 = x0 + 16;
    const float s1 = float(STRIP_S_END[k]);
    const VertexRecord a = vertex(x0, 8, ~0u, 0, 0, 0), b = vertex(x1, 8, ~0u, 0, s1, 0),
                       c = vertex(x1, 24, ~0u, 0, s1, 0.125f), d = vertex(x0, 24, ~0u, 0, 0, 0.125f);
    frame.triangle(a, b, c);
    frame.triangle(a, c, d);
  }
}

// GL (ES 1.1 3.8.8): NEAREST_MIPMAP_NEAREST takes level ceil(lambda + 1/2) -
// 1 for lambda > 1/2, level 0 when magnified, at most the last level.
TEST(TileRasterizer, MipmapNearestShowsTheLevelOfEachStrip) {
  for (const unsigned last : {6u, 2u}) {
    VectorPort port(MEMORY_SIZE);
    put_mipmaps(port);
    Frame frame(port, 96, 48);
    frame.clear(0);
    mipmap_state(frame, TexFilter::nearest, TexFilter::nearest, tessera::TexMipmap::nearest, last);
    mipmap_strips(frame);
    frame.finish();
    const RunResult r = run(port, frame.config);
    ASSERT_EQ(r.error, RasterError::none);
    EXPECT_EQ(r.texels, 6u * 16u * 16u);  // one fetch per pixel
    for (unsigned k = 0; k < 6; ++k) {
      const double lambda = std::log2(64 * STRIP_S_END[k] / 16);
      const double d = lambda <= 0.5 ? 0 : std::ceil(lambda + 0.5) - 1;
      const unsigned level = unsigned(std::min(d, double(last)));
      for (unsigned y = 8; y < 24; ++y)
        for (unsigned x = 16 * k; x < 16 * k + 16; ++x)
          EXPECT_EQ(frame.pixel(x, y), LEVEL_COLORS[level])
              << "strip " << k << " last " << last << " at " << x << "," << y;
    }
  }
}

// Two texture units, each with its own level of detail: unit 0 REPLACE at
// the strips' coordinates, unit 1 ADD on the same chain at coordinates four
// times as large (lambda + 2, so two levels further, at most the last).
// Each pixel is the sum of the two levels' colours, clamped per channel
// (ADD: C = min(Cf + Ct, 1), A = Af At).
TEST(TileRasterizer, EachTextureUnitTakesItsOwnMipmapLevel) {
  VectorPort port(MEMORY_SIZE);
  put_mipmaps(port);
  Frame frame(port, 96, 48);
  frame.clear(0);
  uint32_t table[6];
  for (unsigned k = 1; k <= 6; ++k) table[k - 1] = level_address(k);
  const uint32_t table_address = frame.put(table, sizeof table);
  StateBlock block = default_state();
  block.flags |= StateFlag::texture_units;
  struct {
    StateBlock block;
    TextureUnitsHeader header;
    TextureUnitState unit[2];
  } words{block, {2}, {}};
  for (unsigned u = 0; u < 2; ++u) {
    words.unit[u].address = TEXTURE_BASE;
    words.unit[u].size = 6 | 6u << 8 | 6u << 16;
    words.unit[u].level_table = table_address;
    words.unit[u].mode = code_of(tessera::TexMipmap::nearest) << UNIT_MIPMAP_SHIFT |
                         code_of(u == 0 ? TexEnv::replace : TexEnv::add) << UNIT_ENV_SHIFT;
  }
  static_assert(sizeof words == state_block_bytes(StateFlag::texture_units, 2), "block, header and two units");
  frame.all({uint32_t(Opcode::state), frame.put(&words, sizeof words)});
  for (unsigned k = 0; k < 6; ++k) {
    const double x0 = 16.0 * k, x1 = x0 + 16;
    const float s1 = float(STRIP_S_END[k]);
    const VertexRecord a = vertex(x0, 8, ~0u, 0, 0, 0), b = vertex(x1, 8, ~0u, 0, s1, 0),
                       c = vertex(x1, 24, ~0u, 0, s1, 0.125f), d = vertex(x0, 24, ~0u, 0, 0, 0.125f);
    const auto triangle = [&frame](const VertexRecord& p, const VertexRecord& q, const VertexRecord& r) {
      struct {
        TriangleRecord record;
        TriangleUnitCoords unit1;
      } t{{{p, q, r}},
          {{4 * p.s_over_w, 4 * q.s_over_w, 4 * r.s_over_w}, {4 * p.t_over_w, 4 * q.t_over_w, 4 * r.t_over_w}}};
      static_assert(sizeof t == triangle_record_bytes(StateFlag::texture_units, 2), "record and unit 1");
      frame.all({uint32_t(Opcode::triangle), frame.put(&t, sizeof t)});
    };
    triangle(a, b, c);
    triangle(a, c, d);
  }
  frame.finish();
  const RunResult r = run(port, frame.config);
  ASSERT_EQ(r.error, RasterError::none);
  EXPECT_EQ(r.texels, 2u * 6u * 16u * 16u);  // one fetch per unit and pixel
  const auto level_of = [](double lambda) {
    const double d = lambda <= 0.5 ? 0 : std::ceil(lambda + 0.5) - 1;
    return unsigned(std::min(d, 6.0));
  };
  for (unsigned k = 0; k < 6; ++k) {
    const double lambda = std::log2(64 * STRIP_S_END[k] / 16);
    const uint32_t c0 = LEVEL_COLORS[level_of(lambda)], c1 = LEVEL_COLORS[level_of(lambda + 2)];
    uint32_t want = 0xff000000u;
    for (unsigned ch = 0; ch < 24; ch += 8) want |= std::min(((c0 >> ch) & 0xff) + ((c1 >> ch) & 0xff), 255u) << ch;
    for (unsigned y = 8; y < 24; ++y)
      for (unsigned x = 16 * k; x < 16 * k + 16; ++x)
        EXPECT_EQ(frame.pixel(x, y), want) << "strip " << k << " at " << x << "," << y;
  }
}

// LINEAR_MIPMAP_LINEAR: levels floor(lambda) and the next, weighted by
// frac(lambda) in 1/256; a one-colour level filters to its colour.
TEST(TileRasterizer, MipmapLinearBlendsTwoLevels) {
  VectorPort port(MEMORY_SIZE);
  put_mipmaps(port);
  Frame frame(port, 96, 48);
  frame.clear(0);
  mipmap_state(frame, TexFilter::linear, TexFilter::linear, tessera::TexMipmap::linear, 6);
  mipmap_strips(frame);
  frame.finish();
  const RunResult r = run(port, frame.config);
  ASSERT_EQ(r.error, RasterError::none);
  // Strips with integer lambda (or magnified, or at the last level) read
  // four texels of one level; the strip with rho 3 eight, of two.
  EXPECT_EQ(r.texels, 5u * 16u * 16u * 4u + 16u * 16u * 8u);
  for (unsigned k = 0; k < 6; ++k) {
    const double lambda = std::max(std::log2(64 * STRIP_S_END[k] / 16), 0.0);
    const unsigned d1 = unsigned(std::min(std::floor(lambda), 6.0));
    const unsigned w = d1 >= 6 ? 0 : unsigned(std::lround((lambda - d1) * 256));
    const uint32_t c1 = LEVEL_COLORS[d1], c2 = LEVEL_COLORS[std::min(d1 + 1, 6u)];
    uint32_t want = 0;
    for (unsigned ch = 0; ch < 32; ch += 8)
      want |= ((((c1 >> ch) & 0xff) * (256 - w) + ((c2 >> ch) & 0xff) * w + 128) >> 8) << ch;
    if (k == 4) {
      EXPECT_EQ(w, 150u);  // log2 3 = 1.585
    }
    for (unsigned y = 8; y < 24; ++y)
      for (unsigned x = 16 * k; x < 16 * k + 16; ++x)
        EXPECT_EQ(frame.pixel(x, y), want) << "strip " << k << " at " << x << "," << y;
  }
}

// A floor in perspective: the level grows with the distance. Each pixel's
// level against GL's rule from rho = max(|du/dx|, |dv/dx|, |du/dy|,
// |dv/dy|) at the pixel's centre, worked out in doubles (pixels within 1/64
// of a level boundary are not checked: the hardware's coordinates and
// lambda are fixed point).
TEST(TileRasterizer, MipmapLevelsFollowPerspective) {
  VectorPort port(MEMORY_SIZE);
  put_mipmaps(port);
  Frame frame(port, 96, 48);
  frame.clear(0);
  mipmap_state(frame, TexFilter::nearest, TexFilter::nearest, tessera::TexMipmap::nearest, 6);
  // A trapezoid: near edge y = 0 (w 1), far edge y = 48 (w 8); s 0 .. 4, t 0 .. 8.
  const float near_w = 1, far_w = 8;
  const VertexRecord a = vertex(0, 0, ~0u, 0, 0, 0, near_w), b = vertex(96, 0, ~0u, 0, 4, 0, near_w),
                     c = vertex(96, 48, ~0u, 0, 4, 8, far_w), d = vertex(0, 48, ~0u, 0, 0, 8, far_w);
  frame.triangle(a, b, c);
  frame.triangle(a, c, d);
  frame.finish();
  const RunResult r = run(port, frame.config);
  ASSERT_EQ(r.error, RasterError::none);
  // s/w, t/w and 1/w are affine over each triangle (abc below the diagonal
  // a-c, acd above it): barycentric interpolation of the vertices' values,
  // the same triangle's plane at the pixel and at its neighbours.
  struct V {
    double x, y, s, t, w;
  };
  const V va{0, 0, 0, 0, near_w}, vb{96, 0, 4, 0, near_w}, vc{96, 48, 4, 8, far_w}, vd{0, 48, 0, 8, far_w};
  const auto at = [](const V& p, const V& q, const V& o, double x, double y, double& s, double& t) {
    const double area = (q.x - p.x) * (o.y - p.y) - (o.x - p.x) * (q.y - p.y);
    const double l1 = ((x - p.x) * (o.y - p.y) - (o.x - p.x) * (y - p.y)) / area;
    const double l2 = ((q.x - p.x) * (y - p.y) - (x - p.x) * (q.y - p.y)) / area, l0 = 1 - l1 - l2;
    const double inv_w = l0 / p.w + l1 / q.w + l2 / o.w;
    s = (l0 * p.s / p.w + l1 * q.s / q.w + l2 * o.s / o.w) / inv_w;
    t = (l0 * p.t / p.w + l1 * q.t / q.w + l2 * o.t / o.w) / inv_w;
  };
  unsigned checked = 0, levels_seen = 0;
  bool seen[7] = {};
  for (unsigned y = 0; y < 48; ++y) {
    for (unsigned x = 0; x < 96; ++x) {
      const double diagonal = (y + 0.5) - (x + 0.5) / 2;  // below a-c: negative
      if (std::fabs(diagonal) < 1.5) continue;
      const bool lower = diagonal < 0;
      const V& p = va;
      const V& q = lower ? vb : vc;
      const V& rr = lower ? vc : vd;
      // GL's partial derivatives at the pixel's centre, by central
      // differences over a small step.
      const double h = 1.0 / 1024;
      double s0, t0, s1, t1, sx, tx, sy, ty;
      at(p, q, rr, x + 0.5 - h, y + 0.5, s0, t0);
      at(p, q, rr, x + 0.5 + h, y + 0.5, s1, t1);
      const double dsdx = (s1 - s0) / (2 * h), dtdx = (t1 - t0) / (2 * h);
      at(p, q, rr, x + 0.5, y + 0.5 - h, s0, t0);
      at(p, q, rr, x + 0.5, y + 0.5 + h, sx, tx);
      sy = (sx - s0) / (2 * h);
      ty = (tx - t0) / (2 * h);
      const double rho = 64 * std::max({std::fabs(dsdx), std::fabs(dtdx), std::fabs(sy), std::fabs(ty)});
      const double lambda = std::log2(rho);
      const double frac_to_boundary = std::fabs(lambda - 0.5 - std::round(lambda - 0.5));
      if (frac_to_boundary < 1.0 / 64) continue;
      const double nearest = lambda <= 0.5 ? 0 : std::ceil(lambda + 0.5) - 1;
      const unsigned level = unsigned(std::min(nearest, 6.0));
      EXPECT_EQ(frame.pixel(x, y), LEVEL_COLORS[level]) << x << "," << y << " lambda " << lambda;
      if (!seen[level]) ++levels_seen;
      seen[level] = true;
      ++checked;
    }
  }
  EXPECT_GT(checked, 96u * 48u * 8 / 10);
  EXPECT_GE(levels_seen, 3u);
}

// A level table outside memory is a bus error at the state (the decoder
// reads it with the unit records); a level's texels outside memory are
// bad_texture at the texel.
TEST(TileRasterizer, MipmapLevelTableAndLevelTexelsOutsideMemory) {
  {
    VectorPort port(MEMORY_SIZE);
    put_mipmaps(port);
    Frame frame(port, 96, 48);
    mipmap_state(frame, TexFilter::nearest, TexFilter::nearest, tessera::TexMipmap::nearest, 6, MEMORY_SIZE - 8);
    mipmap_strips(frame);
    frame.finish();
    const RunResult r = run(port, frame.config);
    EXPECT_EQ(r.error, RasterError::bus_error);
    EXPECT_EQ(r.error_address, MEMORY_SIZE - 8);
  }
  {
    VectorPort port(MEMORY_SIZE);
    put_mipmaps(port);
    Frame frame(port, 96, 48);
    uint32_t table[6];
    for (unsigned k = 1; k <= 6; ++k) table[k - 1] = level_address(k);
    table[2] = MEMORY_SIZE + 0x100;  // level 3
    const uint32_t table_address = frame.put(table, sizeof table);
    mipmap_state(frame, TexFilter::nearest, TexFilter::nearest, tessera::TexMipmap::nearest, 6, table_address);
    mipmap_strips(frame);
    frame.finish();
    const RunResult r = run(port, frame.config);
    EXPECT_EQ(r.error, RasterError::bad_texture);
    // A texel of level 3 (8 x 8), the first strip 3 fetches.
    EXPECT_GE(r.error_address, MEMORY_SIZE + 0x100);
    EXPECT_LT(r.error_address, MEMORY_SIZE + 0x100 + 8 * 8 * 4);
  }
}

// A state enabling more units than the hardware has (RunConfig::
// texture_units, the TEXTURE_UNITS register) stops the run at its header.
TEST(TileRasterizer, MoreUnitsThanTheHardwareHasIsBadTexture) {
  ErrorCase c;
  c.frame.config.texture_units = 1;
  StateBlock s = default_state();
  s.flags |= StateFlag::texture_units;
  struct {
    StateBlock block;
    TextureUnitsHeader header;
    TextureUnitState unit[2];
  } words{s, {2}, {}};
  for (TextureUnitState& unit : words.unit) {
    unit.address = TEXTURE_BASE;
    unit.size = 2 | 2u << 8;
  }
  const uint32_t state_address = c.frame.put(&words, sizeof words);
  c.frame.lists[ErrorCase::BAD_TILE].insert(c.frame.lists[ErrorCase::BAD_TILE].end(),
                                            {uint32_t(Opcode::state), state_address});
  c.frame.finish();
  const RunResult r = c.run_and_check_tiles(ErrorCase::BAD_TILE);
  EXPECT_EQ(r.error, RasterError::bad_texture);
  EXPECT_EQ(r.error_address, state_address + 48);
}

TEST(TileRasterizer, ZeroAreaTriangleIsSkipped) {
  VectorPort port(MEMORY_SIZE);
  Frame frame(port, 96, 48);
  frame.clear(0xff000000);
  frame.triangle(vertex(2.5, 2.5), vertex(12.5, 7.5), vertex(22.5, 12.5));  // collinear, inside tile (0, 2)
  frame.finish();
  const RunResult r = run(port, frame.config);
  EXPECT_EQ(r.error, RasterError::none);
  EXPECT_EQ(r.triangles, 0u);
  EXPECT_EQ(r.triangles_skipped, 1u);
  EXPECT_EQ(r.fragments, 0u);
  for (unsigned y = 0; y < 48; ++y)
    for (unsigned x = 0; x < 96; ++x) ASSERT_EQ(frame.pixel(x, y), 0xff000000u);
}

// EASA: alpha = coverage from the normalised edge functions. Method 1's
// fixed-point table is far off for a long edge (|dx| + |dy| of hundreds of
// pixels), Method 3 stays close to the exact reciprocal.
TEST(TileRasterizer, ReciprocalMethodChangesAntialiasedEdges) {
  const VertexRecord tri[3] = {vertex(1.3, 2.1), vertex(94.7, 17.9), vertex(6.2, 46.4)};
  std::vector<int> alpha[2];
  for (int m = 0; m < 2; ++m) {
    VectorPort port(MEMORY_SIZE);
    Frame frame(port, 96, 48);
    frame.config.recip_method = m == 0 ? RecipMethod::method1 : RecipMethod::method3;
    frame.clear(0);
    StateBlock s = default_state();
    s.flags |= polygon_smooth;
    frame.state(s);
    frame.triangle(tri[0], tri[1], tri[2]);
    frame.finish();
    ASSERT_EQ(run(port, frame.config).error, RasterError::none);
    for (unsigned y = 0; y < 48; ++y)
      for (unsigned x = 0; x < 96; ++x) alpha[m].push_back(int(frame.pixel(x, y) >> 24));
  }
  // Exact L1-normalised coverage for comparison.
  int error[2] = {0, 0};
  unsigned partial = 0;
  for (unsigned y = 0; y < 48; ++y) {
    for (unsigned x = 0; x < 96; ++x) {
      double c = 1;
      for (int k = 0; k < 3; ++k) {
        const int a = k, b = (k + 2) % 3;  // clockwise: 0 -> 2 -> 1
        const double x0 = (tri[a].xy & 0xffff) / 16.0, y0 = (tri[a].xy >> 16) / 16.0;
        const double x1 = (tri[b].xy & 0xffff) / 16.0, y1 = (tri[b].xy >> 16) / 16.0;
        const double dx = x1 - x0, dy = y1 - y0;
        const double e = (x + 0.5 - x0) * dy - (y + 0.5 - y0) * dx;
        c = std::min(c, std::clamp(0.5 + e / (std::fabs(dx) + std::fabs(dy)), 0.0, 1.0));
      }
      const int exact = int(std::lround(c * 255));
      if (exact > 0 && exact < 255) ++partial;
      for (int m = 0; m < 2; ++m) error[m] = std::max(error[m], std::abs(alpha[m][y * 96 + x] - exact));
    }
  }
  EXPECT_GT(partial, 50u);
  EXPECT_NE(alpha[0], alpha[1]);
  EXPECT_LE(error[1], 6);
  EXPECT_GT(error[0], 3 * error[1]);
}

TEST(TileRasterizer, EmptyTilesAreLeftAloneAndCyclesAddUp) {
  VectorPort port(MEMORY_SIZE);
  for (uint32_t a = COLOR_BASE; a < COLOR_BASE + 96 * 48 * 4; a += 4) port.set_word(a, 0x77);
  Frame frame(port, 96, 48);
  frame.clear(0xff000000);
  frame.triangle(vertex(3, 3), vertex(40, 5), vertex(10, 30));
  frame.lists[8].clear();  // bottom-right tile: word_count 0
  frame.finish();
  CycleCosts costs;
  costs.tile_pixel_clear = 1;
  costs.tile_write_word = 1;
  TileRasterizer rasterizer(port, costs);
  const RunResult r = rasterizer.run(frame.config);
  ASSERT_EQ(r.error, RasterError::none);
  EXPECT_EQ(r.tiles, 8u);
  EXPECT_EQ(r.commands, 16u);
  EXPECT_EQ(frame.pixel(90, 2), 0x77u);
  EXPECT_EQ(frame.pixel(90, 40), 0xff000000u);
  EXPECT_EQ(r.setup_cycles + r.tile_cycles + r.fragment_cycles + r.texel_cycles, port.total_cycles);
  // 8 tiles of 32 x 16: start, commands, cleared pixels, written words.
  EXPECT_EQ(r.tile_cycles, 8 * (4 + 2 + 512 + 512 + 512));
  EXPECT_EQ(r.bytes_written, 8u * 512 * 8);
}

}  // namespace

// Garbage everywhere: random tile table, lists, records and state blocks.
// Whatever the outcome, the run ends without crashing (run under ASan/UBSan
// in the sanitizer build).
TEST(TileRasterizer, RandomInputNeverCrashes) {
  std::mt19937 random(12345);
  const auto next = [&random] { return uint32_t(random()); };
  uint64_t commands = 0, errors = 0;
  for (int round = 0; round < 40; ++round) {
    VectorPort port(MEMORY_SIZE);
    for (uint32_t a = DATA_BASE; a < DATA_BASE + 0x4000; a += 4) {
      // Mostly valid opcodes and pointers into the data area, with noise.
      const uint32_t r = next();
      uint32_t v = next();
      if (r % 16 < 8)
        v = (1 + r % 3) | (r & 0x700);
      else if (r % 16 < 15)
        v = DATA_BASE + (next() % 0x4000 & ~3u);
      port.set_word(a, v);
    }
    Frame frame(port, 96, 48);
    frame.config.color_format = round % 2 == 0 ? tessera::PixelFormat::rgba8888 : tessera::PixelFormat::rgb565;
    frame.config.recip_method = static_cast<RecipMethod>(round % 3);
    for (size_t t = 0; t < frame.lists.size(); ++t) {
      port.set_word(TILE_TABLE + 8 * uint32_t(t), DATA_BASE + (next() % 0x3000 & ~3u));
      port.set_word(TILE_TABLE + 8 * uint32_t(t) + 4, next() % 64);
    }
    TileRasterizer rasterizer(port);
    const RunResult r = rasterizer.run(frame.config);
    EXPECT_EQ(r.setup_cycles + r.tile_cycles + r.fragment_cycles + r.texel_cycles, port.total_cycles);
    commands += r.commands;
    errors += r.error != RasterError::none;
  }
  EXPECT_GT(commands, 20u);  // most runs stop at an early garbage word
  EXPECT_GT(errors, 0u);
}
