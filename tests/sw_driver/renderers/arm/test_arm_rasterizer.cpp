// Unit tests of the arm renderer's functional core, run natively on a
// NativeMemory. Expected values come from GL's definitions (edge functions in
// doubles, barycentric interpolation, the texture environment and blending
// equations), not from the implementation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "renderers/arm/arm_rasterizer.h"
#include "renderers/arm/native_memory.h"
#include "renderers/common/fixed_math.h"

namespace tessera::arm {
namespace {

constexpr unsigned GUARD = 256;  // untouched bytes around every buffer
constexpr uint8_t GUARD_BYTE = 0xa5;

struct Rgba {
  int r, g, b, a;
};

// A frame of width x height with colour, depth and stencil buffers and room
// for textures, each surrounded by a guard band.
class Frame {
 public:
  Frame(unsigned width, unsigned height, PixelFormat format)
      : width(width),
        height(height),
        format(format),
        color_address(0x1000 + GUARD),
        depth_address(color_address + width * height * bytes_per_pixel(format) + GUARD + 2),  // odd gap
        stencil_address(depth_address + width * height * 2 + GUARD),
        texture_address(stencil_address + width * height + GUARD),
        memory(texture_address + TEXTURE_BYTES + GUARD - 0x1000, 0x1000) {
    std::fill(memory.at(memory.base(), memory.size()), memory.at(memory.base(), memory.size()) + memory.size(),
              GUARD_BYTE);
    FrameBuffers fb;
    fb.width = width;
    fb.height = height;
    fb.color_format = format;
    fb.color_address = color_address;
    fb.depth_address = depth_address;
    fb.stencil_address = stencil_address;
    rasterizer = std::make_unique<ArmRasterizer>(memory, fb);
    gl::ClearRequest clear;
    clear.color = clear.depth = clear.stencil = true;
    rasterizer->clear(clear);
  }

  // Colour at GL pixel (x, y), decoded here from the documented formats.
  Rgba color(int x, int y) {
    const unsigned bpp = format == PixelFormat::rgb565 ? 2 : 4;
    const uint8_t* p = memory.at(color_address + ((height - 1 - y) * width + x) * bpp, bpp);
    if (format == PixelFormat::rgba8888) return {p[0], p[1], p[2], p[3]};
    const int v = p[0] | p[1] << 8;
    const int r5 = v >> 11, g6 = (v >> 5) & 63, b5 = v & 31;
    return {r5 * 255 / 31, g6 * 255 / 63, b5 * 255 / 31, 255};
  }
  uint16_t packed565(int x, int y) {
    const uint8_t* p = memory.at(color_address + ((height - 1 - y) * width + x) * 2, 2);
    return uint16_t(p[0] | p[1] << 8);
  }
  uint16_t depth(int x, int y) {
    const uint8_t* p = memory.at(depth_address + ((height - 1 - y) * width + x) * 2, 2);
    return uint16_t(p[0] | p[1] << 8);
  }
  uint8_t stencil(int x, int y) { return *memory.at(stencil_address + (height - 1 - y) * width + x); }

  // Writes a texture (RGBA8, row t = 0 first) `offset` bytes into the
  // texture area and returns its descriptor.
  gl::Texture texture(unsigned w, unsigned h, const std::vector<Rgba>& texels, uint32_t offset = 0) {
    uint8_t* p = memory.at(texture_address + offset, w * h * 4);
    for (unsigned i = 0; i < w * h; ++i) {
      p[4 * i] = uint8_t(texels[i].r);
      p[4 * i + 1] = uint8_t(texels[i].g);
      p[4 * i + 2] = uint8_t(texels[i].b);
      p[4 * i + 3] = uint8_t(texels[i].a);
    }
    gl::Texture tex;
    tex.address = texture_address + offset;
    tex.width = w;
    tex.height = h;
    tex.min_filter = tex.mag_filter = gl::TexFilter::nearest;
    return tex;
  }

  // Every byte outside the buffers and the texture still holds GUARD_BYTE.
  bool guards_intact() {
    const uint32_t bpp = format == PixelFormat::rgb565 ? 2 : 4;
    const std::array<std::pair<uint32_t, uint32_t>, 4> used = {{{color_address, width * height * bpp},
                                                                {depth_address, width * height * 2},
                                                                {stencil_address, width * height},
                                                                {texture_address, TEXTURE_BYTES}}};
    for (uint32_t a = memory.base(); a < memory.base() + memory.size(); ++a) {
      bool inside = false;
      for (const auto& [start, bytes] : used) inside |= a >= start && a < start + bytes;
      if (!inside && *memory.at(a) != GUARD_BYTE) return false;
    }
    return true;
  }

  void draw(const gl::RasterState& state, const std::vector<gl::Triangle>& triangles) {
    rasterizer->draw(state, triangles.data(), triangles.size());
  }

  static constexpr uint32_t TEXTURE_BYTES = 64 * 64 * 4;
  const unsigned width, height;
  const PixelFormat format;
  const uint32_t color_address, depth_address, stencil_address, texture_address;
  NativeMemory memory;
  std::unique_ptr<ArmRasterizer> rasterizer;
};

gl::ScreenVertex vertex(double x, double y, Rgba c = {255, 255, 255, 255}, double z = 0.5, float s = 0, float t = 0,
                        float inv_w = 1) {
  gl::ScreenVertex v{};
  v.x = int32_t(std::lround(x * 16));
  v.y = int32_t(std::lround(y * 16));
  v.z = uint32_t(std::lround(z * 0xffffff));
  v.r = uint8_t(c.r);
  v.g = uint8_t(c.g);
  v.b = uint8_t(c.b);
  v.a = uint8_t(c.a);
  v.tex[0] = {s, t};
  v.inv_w = inv_w;
  return v;
}

gl::Triangle triangle(gl::ScreenVertex a, gl::ScreenVertex b, gl::ScreenVertex c) {
  return gl::Triangle{{a, b, c}};
}

// The reference: pixel centre (xc, yc) is covered if every edge function of
// the counter-clockwise triangle is positive, or zero on a left edge (going
// down) or a top edge (horizontal, going left).
bool covers(const gl::Triangle& tri, double xc, double yc) {
  double x[3], y[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = tri.v[k].x / 16.0;
    y[k] = tri.v[k].y / 16.0;
  }
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  if (area == 0) return false;
  if (area < 0) {
    std::swap(x[1], x[2]);
    std::swap(y[1], y[2]);
  }
  for (int k = 0; k < 3; ++k) {
    const double ax = x[k], ay = y[k], dx = x[(k + 1) % 3] - ax, dy = y[(k + 1) % 3] - ay;
    const double e = dx * (yc - ay) - dy * (xc - ax);
    if (e > 0) continue;
    if (e == 0 && (dy < 0 || (dy == 0 && dx < 0))) continue;
    return false;
  }
  return true;
}

// Barycentric weights of (xc, yc).
std::array<double, 3> barycentric(const gl::Triangle& tri, double xc, double yc) {
  double x[3], y[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = tri.v[k].x / 16.0;
    y[k] = tri.v[k].y / 16.0;
  }
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  const double w1 = ((xc - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (yc - y[0])) / area;
  const double w2 = ((x[1] - x[0]) * (yc - y[0]) - (xc - x[0]) * (y[1] - y[0])) / area;
  return {1 - w1 - w2, w1, w2};
}

gl::RasterState additive_state() {
  gl::RasterState state;
  state.flat_shading = true;
  state.blend = true;
  state.blend_src = gl::BlendFactor::one;
  state.blend_dst = gl::BlendFactor::one;
  return state;
}

// --- Fill rule ---------------------------------------------------------------

void check_fan(double cx, double cy, const std::vector<std::pair<double, double>>& rim) {
  Frame f(64, 48, PixelFormat::rgba8888);
  std::vector<gl::Triangle> fan;
  for (size_t k = 0; k < rim.size(); ++k) {
    const auto [x0, y0] = rim[k];
    const auto [x1, y1] = rim[(k + 1) % rim.size()];
    const Rgba one{1, 0, 0, 0};
    if (k % 2 == 0)
      fan.push_back(triangle(vertex(cx, cy, one), vertex(x0, y0, one), vertex(x1, y1, one)));
    else
      fan.push_back(triangle(vertex(x1, y1, one), vertex(x0, y0, one), vertex(cx, cy, one)));
  }
  f.draw(additive_state(), fan);
  int inside = 0;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      int expected = 0;
      for (const gl::Triangle& t : fan) expected += covers(t, x + 0.5, y + 0.5);
      ASSERT_LE(expected, 1) << "reference overlap at " << x << "," << y;
      // Strictly inside the (convex) rim polygon: covered exactly once.
      bool strictly_inside = true, strictly_outside = false;
      for (size_t k = 0; k < rim.size(); ++k) {
        const auto [x0, y0] = rim[k];
        const auto [x1, y1] = rim[(k + 1) % rim.size()];
        const double e = (x1 - x0) * (y + 0.5 - y0) - (y1 - y0) * (x + 0.5 - x0);  // rim is counter-clockwise
        strictly_inside &= e > 0;
        strictly_outside |= e < 0;
      }
      if (strictly_inside) {
        EXPECT_EQ(expected, 1);
      }
      if (strictly_outside) {
        EXPECT_EQ(expected, 0);
      }
      EXPECT_EQ(f.color(x, y).r, expected) << "pixel " << x << "," << y;
      inside += f.color(x, y).r;
    }
  }
  EXPECT_GT(inside, 100);
  EXPECT_TRUE(f.guards_intact());
}

TEST(ArmRasterizerFillRule, FanAroundPixelCentreWithEdgesThroughCentres) {
  // Horizontal, vertical and diagonal edges through pixel centres, the centre
  // of the fan on a pixel centre.
  const double cx = 30.5, cy = 22.5;
  std::vector<std::pair<double, double>> rim = {{cx + 12, cy}, {cx + 9, cy + 9}, {cx, cy + 12}, {cx - 9, cy + 9},
                                                {cx - 12, cy}, {cx - 9, cy - 9}, {cx, cy - 12}, {cx + 9, cy - 9}};
  check_fan(cx, cy, rim);
}

TEST(ArmRasterizerFillRule, FanAroundSubpixelCentre) {
  const double cx = 31.3125, cy = 20.75;
  std::vector<std::pair<double, double>> rim;
  for (int k = 0; k < 13; ++k) {
    const double angle = 2 * 3.14159265358979 * k / 13;
    rim.emplace_back(std::round((cx + 17 * std::cos(angle)) * 16) / 16,
                     std::round((cy + 15 * std::sin(angle)) * 16) / 16);
  }
  check_fan(cx, cy, rim);
}

void check_grid(bool jitter) {
  Frame f(64, 48, PixelFormat::rgba8888);
  const int nx = 6, ny = 5;
  const double x0 = 4.5, dx = 7.5, y0 = 3.5, dy = 6.5;
  std::mt19937 random(12345);
  std::uniform_int_distribution<int> offset(-24, 24);  // +-1.5 pixels in 1/16
  std::vector<std::vector<std::pair<double, double>>> p(nx + 1, std::vector<std::pair<double, double>>(ny + 1));
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) {
      double x = x0 + i * dx, y = y0 + j * dy;
      if (jitter && i > 0 && i < nx) x += offset(random) / 16.0;
      if (jitter && j > 0 && j < ny) y += offset(random) / 16.0;
      p[i][j] = {x, y};
    }
  }
  std::vector<gl::Triangle> grid;
  const Rgba one{0, 1, 0, 0};
  auto v = [&](int i, int j) { return vertex(p[i][j].first, p[i][j].second, one); };
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      if ((i + j) % 2 == 0) {
        grid.push_back(triangle(v(i, j), v(i + 1, j), v(i + 1, j + 1)));
        grid.push_back(triangle(v(i, j), v(i, j + 1), v(i + 1, j + 1)));
      } else {
        grid.push_back(triangle(v(i + 1, j), v(i, j + 1), v(i, j)));
        grid.push_back(triangle(v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)));
      }
    }
  }
  f.draw(additive_state(), grid);
  const double x1 = x0 + nx * dx, y1 = y0 + ny * dy;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const double xc = x + 0.5, yc = y + 0.5;
      // The union is the rectangle; its left edge is drawn, its top edge
      // (y1, not on a centre here) would be, its right and bottom are not.
      const int expected = (xc >= x0 && xc < x1 && yc > y0 && yc <= y1) ? 1 : 0;
      EXPECT_EQ(f.color(x, y).g, expected) << "pixel " << x << "," << y;
    }
  }
  EXPECT_TRUE(f.guards_intact());
}

