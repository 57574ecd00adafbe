// The functional core of the `arm` renderer: the study's sequential software
// rasterizer for the ARM host (fixed-point scan conversion with incremental
// edge and attribute stepping). Plain C++: it reaches its buffers and
// textures only through PixelMemory, which either counts (native) or charges
// (host model) the accesses it declares, and it charges its instructions with
// PixelMemory::charge: units of the rows of the host's measured cost table
// (sw_driver/costs), per triangle, row, span, pixel walked, pixel shaded,
// texel sampled and pixel written.
//
// Buffers. Colour is RGB565 (uint16, R in bits 15..11, little endian) or
// RGBA8888 (bytes R, G, B, A at increasing addresses); depth is uint16,
// smaller is nearer; stencil is uint8. Every buffer is width * height
// elements, packed, row 0 = the TOP row of the image (display order), so GL
// row y lives in buffer row height - 1 - y.
//
// Formats and rounding.
// - Depth: the 0.24 window depth is reduced to 16 bits by taking its top 16
//   bits (z24 >> 8, truncation). Depth is interpolated as z24 * 2^7 and the
//   16-bit value is the interpolant >> 15.
// - Colour channels are interpolated with 16 fraction bits and rounded to
//   nearest (the 0.5 is added once per span). To and from RGB565 they go by
//   the one rule of common/pixel_format.h: rounded to nearest on the way in,
//   widened by bit replication on the way out; the RGB565 buffer has no
//   alpha, destination alpha reads as 255.
// - Products of two 0.8 codes (modulate, decal, blending) are rounded to
//   nearest exactly: mul(a, b) = (a * b + 127) / 255, computed as
//   (x + 128 + ((x + 128) >> 8)) >> 8 with x = a * b.
// - Texture coordinates: s/w, t/w and 1/w are interpolated (1/w normalised
//   per triangle to the largest vertex 1/w, as q in [1, 2^30]; s W q and
//   t H q with F fraction bits, F = min(24, 30 - bits of the largest |s W|,
//   |t H| of the triangle), so that they stay below 2^30) and divided per
//   pixel to texel units with 8 fraction bits. When the three 1/w are equal the division is
//   skipped (affine). Nearest takes texel floor(u); bilinear blends texels
//   floor(u - 0.5) and +1 with 8-bit weights, rounded to nearest. Repeat
//   wraps with & (size - 1), clamp-to-edge clamps the texel index.
// - Level of detail: where it matters (a mipmap minification filter, or
//   different minification and magnification filters) lambda = log2(rho) is
//   computed per pixel from the derivatives of u = (s q)/q and v, which
//   follow from the planes' gradients and the pixel's stepped values
//   (renderers/common/texturing.h: texture_lod, choose_levels); the levels
//   are sampled at u / 2^level and two levels blended with an 8-bit weight.
//   Where it does not matter it is not computed.
//
// Fill rule (shared edges are drawn exactly once). Pixel (i, j) is drawn if
// its centre (i + 0.5, j + 0.5) is inside the triangle. A centre exactly on
// an edge is drawn only if that edge is a LEFT edge (the triangle lies at
// greater x) or a horizontal TOP edge (the triangle lies below it, at smaller
// GL y, i.e. lower on the screen). A centre on a vertex is drawn only if both
// edges through it qualify. Equivalently: sample at (x + e, y - e*e) for an
// infinitesimal e > 0. The scan converter implements it exactly with integer
// arithmetic: row j is walked if y_min < j + 0.5 <= y_max, and on it the
// pixels i with x_left <= i + 0.5 < x_right, the edge crossings being tracked
// as exact quotient-and-remainder (DDA) from the 9.4 vertices.
//
// Guards. Zero-area triangles draw nothing. Spans are clipped to the screen
// and the scissor box, so a triangle partly off screen is drawn only where it
// is on screen. Triangles with a vertex beyond +-(2^14 - 1) in 9.4 (about
// 1024 pixels, where the 32-bit edge and area bounds of planes.h
// end) are skipped; the front end keeps vertices in [0, 512] pixels.
//
// Arithmetic (written for the ARM922T: no FPU, no divide instruction). The
// scan conversion, the planes' set-up and every per-span and per-pixel step
// are 32-bit integer fixed point with 32x32->64 products, 64-bit adds and
// shifts; no double precision, no 64-bit division, no 128-bit product.
// Single precision only where the vertex's own values are floats (its 1/w,
// s, t, fog coordinate and unsnapped window position): a few operations per
// vertex turn them into the fixed-point vertex values. Each plane is the
// vertex 0 value plus the differences to vertices 1 and 2 times the
// barycentric weights of a span's first pixel (2.30, from the edge
// functions and a 30-bit reciprocal of the area: one 32-bit division per
// triangle); its step per pixel is the x gradient rounded to nearest. The
// perspective divide takes one reciprocal of q per shaded pixel (one 32-bit
// division, a Newton step and an exact correction) and multiplies. The
// level of detail is log2 by a 257-entry table in 16.16. The bounds behind
// every format are written beside the code (planes.h, triangle_setup.cpp,
// renderers/common/fixed_math.h) and tested at the largest screen (512 x
// 512), with vertices at the coordinate limit, slivers and degenerate
// triangles (tests/sw_driver/renderers/arm/).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/pixel_format.h"
#include "gl/renderer.h"
#include "renderers/arm/pixel_memory.h"

