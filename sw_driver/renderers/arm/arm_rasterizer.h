// The functional core of the `arm` renderer: the study's sequential software
// rasterizer for the ARM host (fixed-point scan conversion with incremental
// edge and attribute stepping). Plain C++: it reaches its buffers and
// textures only through PixelMemory, which either counts (native) or charges
// (host model) the accesses it declares, and it charges its instructions with
// PixelMemory::compute using the per-pixel and per-span counts listed in
// README.md.
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
// 1024 pixels, where the 32-bit edge and area bounds of arm_rasterizer.cpp
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
// every format are written beside the code (arm_rasterizer.cpp,
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

// ARM922T instructions the core charges, by where they are executed. The
// defaults are the counts of a hand-scheduled ARM implementation, justified
// in README.md; every count is in instructions of its Op class (a taken
// branch is one Op::branch, a software division one Op::call plus
// `division_alu` Op::alu).
struct InstructionCounts {
  // Per triangle: sorting, area, edge set-up, the gradient divisions.
  unsigned triangle_alu = 70, triangle_mul = 10, triangle_branch = 8, triangle_divisions = 4;
  unsigned division_alu = 20;
  unsigned attribute_setup_alu = 8, attribute_setup_mul = 4;   // per interpolated attribute
  unsigned texture_vertex_fconv = 3, texture_vertex_fmul = 4;  // per vertex, soft float -> fixed
  // Per scanline walked: two edge DDAs, the span clip, the loop.
  unsigned row_alu = 12, row_branch = 1;
  // Per non-empty span: buffer addresses, loop entry, and per attribute the
  // start value and the range check.
  unsigned span_alu = 8, span_mul = 1, span_branch = 2;
  unsigned span_attribute_alu = 4, span_attribute_mul = 3;
  // Per pixel of a span, whether it is drawn or not.
  unsigned pixel_alu = 1, pixel_branch = 1;  // SUBS, BNE
  unsigned depth_step_test_alu = 3, stencil_test_alu = 4, stencil_update_alu = 3;
  unsigned color_step_alu = 4;  // Gouraud only
  unsigned texcoord_step_alu_perspective = 6, texcoord_step_alu_affine = 4;
  unsigned texcoord_step_alu_unit = 2;  // each texture unit after the first: its s/w and t/w
  // Per shaded pixel.
  unsigned perspective_alu = 4, perspective_mul = 2;  // plus one division
  unsigned perspective_unit_mul = 2;                  // each further unit: s/w, t/w times the reciprocal
  unsigned texel_nearest_alu = 8, texel_nearest_mul = 1;
  unsigned texel_linear_alu = 30, texel_linear_mul = 9;
  // The level of detail: four derivatives of u/q and v/q (two products and a
  // difference each, over q squared), two sums of squares, the larger, and
  // log2 by CLZ and a 16-entry table of the mantissa; per pixel where 1/w
  // varies, once per triangle where it does not. A second mipmap level:
  // its texel fetch, plus the blend of the two colours.
  unsigned lod_alu = 30, lod_mul = 14, mipmap_blend_alu = 12, mipmap_blend_mul = 4;
  unsigned modulate_alu = 12, modulate_mul = 4, decal_alu = 12, decal_mul = 3;
  unsigned blend_env_alu = 16, blend_env_mul = 7, add_env_alu = 14, add_env_mul = 1;
  // GL_COMBINE, per unit: per argument (source select and operand), then
  // the function of the colour (three channels) and of the alpha half.
  unsigned combine_rgb_argument_alu = 4, combine_alpha_argument_alu = 2;
  unsigned combine_rgb_function_alu = 18, combine_rgb_function_mul = 6;
  unsigned combine_alpha_function_alu = 6, combine_alpha_function_mul = 2;
  unsigned combine_dot3_alu = 16, combine_dot3_mul = 3;
  unsigned alpha_test_alu = 2;
  // Fog (README.md, "Fog"): per vertex the fog argument from soft float, per
  // pixel its step, per shaded pixel its perspective product, the factor of
  // the mode and the blend of R, G, B with the fog colour.
  unsigned fog_vertex_fmul = 1, fog_vertex_fadd = 1, fog_vertex_fconv = 1;
  unsigned fog_step_alu = 1;
  unsigned fog_perspective_mul = 1;
  unsigned fog_linear_alu = 4, fog_linear_mul = 1;
  unsigned fog_exp_alu = 7, fog_exp_mul = 1, fog_exp_load_use = 1;
  unsigned fog_exp2_alu = 9, fog_exp2_mul = 2, fog_exp2_load_use = 1;
  unsigned fog_blend_alu = 13, fog_blend_mul = 6;
  // Per pixel written.
  unsigned depth_write_alu = 1;
  // Packing to RGB565 rounds each channel to nearest (common/pixel_format.h):
  // one multiply-accumulate and one shift per channel, then two ORRs.
  unsigned pack_rgb565_alu = 5, pack_rgb565_mul = 3, pack_rgba8888_alu = 3;
  unsigned unpack_rgb565_alu = 6, unpack_rgba8888_alu = 3;
  unsigned blend_factor_alu = 12, blend_factor_mul = 4, blend_combine_alu = 8;  // per factor other than ZERO/ONE
  unsigned logic_op_alu = 2, color_mask_alu = 3;
  // Clears and read-back.
  unsigned clear_block_alu = 1, clear_block_branch = 1;  // per 32 bytes (STM of 8 registers)
  unsigned clear_row_alu = 4, clear_masked_pixel_alu = 4;
  unsigned read_pixel_alu = 6;
};

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
  ArmRasterizer(PixelMemory& memory, const FrameBuffers& buffers, const InstructionCounts& counts = {});

  const FrameBuffers& buffers() const { return m_buffers; }
  const InstructionCounts& instruction_counts() const { return m_counts; }
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
  struct TriangleSetup;  // per-triangle attribute planes (arm_rasterizer.cpp)
  struct DrawContext;    // per-draw decisions and instruction counts (arm_rasterizer.cpp)

  void draw_triangle(const DrawContext& context, const gl::Triangle& triangle);
  void shade_span(const DrawContext& context, const TriangleSetup& setup, int j, int x_first, int x_last);
  // Nearest or bilinear texel of `tex`'s mipmap level `level` at that level's texel coordinates (u8, v8).
  void fetch_texel(const gl::Texture& tex, unsigned level, int u8, int v8, bool linear, uint8_t out[4]);
  void write_color_run(const DrawContext& context, uint32_t row_offset, int x_begin, int begin, int end);

  PixelMemory& m_memory;
  FrameBuffers m_buffers;
  InstructionCounts m_counts;
  // Per-span scratch, sized to the width once so that nothing is allocated
  // while drawing.
  std::vector<uint16_t> m_depth_old, m_depth_new;
  std::vector<uint8_t> m_stencil_old, m_stencil_new, m_pass;
  std::vector<uint32_t> m_source;  // RGBA8 as r | g << 8 | b << 16 | a << 24
};

}  // namespace tessera::arm