TEST(ArmRasterizerFillRule, GridOfQuadsOnPixelCentres) {
  check_grid(false);
}
TEST(ArmRasterizerFillRule, JitteredGridOfQuads) {
  check_grid(true);
}

TEST(ArmRasterizerFillRule, CoverageMatchesEdgeFunctionReference) {
  Frame f(64, 48, PixelFormat::rgba8888);
  std::mt19937 random(4711);
  std::uniform_int_distribution<int> xs(-8 * 16, 72 * 16), ys(-8 * 16, 56 * 16), snap(0, 2);
  auto coordinate = [&](std::uniform_int_distribution<int>& d) {
    double c = d(random) / 16.0;
    switch (snap(random)) {
      case 0: return std::floor(c) + 0.5;  // on a pixel centre
      case 1: return std::floor(c);        // on a pixel corner
      default: return c;
    }
  };
  gl::RasterState state;
  state.flat_shading = true;
  for (int n = 0; n < 300; ++n) {
    gl::ClearRequest clear;
    clear.color = true;
    f.rasterizer->clear(clear);
    const gl::Triangle t = triangle(vertex(coordinate(xs), coordinate(ys)), vertex(coordinate(xs), coordinate(ys)),
                                    vertex(coordinate(xs), coordinate(ys), Rgba{255, 255, 255, 255}));
    f.draw(state, {t});
    int mismatches = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) mismatches += (f.color(x, y).r == 255) != covers(t, x + 0.5, y + 0.5);
    ASSERT_EQ(mismatches, 0) << "triangle " << n;
  }
  EXPECT_TRUE(f.guards_intact());
}

// --- Depth ---------------------------------------------------------------------

TEST(ArmRasterizerDepth, NearerHidesFartherInEitherOrder) {
  const gl::Triangle near_red = triangle(vertex(5, 5, {255, 0, 0, 255}, 0.2), vertex(50, 10, {255, 0, 0, 255}, 0.4),
                                         vertex(20, 40, {255, 0, 0, 255}, 0.3));
  const gl::Triangle far_green = triangle(vertex(10, 30, {0, 255, 0, 255}, 0.8), vertex(60, 2, {0, 255, 0, 255}, 0.5),
                                          vertex(58, 44, {0, 255, 0, 255}, 0.6));
  gl::RasterState state;
  state.depth_test = true;
  state.depth_func = gl::CompareFunc::less;
  for (bool near_first : {true, false}) {
    Frame f(64, 48, PixelFormat::rgba8888);
    if (near_first) {
      f.draw(state, {near_red, far_green});
    } else {
      f.draw(state, {far_green, near_red});
    }
    for (int y = 0; y < 48; ++y) {
      for (int x = 0; x < 64; ++x) {
        const bool in_near = covers(near_red, x + 0.5, y + 0.5), in_far = covers(far_green, x + 0.5, y + 0.5);
        const Rgba c = f.color(x, y);
        if (in_near) {
          EXPECT_EQ(c.r, 255) << x << "," << y;
        } else if (in_far) {
          EXPECT_EQ(c.g, 255) << x << "," << y;
        } else {
          EXPECT_EQ(c.r + c.g + c.b, 0);
        }
      }
    }
  }
}

TEST(ArmRasterizerDepth, AllCompareFunctionsAgainstClearedDepth) {
  const uint32_t cleared = 0x800000;  // 16 bits: 0x8000
  // Top 16 bits of 0.24: 0x8000ff and 0x800000 compare equal.
  for (uint32_t z24 : {0x7fff00u, 0x800000u, 0x8000ffu, 0x810000u}) {
    for (int func = 0; func < 8; ++func) {
      Frame f(16, 12, PixelFormat::rgba8888);
      gl::ClearRequest clear;
      clear.depth = true;
      clear.depth_value = cleared;
      f.rasterizer->clear(clear);
      gl::RasterState state;
      state.depth_test = true;
      state.depth_func = gl::CompareFunc(func);
      gl::Triangle t = triangle(vertex(-20, -20), vertex(60, -20), vertex(-20, 60));
      for (auto& v : t.v) v.z = z24;
      f.draw(state, {t});
      const uint32_t in = z24 >> 8, stored = cleared >> 8;
      const bool pass[8] = {false, in<stored, in == stored, in <= stored, in> stored, in != stored, in >= stored, true};
      for (int y = 0; y < 12; ++y) {
        for (int x = 0; x < 16; ++x) {
          EXPECT_EQ(f.color(x, y).r == 255, pass[func]) << "func " << func << " z " << z24;
          EXPECT_EQ(f.depth(x, y), pass[func] ? in : stored);
        }
      }
    }
  }
}

TEST(ArmRasterizerDepth, EqualRedrawsTheSameTriangleAndDepthMaskHolds) {
  Frame f(64, 48, PixelFormat::rgba8888);
  const Rgba white{255, 255, 255, 255};
  const gl::Triangle t = triangle(vertex(3, 4, white, 0.1), vertex(60, 9, white, 0.9), vertex(30, 45, white, 0.5));
  gl::RasterState state;
  state.flat_shading = true;
  state.depth_test = true;
  f.draw(state, {t});
  std::vector<uint16_t> before;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) before.push_back(f.depth(x, y));
  gl::Triangle blue = t;
  for (auto& v : blue.v) v.r = v.g = 0;
  state.depth_func = gl::CompareFunc::equal;
  state.depth_write = false;
  f.draw(state, {blue});
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool in = covers(t, x + 0.5, y + 0.5);
      EXPECT_EQ(f.color(x, y).r, 0);  // white where drawn first, blue where redrawn
      EXPECT_EQ(f.color(x, y).b, in ? 255 : 0);
      EXPECT_EQ(f.depth(x, y), before[size_t(y * 64 + x)]);
      if (in) {
        const auto w = barycentric(t, x + 0.5, y + 0.5);
        const double z24 = w[0] * t.v[0].z + w[1] * t.v[1].z + w[2] * t.v[2].z;
        EXPECT_NEAR(f.depth(x, y), z24 / 256.0, 1.0);
      }
    }
  }
}