namespace tessera::arm {

struct DrawContext;    // per-draw decisions and what they cost the host (draw_context.h)
struct TriangleSetup;  // per-triangle attribute planes (triangle_setup.h)

// Where the buffers are and what they look like.
struct FrameBuffers {
  unsigned width = 0, height = 0;
  PixelFormat color_format = PixelFormat::rgb565;
  uint32_t color_address = 0;
  uint32_t depth_address = 0;
  uint32_t stencil_address = 0;
};

class ArmRasterizer {
 public:
  ArmRasterizer(PixelMemory& memory, const FrameBuffers& buffers);

  const FrameBuffers& buffers() const { return m_buffers; }
  unsigned width() const { return m_buffers.width; }
  unsigned height() const { return m_buffers.height; }
  // Double buffering: the caller moves drawing to the other colour buffer.
  void set_color_address(uint32_t address) { m_buffers.color_address = address; }
  uint32_t color_address() const { return m_buffers.color_address; }

  void clear(const gl::ClearRequest& request);
  void draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count);
  // As gl::Renderer::read_pixels: RGBA8, rows from y upwards, width * height
  // * 4 bytes. Pixels outside the screen read as 0.
  void read_pixels(int x, int y, int width, int height, uint8_t* rgba);

 private:
  // The stages, as the raster core's: the triangle's set-up and scan
  // conversion (draw_triangle), each span's shading (shade_span:
  // span_shading.h), its stores (store_span, write_color_run:
  // fragment_operations.cpp).
  void draw_triangle(const DrawContext& context, const gl::Triangle& triangle);
  void shade_span(const DrawContext& context, const TriangleSetup& setup, int j, int x_first, int x_last);
  void store_span(const DrawContext& context, uint32_t row_offset, int x_first, int n, uint32_t passed);
  void write_color_run(const DrawContext& context, uint32_t row_offset, int x_begin, int begin, int end);

  PixelMemory& m_memory;
  FrameBuffers m_buffers;
  // Per-span scratch, sized to the width once so that nothing is allocated
  // while drawing.
  std::vector<uint16_t> m_depth_old, m_depth_new;
  std::vector<uint8_t> m_stencil_old, m_stencil_new, m_pass;
  std::vector<uint32_t> m_source;  // RGBA8 as r | g << 8 | b << 16 | a << 24
};

}  // namespace tessera::arm