// --- Shading -------------------------------------------------------------------

TEST(ArmRasterizerShading, GouraudMatchesBarycentricInterpolation) {
  Frame f(64, 48, PixelFormat::rgba8888);
  const Rgba ca{0, 10, 250, 255}, cb{200, 100, 0, 128}, cc{50, 255, 60, 0};
  const gl::Triangle t = triangle(vertex(10.5, 40.5, ca), vertex(50.5, 40.5, cb), vertex(30.5, 5.5, cc));
  f.draw(gl::RasterState{}, {t});
  // Vertex A is on the top edge and a left edge: drawn with A's colour.
  const Rgba a = f.color(10, 40);
  EXPECT_NEAR(a.r, ca.r, 1);
  EXPECT_NEAR(a.g, ca.g, 1);
  EXPECT_NEAR(a.b, ca.b, 1);
  EXPECT_NEAR(a.a, ca.a, 1);
  // Along the top edge A -> B red rises linearly by 5 per pixel.
  for (int x = 10; x < 50; ++x) EXPECT_NEAR(f.color(x, 40).r, (x - 10) * 5.0, 1.0) << x;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (!covers(t, x + 0.5, y + 0.5)) continue;
      const auto w = barycentric(t, x + 0.5, y + 0.5);
      const Rgba c = f.color(x, y);
      EXPECT_NEAR(c.r, w[0] * ca.r + w[1] * cb.r + w[2] * cc.r, 1.0);
      EXPECT_NEAR(c.g, w[0] * ca.g + w[1] * cb.g + w[2] * cc.g, 1.0);
      EXPECT_NEAR(c.b, w[0] * ca.b + w[1] * cb.b + w[2] * cc.b, 1.0);
      EXPECT_NEAR(c.a, w[0] * ca.a + w[1] * cb.a + w[2] * cc.a, 1.0);
    }
  }
}

TEST(ArmRasterizerShading, FlatUsesTheProvokingVertex) {
  Frame f(64, 48, PixelFormat::rgba8888);
  gl::RasterState state;
  state.flat_shading = true;
  const gl::Triangle t =
      triangle(vertex(2, 2, {255, 0, 0, 255}), vertex(60, 5, {0, 255, 0, 255}), vertex(30, 45, {1, 2, 3, 4}));
  f.draw(state, {t});
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (!covers(t, x + 0.5, y + 0.5)) continue;
      const Rgba c = f.color(x, y);
      EXPECT_EQ(c.r, 1);
      EXPECT_EQ(c.g, 2);
      EXPECT_EQ(c.b, 3);
      EXPECT_EQ(c.a, 4);
    }
  }
}

// --- Texturing -----------------------------------------------------------------

const std::vector<Rgba> TEXELS_2X2 = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {200, 100, 50, 128}};

// A square [8, 40) x [8, 40) mapped to s, t in [0, smax].
std::vector<gl::Triangle> textured_square(double smax, Rgba c, double x0 = 8) {
  const double x1 = x0 + 32;
  const auto a = vertex(x0, x0, c, 0.5, 0, 0), b = vertex(x1, x0, c, 0.5, float(smax), 0),
             d = vertex(x1, x1, c, 0.5, float(smax), float(smax)), e = vertex(x0, x1, c, 0.5, 0, float(smax));
  return {triangle(a, b, d), triangle(a, d, e)};
}

int div255_round(int x) {
  return int(std::lround(x / 255.0));
}

void check_texture(gl::TexWrap wrap, double smax, gl::TexEnvMode env) {
  Frame f(48, 48, PixelFormat::rgba8888);
  gl::RasterState state;
  state.flat_shading = true;
  state.unit[0].enabled = true;
  state.unit[0].tex = f.texture(2, 2, TEXELS_2X2);
  state.unit[0].tex.wrap_s = state.unit[0].tex.wrap_t = wrap;
  state.unit[0].env = env;
  const uint8_t env_color[4] = {40, 80, 160, 0};
  std::copy(env_color, env_color + 4, state.unit[0].env_color);
  const Rgba cf{128, 255, 64, 200};
  f.draw(state, textured_square(smax, cf));
  for (int y = 8; y < 40; ++y) {
    for (int x = 8; x < 40; ++x) {
      // Texel coordinate u = s * 2, never an integer at a pixel centre here.
      const double u = (x + 0.5 - 8) / 32 * smax * 2, v = (y + 0.5 - 8) / 32 * smax * 2;
      int i = int(std::floor(u)), j = int(std::floor(v));
      if (wrap == gl::TexWrap::repeat) {
        i &= 1;
        j &= 1;
      } else {
        i = std::min(i, 1);
        j = std::min(j, 1);
      }
      const Rgba t = TEXELS_2X2[size_t(j) * 2 + size_t(i)];
      Rgba expected{};
      switch (env) {
        case gl::TexEnvMode::modulate:
          expected = {div255_round(cf.r * t.r), div255_round(cf.g * t.g), div255_round(cf.b * t.b),
                      div255_round(cf.a * t.a)};
          break;
        case gl::TexEnvMode::replace: expected = t; break;
        case gl::TexEnvMode::decal:
          expected = {div255_round(cf.r * (255 - t.a) + t.r * t.a), div255_round(cf.g * (255 - t.a) + t.g * t.a),
                      div255_round(cf.b * (255 - t.a) + t.b * t.a), cf.a};
          break;
        // BLEND with GL_TEXTURE_ENV_COLOR (40, 80, 160, 0): Cf (1 - Ct) + Cc Ct.
        case gl::TexEnvMode::blend:
          expected = {div255_round(cf.r * (255 - t.r) + 40 * t.r), div255_round(cf.g * (255 - t.g) + 80 * t.g),
                      div255_round(cf.b * (255 - t.b) + 160 * t.b), div255_round(cf.a * t.a)};
          break;
        case gl::TexEnvMode::add:
          expected = {std::min(cf.r + t.r, 255), std::min(cf.g + t.g, 255), std::min(cf.b + t.b, 255),
                      div255_round(cf.a * t.a)};
          break;
        case gl::TexEnvMode::combine: FAIL() << "not a case of this test"; break;
      }
      const Rgba c = f.color(x, y);
      ASSERT_EQ(c.r, expected.r) << x << "," << y;
      ASSERT_EQ(c.g, expected.g) << x << "," << y;
      ASSERT_EQ(c.b, expected.b) << x << "," << y;
      ASSERT_EQ(c.a, expected.a) << x << "," << y;
    }
  }
  EXPECT_TRUE(f.guards_intact());
}

TEST(ArmRasterizerTexture, NearestReplace) {
  check_texture(gl::TexWrap::repeat, 1, gl::TexEnvMode::replace);
}
TEST(ArmRasterizerTexture, NearestRepeat) {
  check_texture(gl::TexWrap::repeat, 2, gl::TexEnvMode::replace);
}
TEST(ArmRasterizerTexture, NearestClampToEdge) {
  check_texture(gl::TexWrap::clamp_to_edge, 2, gl::TexEnvMode::replace);
}
TEST(ArmRasterizerTexture, Modulate) {
  check_texture(gl::TexWrap::repeat, 1, gl::TexEnvMode::modulate);
}
TEST(ArmRasterizerTexture, Decal) {
  check_texture(gl::TexWrap::repeat, 1, gl::TexEnvMode::decal);
}

TEST(ArmRasterizerTexture, Blend) {
  check_texture(gl::TexWrap::repeat, 1, gl::TexEnvMode::blend);
}
TEST(ArmRasterizerTexture, Add) {
  check_texture(gl::TexWrap::repeat, 1, gl::TexEnvMode::add);
}

// Two units applied in order: unit 0 REPLACEs the fragment colour by the
// 2x2 texture, unit 1 (a 1x1 texture, its coordinates those of unit 0)
// either ADDs its texel or, in GL_COMBINE, INTERPOLATEs between the primary
// colour and the previous unit's result by the constant's alpha.
void check_two_units(bool combine) {
  Frame f(48, 48, PixelFormat::rgba8888);
  gl::RasterState state;
  state.flat_shading = true;
  state.unit[0].enabled = true;
  state.unit[0].tex = f.texture(2, 2, TEXELS_2X2);
  state.unit[0].env = gl::TexEnvMode::replace;
  state.unit[1].enabled = true;
  state.unit[1].tex = f.texture(1, 1, {Rgba{10, 20, 30, 255}}, 2 * 2 * 4);
  const int k = 64;  // the constant's alpha
  if (combine) {
    gl::TextureUnit& u = state.unit[1];
    u.env = gl::TexEnvMode::combine;
    u.env_color[3] = uint8_t(k);
    u.combine_rgb.func = u.combine_alpha.func = gl::CombineFunc::interpolate;
    for (gl::CombineStage* stage : {&u.combine_rgb, &u.combine_alpha}) {
      stage->source[0] = gl::CombineSource::primary_color;
      stage->source[1] = gl::CombineSource::previous;
      stage->source[2] = gl::CombineSource::constant;
    }
  } else {
    state.unit[1].env = gl::TexEnvMode::add;
  }
  const Rgba cf{128, 255, 64, 200};
  std::vector<gl::Triangle> square = textured_square(1, cf);
  for (gl::Triangle& t : square)
    for (gl::ScreenVertex& v : t.v) v.tex[1] = v.tex[0];
  f.draw(state, square);
  for (int y = 8; y < 40; ++y) {
    for (int x = 8; x < 40; ++x) {
      const int i = int(std::floor((x + 0.5 - 8) / 16)), j = int(std::floor((y + 0.5 - 8) / 16));
      const Rgba t = TEXELS_2X2[size_t(j) * 2 + size_t(i)];
      Rgba expected{};
      if (combine) {
        // Primary k/255 + previous (1 - k/255).
        auto mix = [&](int p, int q) { return div255_round(p * k + q * (255 - k)); };
        expected = {mix(cf.r, t.r), mix(cf.g, t.g), mix(cf.b, t.b), mix(cf.a, t.a)};
      } else {
        expected = {std::min(t.r + 10, 255), std::min(t.g + 20, 255), std::min(t.b + 30, 255), t.a};
      }
      const Rgba c = f.color(x, y);
      ASSERT_EQ(c.r, expected.r) << x << "," << y;
      ASSERT_EQ(c.g, expected.g) << x << "," << y;
      ASSERT_EQ(c.b, expected.b) << x << "," << y;
      ASSERT_EQ(c.a, expected.a) << x << "," << y;
    }
  }
  EXPECT_TRUE(f.guards_intact());
}

TEST(ArmRasterizerTexture, SecondUnitAddsToTheFirst) {
  check_two_units(false);
}
TEST(ArmRasterizerTexture, SecondUnitCombinesPrimaryAndPrevious) {
  check_two_units(true);
}

TEST(ArmRasterizerTexture, BilinearAtTheTextureCentreAveragesFourTexels) {
  Frame f(48, 48, PixelFormat::rgba8888);
  gl::RasterState state;
  state.flat_shading = true;
  state.unit[0].enabled = true;
  state.unit[0].tex = f.texture(2, 2, TEXELS_2X2);
  state.unit[0].tex.mag_filter = gl::TexFilter::linear;
  state.unit[0].tex.wrap_s = state.unit[0].tex.wrap_t = gl::TexWrap::clamp_to_edge;
  state.unit[0].env = gl::TexEnvMode::replace;
  f.draw(state, textured_square(1, {255, 255, 255, 255}, 8.5));
  // Pixel (24, 24) has its centre at s = t = 0.5: texel coordinate (1, 1).
  const Rgba c = f.color(24, 24);
  EXPECT_NEAR(c.r, (255 + 0 + 0 + 200) / 4.0, 1.0);
  EXPECT_NEAR(c.g, (0 + 255 + 0 + 100) / 4.0, 1.0);
  EXPECT_NEAR(c.b, (0 + 0 + 255 + 50) / 4.0, 1.0);
  EXPECT_NEAR(c.a, (255 * 3 + 128) / 4.0, 1.0);
  // Deep inside a texel's quarter, clamped: that texel alone.
  const Rgba corner = f.color(9, 9);
  EXPECT_EQ(corner.r, 255);
  EXPECT_EQ(corner.g, 0);
}

TEST(ArmRasterizerTexture, PerspectiveCorrectCoordinates) {
  Frame f(64, 48, PixelFormat::rgba8888);
  std::vector<Rgba> ramp(64);
  for (int i = 0; i < 64; ++i) ramp[size_t(i)] = {i * 4, 0, 0, 255};
  gl::RasterState state;
  state.flat_shading = true;
  state.unit[0].enabled = true;
  state.unit[0].tex = f.texture(64, 1, ramp);
  state.unit[0].env = gl::TexEnvMode::replace;
  const gl::Triangle t = triangle(vertex(2, 2, {}, 0.5, 0.0f, 0.5f, 1.0f), vertex(62, 2, {}, 0.5, 0.999f, 0.5f, 0.25f),
                                  vertex(2, 46, {}, 0.5, 0.0f, 0.5f, 1.0f));
  f.draw(state, {t});
  int checked = 0, far_from_affine = 0;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (!covers(t, x + 0.5, y + 0.5)) continue;
      const auto w = barycentric(t, x + 0.5, y + 0.5);
      double sq = 0, q = 0, affine = 0;
      for (int k = 0; k < 3; ++k) {
        sq += w[k] * t.v[k].tex[0].s * t.v[k].inv_w;
        q += w[k] * t.v[k].inv_w;
        affine += w[k] * t.v[k].tex[0].s;
      }
      const double u = sq / q * 64;
      const int texel = f.color(x, y).r / 4;
      EXPECT_LE(std::abs(texel - std::floor(u)), 1.0) << x << "," << y << " u=" << u;
      far_from_affine += std::abs(affine * 64 - u) > 4;
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
  EXPECT_GT(far_from_affine, 100);
}

// --- Fog ---------------------------------------------------------------------

// GL's fog factor of eye distance c, in double (ES 1.1, 3.8).
double gl_fog_factor(const gl::RasterState& s, double c) {
  switch (s.fog_mode) {
    case gl::FogMode::linear: return std::clamp((s.fog_end - c) / (s.fog_end - s.fog_start), 0.0, 1.0);
    case gl::FogMode::exp: return std::exp(-s.fog_density * c);
    case gl::FogMode::exp2: return std::exp(-(s.fog_density * c) * (s.fog_density * c));
  }
  return 1;
}

// A perspective triangle whose eye distance grows from 2 to 16 across the
// frame, in each mode: every pixel is GL's C f + Cfog (1 - f) with the fog
// coordinate interpolated perspective-correctly (c/w over 1/w, as Mesa
// does), within 2 codes (the 8-bit factor: 0.82; the blend's rounding: 0.5;
// the fog argument's 16.16 interpolation: well below one code). Alpha stays.
TEST(ArmRasterizerFog, EveryModeMatchesGlFormulaPerFragment) {
  for (const gl::FogMode mode : {gl::FogMode::linear, gl::FogMode::exp, gl::FogMode::exp2}) {
    Frame f(64, 48, PixelFormat::rgba8888);
    gl::RasterState state;
    state.fog = true;
    state.fog_mode = mode;
    state.fog_density = mode == gl::FogMode::exp2 ? 0.12f : 0.2f;
    state.fog_start = 3;
    state.fog_end = 14;
    state.fog_color[0] = 200, state.fog_color[1] = 100, state.fog_color[2] = 20, state.fog_color[3] = 7;
    auto v = [](double x, double y, Rgba c, float eye) {
      gl::ScreenVertex sv = vertex(x, y, c, 0.5, 0, 0, 1.0f / eye);
      sv.fog = eye;
      return sv;
    };
    const gl::Triangle t =
        triangle(v(1, 1, {10, 240, 128, 99}, 2), v(63, 1, {250, 0, 60, 99}, 16), v(1, 47, {30, 30, 220, 99}, 5));
    f.draw(state, {t});
    int checked = 0;
    for (int y = 0; y < 48; ++y) {
      for (int x = 0; x < 64; ++x) {
        if (!covers(t, x + 0.5, y + 0.5)) continue;
        const auto w = barycentric(t, x + 0.5, y + 0.5);
        double q = 0, cq = 0, rgb_q[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k) {
          q += w[k] * t.v[k].inv_w;
          cq += w[k] * t.v[k].fog * t.v[k].inv_w;
          const uint8_t channels[3] = {t.v[k].r, t.v[k].g, t.v[k].b};
          for (int ch = 0; ch < 3; ++ch) rgb_q[ch] += w[k] * channels[ch] * t.v[k].inv_w;
        }
        const double factor = gl_fog_factor(state, cq / q);
        const Rgba got = f.color(x, y);
        const int got_rgb[3] = {got.r, got.g, got.b};
        for (int ch = 0; ch < 3; ++ch) {
          const double colour = rgb_q[ch] / q;
          const double expected = factor * colour + (1 - factor) * state.fog_color[ch];
          EXPECT_LE(std::fabs(got_rgb[ch] - expected), 2.0) << "mode " << int(mode) << " at " << x << "," << y;
        }
        EXPECT_EQ(got.a, 99);
        ++checked;
      }
    }
    EXPECT_GT(checked, 1000);
  }
}

// Fog off leaves the picture as it was: the same triangle with fog
// coordinates set but GL_FOG disabled draws the unfogged colours.
TEST(ArmRasterizerFog, DisabledFogChangesNothing) {
  Frame plain(32, 32, PixelFormat::rgb565), with_coordinates(32, 32, PixelFormat::rgb565);
  gl::Triangle t =
      triangle(vertex(1, 1, {200, 10, 10, 255}), vertex(31, 2, {10, 200, 10, 255}), vertex(3, 30, {10, 10, 200, 255}));
  plain.draw(gl::RasterState{}, {t});
  for (auto& sv : t.v) sv.fog = 50;
  gl::RasterState state;
  state.fog_mode = gl::FogMode::linear;
  with_coordinates.draw(state, {t});
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) ASSERT_EQ(plain.packed565(x, y), with_coordinates.packed565(x, y));
}

// Fog comes after texturing: a REPLACE texel is fogged, not the vertex colour.
TEST(ArmRasterizerFog, AppliesAfterTheTextureEnvironment) {
  Frame f(16, 16, PixelFormat::rgba8888);
  gl::RasterState state;
  state.unit[0].enabled = true;
  state.unit[0].tex = f.texture(1, 1, {{255, 255, 255, 255}});
  state.unit[0].env = gl::TexEnvMode::replace;
  state.fog = true;
  state.fog_mode = gl::FogMode::linear;
  state.fog_start = 0;
  state.fog_end = 10;
  // c = 5 everywhere: f = 1/2, so white against a black fog gives 128 (127.5 up).
  gl::Triangle t = triangle(vertex(0, 0, {0, 0, 0, 255}), vertex(16, 0, {0, 0, 0, 255}), vertex(0, 16, {0, 0, 0, 255}));
  for (auto& sv : t.v) sv.fog = 5;
  f.draw(state, {t});
  const Rgba c = f.color(2, 2);
  EXPECT_EQ(c.r, 128);
  EXPECT_EQ(c.g, 128);
  EXPECT_EQ(c.b, 128);
  EXPECT_EQ(c.a, 255);
}

// --- Per-fragment operations -----------------------------------------------

TEST(ArmRasterizerFragment, BlendSrcAlphaOneMinusSrcAlpha) {
  Frame f(32, 32, PixelFormat::rgba8888);
  gl::ClearRequest clear;
  clear.color = true;
  const uint8_t dst[4] = {200, 100, 50, 255};
  std::copy(dst, dst + 4, clear.rgba);
  f.rasterizer->clear(clear);
  gl::RasterState state;
  state.blend = true;
  state.blend_src = gl::BlendFactor::src_alpha;
  state.blend_dst = gl::BlendFactor::one_minus_src_alpha;
  const Rgba src{100, 200, 0, 128};
  f.draw(state, {triangle(vertex(-10, -10, src), vertex(60, -10, src), vertex(-10, 60, src))});
  // result = round(S * As / 255) + round(D * (255 - As) / 255), clamped.
  auto expect = [&](int s, int d, int as) {
    return std::min(255, div255_round(s * as) + div255_round(d * (255 - as)));
  };
  const Rgba c = f.color(5, 5);
  EXPECT_EQ(c.r, expect(src.r, dst[0], src.a));
  EXPECT_EQ(c.g, expect(src.g, dst[1], src.a));
  EXPECT_EQ(c.b, expect(src.b, dst[2], src.a));
  EXPECT_EQ(c.a, expect(src.a, dst[3], src.a));
}

TEST(ArmRasterizerFragment, ScissorAndColorMask) {
  Frame f(32, 32, PixelFormat::rgba8888);
  gl::RasterState state;
  state.scissor_test = true;
  state.scissor_x = 5;
  state.scissor_y = 7;
  state.scissor_width = 10;
  state.scissor_height = 4;
  state.color_mask[0] = false;
  state.color_mask[2] = false;
  const Rgba c{255, 255, 255, 255};
  f.draw(state, {triangle(vertex(-10, -10, c), vertex(80, -10, c), vertex(-10, 80, c))});
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const bool in = x >= 5 && x < 15 && y >= 7 && y < 11;
      const Rgba p = f.color(x, y);
      EXPECT_EQ(p.r, 0);
      EXPECT_EQ(p.g, in ? 255 : 0) << x << "," << y;
      EXPECT_EQ(p.b, 0);
      EXPECT_EQ(p.a, in ? 255 : 0);
    }
  }
}

TEST(ArmRasterizerFragment, AlphaTestAndStencil) {
  Frame f(32, 32, PixelFormat::rgba8888);
  gl::RasterState state;
  state.alpha_test = true;
  state.alpha_func = gl::CompareFunc::greater;
  state.alpha_ref = 128;
  const gl::Triangle small =
      triangle(vertex(4, 4, {255, 0, 0, 100}), vertex(20, 4, {255, 0, 0, 100}), vertex(4, 20, {255, 0, 0, 100}));
  f.draw(state, {small});
  EXPECT_EQ(f.color(6, 6).r, 0);  // alpha 100 is not > 128

  // Mark the small triangle in the stencil buffer without drawing colour.
  state = gl::RasterState{};
  state.stencil_test = true;
  state.stencil_func = gl::CompareFunc::always;
  state.stencil_ref = 1;
  state.depth_pass = gl::StencilOp::replace;
  for (bool& m : state.color_mask) m = false;
  f.draw(state, {small});
  // Then draw everything where the stencil equals 1.
  state = gl::RasterState{};
  state.stencil_test = true;
  state.stencil_func = gl::CompareFunc::equal;
  state.stencil_ref = 1;
  state.depth_pass = gl::StencilOp::incr;
  const Rgba g{0, 255, 0, 255};
  f.draw(state, {triangle(vertex(-10, -10, g), vertex(80, -10, g), vertex(-10, 80, g))});
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const bool in = covers(small, x + 0.5, y + 0.5);
      EXPECT_EQ(f.color(x, y).g, in ? 255 : 0) << x << "," << y;
      EXPECT_EQ(f.stencil(x, y), in ? 2 : 0);
    }
  }
}

TEST(ArmRasterizerFragment, LogicOpXor) {
  Frame f(16, 16, PixelFormat::rgba8888);
  gl::ClearRequest clear;
  clear.color = true;
  const uint8_t dst[4] = {0x0f, 0xf0, 0x55, 0xff};
  std::copy(dst, dst + 4, clear.rgba);
  f.rasterizer->clear(clear);
  gl::RasterState state;
  state.logic_op = true;
  state.logic_op_mode = gl::LogicOp::xor_;
  state.blend = true;  // ignored while the logic op is enabled
  const Rgba s{0xff, 0xff, 0x0f, 0x00};
  f.draw(state, {triangle(vertex(-10, -10, s), vertex(60, -10, s), vertex(-10, 60, s))});
  const Rgba c = f.color(3, 3);
  EXPECT_EQ(c.r, 0xf0);
  EXPECT_EQ(c.g, 0x0f);
  EXPECT_EQ(c.b, 0x5a);
  EXPECT_EQ(c.a, 0xff);
}

// --- Clear -------------------------------------------------------------------

TEST(ArmRasterizerClear, MasksAndScissor) {
  Frame f(32, 24, PixelFormat::rgba8888);
  gl::ClearRequest all;
  all.color = all.depth = all.stencil = true;
  all.rgba[0] = 10;
  all.rgba[1] = 20;
  all.rgba[2] = 30;
  all.rgba[3] = 40;
  all.depth_value = 0x123456;
  all.stencil_value = 0xf0;
  f.rasterizer->clear(all);
  gl::ClearRequest part;
  part.color = part.depth = part.stencil = true;
  part.rgba[0] = part.rgba[1] = part.rgba[2] = part.rgba[3] = 200;
  part.color_mask[1] = false;
  part.color_mask[3] = false;
  part.depth_value = 0xabcdef;
  part.stencil_value = 0x0f;
  part.stencil_write_mask = 0x0c;
  part.scissor_test = true;
  part.scissor_x = 3;
  part.scissor_y = 2;
  part.scissor_width = 7;
  part.scissor_height = 5;
  f.rasterizer->clear(part);
  for (int y = 0; y < 24; ++y) {
    for (int x = 0; x < 32; ++x) {
      const bool in = x >= 3 && x < 10 && y >= 2 && y < 7;
      const Rgba c = f.color(x, y);
      EXPECT_EQ(c.r, in ? 200 : 10);
      EXPECT_EQ(c.g, 20);
      EXPECT_EQ(c.b, in ? 200 : 30);
      EXPECT_EQ(c.a, 40);
      EXPECT_EQ(f.depth(x, y), in ? 0xabcd : 0x1234);
      EXPECT_EQ(f.stencil(x, y), in ? ((0xf0 & ~0x0c) | (0x0f & 0x0c)) : 0xf0);
    }
  }
  // Depth write disabled: depth untouched.
  gl::ClearRequest no_depth;
  no_depth.depth = true;
  no_depth.depth_write = false;
  no_depth.depth_value = 0;
  f.rasterizer->clear(no_depth);
  EXPECT_EQ(f.depth(0, 0), 0x1234);
  EXPECT_TRUE(f.guards_intact());
}

// --- Robustness --------------------------------------------------------------

TEST(ArmRasterizerRobustness, FarOutsideAndDegenerateTrianglesStayInTheBuffers) {
  for (PixelFormat format : {PixelFormat::rgb565, PixelFormat::rgba8888}) {
    Frame f(40, 30, format);
    gl::RasterState state;
    state.depth_test = true;
    state.stencil_test = true;
    state.depth_pass = gl::StencilOp::incr;
    state.blend = true;
    state.blend_src = gl::BlendFactor::one;
    state.blend_dst = gl::BlendFactor::one;
    state.unit[0].enabled = true;
    state.unit[0].tex = f.texture(4, 4, std::vector<Rgba>(16, Rgba{10, 20, 30, 255}));
    const Rgba c{1, 1, 1, 1};
    // Far outside the screen, within the core's coordinate limit (+-1024
    // pixels, planes.h); texture coordinates beyond the clamp.
    const gl::Triangle huge =
        triangle(vertex(-1000, -500, c, 0.1, -1000, 3, 0.5f), vertex(1020, 30, c, 0.9, 5000, -7, 1.0f),
                 vertex(30, 1000, c, 0.5, 2, 9000, 0.01f));
    std::vector<gl::Triangle> tris = {
        huge,
        triangle(vertex(5, 5, c), vertex(5, 5, c), vertex(5, 5, c)),           // a point
        triangle(vertex(1, 1, c), vertex(20, 20, c), vertex(39, 39, c)),       // collinear
        triangle(vertex(-5, 7.5, c), vertex(50, 7.5, c), vertex(20, 7.5, c)),  // zero height
        triangle(vertex(-50, 10, c), vertex(-10, 10, c), vertex(-30, 25, c)),  // left of the screen
        triangle(vertex(10, 31, c), vertex(30, 31, c), vertex(20, 60, c)),     // above the screen
    };
    gl::Triangle extreme = huge;
    extreme.v[0].x = INT32_MIN;
    extreme.v[1].y = INT32_MAX;
    tris.push_back(extreme);
    EXPECT_NO_THROW(f.draw(state, tris));
    EXPECT_TRUE(f.guards_intact());
    // The huge triangle covers exactly its reference pixels, once each.
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) EXPECT_EQ(f.stencil(x, y), covers(huge, x + 0.5, y + 0.5) ? 1 : 0);
  }
}

// --- Formats and read-back -------------------------------------------------

// GL's conversion of an 8-bit channel to `bits` bits: round(c * (2^bits - 1) / 255).
int to_bits(int c, int bits) {
  return int(std::lround(c * double((1 << bits) - 1) / 255.0));
}

TEST(ArmRasterizerFormats, Rgb565IsTheRgba8888PictureRoundedToNearest) {
  Frame f565(64, 48, PixelFormat::rgb565), f8888(64, 48, PixelFormat::rgba8888);
  const gl::Triangle t =
      triangle(vertex(3, 3, {255, 0, 17, 255}), vertex(60, 10, {0, 255, 99, 255}), vertex(20, 45, {123, 45, 255, 255}));
  f565.draw(gl::RasterState{}, {t});
  f8888.draw(gl::RasterState{}, {t});
  int drawn = 0;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const Rgba c = f8888.color(x, y);
      EXPECT_EQ(f565.packed565(x, y), (to_bits(c.r, 5) << 11) | (to_bits(c.g, 6) << 5) | to_bits(c.b, 5))
          << x << "," << y;
      drawn += c.a != 0;
    }
  }
  EXPECT_GT(drawn, 500);
  // read_pixels widens 5 and 6 bits by replication, rows from y upwards.
  std::vector<uint8_t> rgba(64 * 48 * 4);
  f565.rasterizer->read_pixels(0, 0, 64, 48, rgba.data());
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const int v = f565.packed565(x, y), r5 = v >> 11, g6 = (v >> 5) & 63, b5 = v & 31;
      const uint8_t* p = &rgba[(size_t(y) * 64 + size_t(x)) * 4];
      EXPECT_EQ(p[0], (r5 << 3) | (r5 >> 2));
      EXPECT_EQ(p[1], (g6 << 2) | (g6 >> 4));
      EXPECT_EQ(p[2], (b5 << 3) | (b5 >> 2));
      EXPECT_EQ(p[3], 255);
    }
  }
}

TEST(ArmRasterizerFormats, ReadPixelsOutsideTheScreenReadsZero) {
  Frame f(8, 8, PixelFormat::rgba8888);
  gl::ClearRequest clear;
  clear.color = true;
  clear.rgba[0] = 9;
  f.rasterizer->clear(clear);
  std::vector<uint8_t> rgba(4 * 4 * 4, 0xee);
  f.rasterizer->read_pixels(6, 6, 4, 4, rgba.data());
  EXPECT_EQ(rgba[0], 9);                // (6, 6)
  EXPECT_EQ(rgba[(0 * 4 + 2) * 4], 0);  // (8, 6) is outside
  EXPECT_EQ(rgba[(2 * 4 + 0) * 4], 0);  // (6, 8) is outside
}

TEST(ArmRasterizerFormats, DoubleBufferingMovesDrawing) {
  Frame f(16, 16, PixelFormat::rgba8888);
  const uint32_t front = f.color_address;
  const uint32_t back = f.texture_address;  // any other buffer-sized area
  f.rasterizer->set_color_address(back);
  gl::ClearRequest clear;
  clear.color = true;
  clear.rgba[1] = 77;
  f.rasterizer->clear(clear);
  EXPECT_EQ(*f.memory.at(back + 1), 77);
  EXPECT_EQ(*f.memory.at(front + 1), 0);
  EXPECT_EQ(f.rasterizer->color_address(), back);
}

// --- Accesses and charges --------------------------------------------------

TEST(ArmRasterizerCost, OneMemoryCallPerSpanAndBuffer) {
  Frame f(64, 48, PixelFormat::rgb565);
  gl::RasterState state;
  state.depth_test = true;
  f.memory.reset_counters();
  const gl::Triangle t = triangle(vertex(2, 2), vertex(60, 3), vertex(30, 45));
  f.draw(state, {t});
  int pixels = 0, rows = 0;
  for (int y = 0; y < 48; ++y) {
    int in_row = 0;
    for (int x = 0; x < 64; ++x) in_row += covers(t, x + 0.5, y + 0.5);
    pixels += in_row;
    rows += in_row > 0;
  }
  const NativeMemory::Counters& counters = f.memory.counters();
  EXPECT_EQ(counters.load_calls, uint64_t(rows));       // depth
  EXPECT_EQ(counters.store_calls, uint64_t(2 * rows));  // depth and colour
  EXPECT_EQ(counters.load_elements, uint64_t(pixels));
  EXPECT_EQ(counters.store_bytes, uint64_t(4 * pixels));
  // The host is charged per row, span, pixel walked, shaded and written.
  EXPECT_EQ(f.memory.units(HostCost::arm_triangle), 1u);
  EXPECT_EQ(f.memory.units(HostCost::arm_span), uint64_t(rows));
  EXPECT_EQ(f.memory.units(HostCost::arm_pixel), uint64_t(pixels));
  EXPECT_EQ(f.memory.units(HostCost::arm_pixel_depth), uint64_t(pixels));
  EXPECT_EQ(f.memory.units(HostCost::arm_pixel_color), uint64_t(pixels));
  EXPECT_EQ(f.memory.units(HostCost::arm_shaded_pixel), uint64_t(pixels));  // the depth buffer was cleared far
  EXPECT_EQ(f.memory.units(HostCost::arm_color_write), uint64_t(pixels));
  EXPECT_EQ(f.memory.units(HostCost::arm_depth_write), uint64_t(pixels));
  EXPECT_EQ(f.memory.units(HostCost::arm_texel_nearest) + f.memory.units(HostCost::arm_texel_linear), 0u);
}

// Mipmaps: a 32 x 32 texture whose six levels are solid colours (level k:
// red 50 k, green 255 - 50 k) on the 32 x 32 pixel square, s and t from 0
// to smax: smax texels of level 0 per pixel, lambda = log2(smax) everywhere.
namespace {

gl::Texture mipmap_levels(Frame& f, gl::TexFilter within, gl::MipmapFilter mipmap) {
  gl::Texture tex = f.texture(32, 32, std::vector<Rgba>(32 * 32, Rgba{0, 255, 0, 255}));
  tex.min_filter = within;
  tex.min_mipmap = mipmap;
  tex.levels = 6;
  uint32_t address = tex.address;
  for (unsigned k = 0; k < 6; ++k) {
    const unsigned side = 32u >> k;
    tex.level[k] = {address, side, side};
    uint8_t* p = f.memory.at(address, side * side * 4);
    for (unsigned i = 0; i < side * side; ++i) {
      p[4 * i] = uint8_t(50 * k);
      p[4 * i + 1] = uint8_t(255 - 50 * k);
      p[4 * i + 2] = 0;
      p[4 * i + 3] = 255;
    }
    address += side * side * 4;
  }
  return tex;
}

Rgba mipmapped_centre(double smax, gl::TexFilter within, gl::MipmapFilter mipmap) {
  Frame f(48, 48, PixelFormat::rgba8888);
  gl::RasterState state;
  state.flat_shading = true;
  state.unit[0].enabled = true;
  state.unit[0].tex = mipmap_levels(f, within, mipmap);
  state.unit[0].env = gl::TexEnvMode::replace;
  f.draw(state, textured_square(smax, {255, 255, 255, 255}));
  return f.color(24, 24);
}

}  // namespace

TEST(ArmRasterizerTexture, NearestMipmapTakesTheLevelOfLambda) {
  // lambda = 2: level ceil(2.5) - 1 = 2.
  EXPECT_EQ(mipmapped_centre(4, gl::TexFilter::nearest, gl::MipmapFilter::nearest).r, 100);
  // lambda = log2(1.5) = 0.58 > 0.5: level 1; log2(1.25) = 0.32: level 0.
  EXPECT_EQ(mipmapped_centre(1.5, gl::TexFilter::nearest, gl::MipmapFilter::nearest).r, 50);
  EXPECT_EQ(mipmapped_centre(1.25, gl::TexFilter::nearest, gl::MipmapFilter::nearest).r, 0);
  // lambda = 6 is past the last level, 5 (1 x 1).
  EXPECT_EQ(mipmapped_centre(64, gl::TexFilter::nearest, gl::MipmapFilter::nearest).r, 250);
  // Magnified (lambda = -1): level 0.
  EXPECT_EQ(mipmapped_centre(0.5, gl::TexFilter::nearest, gl::MipmapFilter::nearest).r, 0);
}

TEST(ArmRasterizerTexture, LinearMipmapBlendsTheTwoLevelsAroundLambda) {
  // lambda = log2(3) = 1.585: levels 1 (red 50) and 2 (red 100), weight 0.585 of level 2: 79.2.
  const Rgba c = mipmapped_centre(3, gl::TexFilter::linear, gl::MipmapFilter::linear);
  EXPECT_NEAR(c.r, 50 + 50 * (std::log2(3.0) - 1), 1.0);
  EXPECT_NEAR(c.g, 205 - 50 * (std::log2(3.0) - 1), 1.0);
  // lambda = 2 exactly: level 2 alone.
  EXPECT_EQ(mipmapped_centre(4, gl::TexFilter::linear, gl::MipmapFilter::linear).r, 100);
}

// Each unit samples with its own level of detail, from its own coordinates:
// unit 0 (REPLACE) at lambda = 2 takes level 2 (red 100, green 155); unit 1
// (ADD) on the same texture at lambda = -1 (magnified) takes level 0 (red 0,
// green 255). Red stays 100; had unit 1 used unit 0's lambda it would add
// level 2's red (200), had unit 0 used unit 1's it would be 0.
TEST(ArmRasterizerTexture, EachUnitSamplesItsMipmapsWithItsOwnLevelOfDetail) {
  Frame f(48, 48, PixelFormat::rgba8888);
  gl::RasterState state;
  state.flat_shading = true;
  const gl::Texture tex = mipmap_levels(f, gl::TexFilter::nearest, gl::MipmapFilter::nearest);
  state.unit[0].enabled = state.unit[1].enabled = true;
  state.unit[0].tex = state.unit[1].tex = tex;
  state.unit[0].env = gl::TexEnvMode::replace;
  state.unit[1].env = gl::TexEnvMode::add;
  std::vector<gl::Triangle> square = textured_square(4, {255, 255, 255, 255});
  for (gl::Triangle& t : square)
    for (gl::ScreenVertex& v : t.v) v.tex[1] = {v.tex[0].s / 8, v.tex[0].t / 8};
  f.draw(state, square);
  const Rgba c = f.color(24, 24);
  EXPECT_EQ(c.r, 100);
  EXPECT_EQ(c.g, 255);  // 155 + 255, saturated
  EXPECT_TRUE(f.guards_intact());
}

// The base format's rules apply per unit before that unit's environment, and
// fog after the last unit: unit 0 REPLACEs with an RGB texel (the fragment's
// alpha kept, table 3.15), unit 1 MODULATEs with an ALPHA texture (colour
// kept, alpha times the texel's), then linear fog at f = 1/2 towards black.
TEST(ArmRasterizerTexture, BaseFormatsPerUnitThenFog) {
  Frame f(16, 16, PixelFormat::rgba8888);
  gl::RasterState state;
  state.flat_shading = true;
  state.unit[0].enabled = state.unit[1].enabled = true;
  state.unit[0].tex = f.texture(1, 1, {{200, 100, 50, 255}});
  state.unit[0].tex.has_alpha = false;
  state.unit[0].env = gl::TexEnvMode::replace;
  state.unit[1].tex = f.texture(1, 1, {{0, 0, 0, 128}}, 64);
  state.unit[1].tex.has_color = false;
  state.unit[1].env = gl::TexEnvMode::modulate;
  state.fog = true;
  state.fog_mode = gl::FogMode::linear;
  state.fog_start = 0;
  state.fog_end = 10;
  gl::Triangle t = triangle(vertex(0, 0, {0, 0, 0, 200}), vertex(16, 0, {0, 0, 0, 200}), vertex(0, 16, {0, 0, 0, 200}));
  for (auto& sv : t.v) sv.fog = 5;
  f.draw(state, {t});
  const Rgba c = f.color(2, 2);
  EXPECT_EQ(c.r, 100);  // 200 / 2
  EXPECT_EQ(c.g, 50);   // 100 / 2
  EXPECT_EQ(c.b, 25);   // 50 / 2
  EXPECT_EQ(c.a, 100);  // 200 (the fragment's, not the RGB texel's 255) x 128 / 255 = 100.4
}

// --- Fixed point: the bounds of planes.h and triangle_setup.cpp at their extremes --------

// floor(2^59 / m) exactly over [2^29, 2^30]: both ends, powers of two, and a
// sweep; the reference is the exact 128-bit quotient (test code only).
TEST(ArmFixedPoint, ReciprocalIsTheExactFloorOver29To30Bits) {
  __extension__ typedef unsigned __int128 Wide;
  auto exact = [](uint32_t m) { return uint32_t((Wide(1) << 59) / m); };
  const uint32_t lo = 1u << 29, hi = 1u << 30;
  for (uint32_t m : {lo, lo + 1, lo + 2, hi - 2, hi - 1, hi, (lo + hi) / 2, 0x2aaaaaabu, 0x3fffc000u})
    EXPECT_EQ(renderers::reciprocal_2_59(m), exact(m)) << m;
  std::mt19937 random(27);
  std::uniform_int_distribution<uint32_t> any(lo, hi);
  for (int i = 0; i < 200000; ++i) {
    const uint32_t m = any(random);
    ASSERT_EQ(renderers::reciprocal_2_59(m), exact(m)) << m;
  }
}

// scaled_quotient(x, 1/d, k) within 2^-28 (relative) plus one of x 2^k / d,
// for the extremes the rasterizer divides: x up to 2^62 and d from 1 to
// 2^39 (twice an unsnapped area), and saturation beyond 2^62.
TEST(ArmFixedPoint, ScaledQuotientWithinItsStatedError) {
  std::mt19937_64 random(1);
  for (int i = 0; i < 200000; ++i) {
    const int dbits = int(random() % 40) + 1, xbits = int(random() % 62) + 1, k = int(random() % 40) - 8;
    const uint64_t d = std::max<uint64_t>(1, random() >> (64 - dbits));
    int64_t x = int64_t(random() >> (64 - xbits));
    if (random() & 1) x = -x;
    const long double exact = std::ldexp((long double)x, k) / (long double)d;
    const int64_t got = renderers::scaled_quotient(x, renderers::make_reciprocal(d), k);
    if (std::fabs(exact) >= std::ldexp(1.0L, 62)) {
      EXPECT_EQ(std::fabs((long double)got), std::ldexp(1.0L, 62)) << x << " " << d << " " << k;
      continue;
    }
    ASSERT_LE(std::fabs((long double)got - std::floor(exact)), std::fabs(exact) * std::ldexp(1.0L, -28) + 1.0L)
        << x << " * 2^" << k << " / " << d;
  }
}

TEST(ArmFixedPoint, Log2Within1Point2UnitsOf2ToTheMinus16) {
  std::mt19937_64 random(2);
  for (uint64_t x : {uint64_t{1}, uint64_t{2}, uint64_t{3}, uint64_t{255}, uint64_t{1} << 31, (uint64_t{1} << 32) - 1,
                     uint64_t{1} << 60, ~uint64_t{0}}) {
    EXPECT_NEAR(renderers::log2_q16(x), std::log2((long double)x) * 65536, 1.2) << x;
  }
  for (int i = 0; i < 100000; ++i) {
    const uint64_t x = std::max<uint64_t>(1, random() >> (random() % 64));
    ASSERT_NEAR(renderers::log2_q16(x), std::log2((long double)x) * 65536, 1.2) << x;
  }
}

// The largest screen (512 x 512) covered by two triangles whose vertices
// lie at the core's coordinate limit (+-(2^14 - 1) in 9.4: the edges, areas
// and DDA numerators at their stated bounds). Coverage is exactly the edge
// functions' (every pixel once), Gouraud colour within one code of the
// barycentric value, depth within one 16-bit step.
TEST(ArmFixedPoint, LargestScreenWithVerticesAtTheCoordinateLimit) {
  Frame f(512, 512, PixelFormat::rgba8888);
  gl::RasterState state;
  state.depth_test = true;
  state.depth_func = gl::CompareFunc::always;
  state.stencil_test = true;
  state.depth_pass = gl::StencilOp::incr;
  const double m = ((1 << 14) - 1) / 16.0;  // 1023.9375 pixels
  const Rgba ca{255, 0, 10, 255}, cb{0, 255, 128, 0}, cc{30, 60, 255, 200}, cd{128, 128, 0, 90};
  const gl::Triangle t1 = triangle(vertex(-m, -m, ca, 0.0), vertex(m, -m, cb, 0.7), vertex(m, m, cc, 1.0));
  const gl::Triangle t2 = triangle(vertex(-m, -m, ca, 0.0), vertex(m, m, cc, 1.0), vertex(-m, m, cd, 0.3));
  f.draw(state, {t1, t2});
  int checked = 0;
  for (int y = 0; y < 512; y += 3) {
    for (int x = 0; x < 512; x += 3) {
      const double xc = x + 0.5, yc = y + 0.5;
      const int expected = covers(t1, xc, yc) + covers(t2, xc, yc);
      ASSERT_EQ(expected, 1);
      ASSERT_EQ(f.stencil(x, y), 1) << x << "," << y;
      const gl::Triangle& t = covers(t1, xc, yc) ? t1 : t2;
      const auto w = barycentric(t, xc, yc);
      const Rgba c = f.color(x, y);
      const Rgba vc[3] = {ca, covers(t1, xc, yc) ? cb : cc, covers(t1, xc, yc) ? cc : cd};
      EXPECT_NEAR(c.r, w[0] * vc[0].r + w[1] * vc[1].r + w[2] * vc[2].r, 1.0) << x << "," << y;
      EXPECT_NEAR(c.g, w[0] * vc[0].g + w[1] * vc[1].g + w[2] * vc[2].g, 1.0) << x << "," << y;
      EXPECT_NEAR(c.a, w[0] * vc[0].a + w[1] * vc[1].a + w[2] * vc[2].a, 1.0) << x << "," << y;
      double z = 0;
      for (int k = 0; k < 3; ++k) z += w[k] * double(t.v[k].z);
      EXPECT_NEAR(f.depth(x, y), z / 256.0, 1.0) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 29000);
  EXPECT_TRUE(f.guards_intact());
}

// A vertex one 1/16 pixel beyond the limit skips its triangle (the front end
// never sends one: its vertices lie in [0, 512]); one at the limit draws.
TEST(ArmFixedPoint, VertexBeyondTheCoordinateLimitSkipsTheTriangle) {
  Frame f(32, 32, PixelFormat::rgba8888);
  gl::RasterState state;
  state.stencil_test = true;
  state.depth_pass = gl::StencilOp::incr;
  gl::Triangle t = triangle(vertex(0, 0), vertex(32, 0), vertex(0, 32));
  t.v[1].x = (1 << 14);
  f.draw(state, {t});
  EXPECT_EQ(f.stencil(1, 1), 0);
  t.v[1].x = (1 << 14) - 1;
  f.draw(state, {t});
  EXPECT_EQ(f.stencil(1, 1), 1);
  Frame g(32, 32, PixelFormat::rgba8888);
  t.v[1].x = -(1 << 14);
  t.v[0].x = 31 * 16;
  t.v[2].x = 31 * 16;
  g.draw(state, {t});
  EXPECT_EQ(g.stencil(30, 1), 0);
  t.v[1].x = -(1 << 14) + 1;
  g.draw(state, {t});
  EXPECT_EQ(g.stencil(30, 1), 1);
}

// Slivers across the largest screen, each with pixel centres on its one
// drawn edge: 1/16 pixel high and 511 pixels long (a top edge), 1/16 pixel
// wide and 511 tall (a left edge), the diagonal with the third vertex 1/16
// pixel off it (a left edge), and a nearly horizontal one whose far end
// drops 1/16 pixel. Coverage is exactly the edge functions', and every drawn
// pixel's colour and depth stay within its vertices' values (the clamp and
// nudge of the planes), within one code of the barycentric colour where the
// weights are in [0, 1].
TEST(ArmFixedPoint, SliversAtTheLargestScreen) {
  const Rgba ca{0, 255, 0, 255}, cb{255, 0, 255, 0}, cc{128, 64, 32, 16};
  const std::vector<gl::Triangle> slivers = {
      triangle(vertex(0.25, 100.5, ca, 0.1), vertex(511.75, 100.5, cb, 0.9), vertex(300, 100.5 - 1 / 16.0, cc, 0.5)),
      triangle(vertex(200.5, 0.25, ca, 0.1), vertex(200.5 + 1 / 16.0, 511.75, cb, 0.9), vertex(200.5, 300, cc, 0.5)),
      triangle(vertex(0.5, 0.5, ca, 0.0), vertex(511.5, 511.5, cb, 1.0), vertex(256.0, 256.0 - 1 / 16.0, cc, 0.5)),
      triangle(vertex(0.5, 400.5, ca, 0.0), vertex(511.5, 400.4375, cb, 1.0), vertex(3.0, 400.5, cc, 0.2)),
  };
  for (const gl::Triangle& t : slivers) {
    Frame f(512, 512, PixelFormat::rgba8888);
    gl::RasterState state;
    state.depth_test = true;
    state.depth_func = gl::CompareFunc::always;
    state.stencil_test = true;
    state.depth_pass = gl::StencilOp::incr;
    f.draw(state, {t});
    int drawn = 0;
    for (int y = 0; y < 512; ++y) {
      for (int x = 0; x < 512; ++x) {
        const bool in = covers(t, x + 0.5, y + 0.5);
        ASSERT_EQ(f.stencil(x, y), in ? 1 : 0) << x << "," << y;
        if (!in) continue;
        ++drawn;
        const Rgba c = f.color(x, y);
        EXPECT_GE(c.r, 0);
        EXPECT_LE(c.r, 255);
        EXPECT_GE(c.g, std::min({ca.g, cb.g, cc.g}));
        EXPECT_LE(c.g, std::max({ca.g, cb.g, cc.g}));
        const uint16_t zmin = uint16_t(std::min({t.v[0].z, t.v[1].z, t.v[2].z}) >> 8);
        const uint16_t zmax = uint16_t(std::max({t.v[0].z, t.v[1].z, t.v[2].z}) >> 8);
        EXPECT_GE(f.depth(x, y), zmin);
        EXPECT_LE(f.depth(x, y), zmax);
        const auto w = barycentric(t, x + 0.5, y + 0.5);
        if (w[0] >= 0 && w[1] >= 0 && w[2] >= 0) {
          EXPECT_NEAR(c.g, w[0] * ca.g + w[1] * cb.g + w[2] * cc.g, 1.0) << x << "," << y;
        }
      }
    }
    EXPECT_GT(drawn, 0);
    EXPECT_TRUE(f.guards_intact());
  }
}

// Perspective texturing at the extremes of its formats on the largest
// screen: s W up to the clamp (2^15 texels: F = 14 fraction bits, s q 2^F
// just below 2^30) and 1/w varying 1000 times across the triangle (q down
// to 2^30 / 1000). The texel each pixel takes is within one of floor(u) of
// the exact perspective-correct u (u = (sum w_k s_k q_k) / (sum w_k q_k)),
// wrapped by the repeat mode.
TEST(ArmFixedPoint, PerspectiveTexturingAtTheFormatsExtremes) {
  Frame f(512, 512, PixelFormat::rgba8888);
  std::vector<Rgba> ramp(64);
  for (int i = 0; i < 64; ++i) ramp[size_t(i)] = {i * 4, 0, 0, 255};
  gl::RasterState state;
  state.flat_shading = true;
  state.unit[0].enabled = true;
  state.unit[0].tex = f.texture(64, 1, ramp);
  state.unit[0].env = gl::TexEnvMode::replace;
  for (const float far_s : {512.0f, 3.0f}) {  // s W = 32768 texels, and 192
    const gl::Triangle t =
        triangle(vertex(0, 0, {}, 0.5, 0.0f, 0.5f, 1.0f), vertex(512, 0, {}, 0.5, far_s, 0.5f, 0.001f),
                 vertex(0, 512, {}, 0.5, 0.0f, 0.5f, 1.0f));
    f.draw(state, {t});
    int checked = 0;
    for (int y = 0; y < 512; y += 5) {
      for (int x = 0; x < 512; x += 5) {
        if (!covers(t, x + 0.5, y + 0.5)) continue;
        const auto w = barycentric(t, x + 0.5, y + 0.5);
        double sq = 0, q = 0;
        for (int k = 0; k < 3; ++k) {
          sq += w[k] * t.v[k].tex[0].s * 64 * t.v[k].inv_w;
          q += w[k] * t.v[k].inv_w;
        }
        const double u = sq / q;
        const int texel = f.color(x, y).r / 4;
        const int exact = int(std::floor(u)) & 63;
        const int distance = std::min((texel - exact) & 63, (exact - texel) & 63);
        EXPECT_LE(distance, 1) << x << "," << y << " u=" << u;
        ++checked;
      }
    }
    EXPECT_GT(checked, 4000);
  }
}

// Degenerate triangles at the largest screen draw nothing: zero area
// (collinear across the screen, a point, two equal vertices).
TEST(ArmFixedPoint, DegenerateTrianglesDrawNothing) {
  Frame f(512, 512, PixelFormat::rgba8888);
  gl::RasterState state;
  state.stencil_test = true;
  state.depth_pass = gl::StencilOp::incr;
  f.draw(state, {triangle(vertex(0, 0), vertex(256, 256), vertex(512, 512)),
                 triangle(vertex(0.5, 511.5), vertex(511.5, 0.5), vertex(256, 256)),
                 triangle(vertex(100, 100), vertex(100, 100), vertex(100, 100)),
                 triangle(vertex(10, 10), vertex(500, 20), vertex(10, 10))});
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) ASSERT_EQ(f.stencil(x, y), 0) << x << "," << y;
}

}  // namespace
}  // namespace tessera::arm
