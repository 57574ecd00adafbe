// The arm renderer's per-draw decisions (draw_context.h).
#include "renderers/arm/draw_context.h"

#include <algorithm>

#include "renderers/common/fragment_ops.h"

namespace tessera::arm {

namespace {

using gl::BlendFactor;
using gl::StencilOp;
using renderers::factor_reads_destination;
using renderers::logic_op_reads_destination;

// How many arguments a GL_COMBINE function reads (ES 1.1 table 3.18).
unsigned combine_arguments(gl::CombineFunc func) {
  switch (func) {
    case gl::CombineFunc::replace: return 1;
    case gl::CombineFunc::interpolate: return 3;
    default: return 2;
  }
}

}  // namespace

bool make_draw_context(const gl::RasterState& state, const FrameBuffers& buffers, DrawContext& c) {
  c.state = &state;
  c.clip_x0 = 0;
  c.clip_y0 = 0;
  c.clip_x1 = int(buffers.width) - 1;
  c.clip_y1 = int(buffers.height) - 1;
  if (state.scissor_test) {
    c.clip_x0 = std::max(c.clip_x0, state.scissor_x);
    c.clip_y0 = std::max(c.clip_y0, state.scissor_y);
    c.clip_x1 = int(std::min<int64_t>(c.clip_x1, int64_t(state.scissor_x) + state.scissor_width - 1));
    c.clip_y1 = int(std::min<int64_t>(c.clip_y1, int64_t(state.scissor_y) + state.scissor_height - 1));
  }
  if (c.clip_x0 > c.clip_x1 || c.clip_y0 > c.clip_y1) return false;

  const PixelFormat format = buffers.color_format;
  c.depth_test = state.depth_test;
  c.depth_write = state.depth_test && state.depth_write;
  c.stencil_test = state.stencil_test;
  c.stencil_writes = state.stencil_test && state.stencil_write_mask != 0 &&
                     (state.stencil_fail != StencilOp::keep || state.depth_fail != StencilOp::keep ||
                      state.depth_pass != StencilOp::keep);
  c.alpha_test = state.alpha_test;
  c.late_tests = state.alpha_test;
  c.gouraud = !state.flat_shading;
  c.fog = state.fog;
  if (c.fog) {
    c.fog_coefficients = renderers::fog_coefficients_f(state);
    c.fog_rgba = renderers::fog_rgba(state);
  }
  for (unsigned u = 0; u < gl::MAX_TEXTURE_UNITS; ++u) {
    const gl::TextureUnit& unit = state.unit[u];
    const gl::Texture& tex = unit.tex;
    if (unit.enabled && tex.width > 0 && tex.height > 0 && (tex.width & (tex.width - 1)) == 0 &&
        (tex.height & (tex.height - 1)) == 0)
      c.units[c.unit_count++] = u;
  }
  c.texture = c.unit_count != 0;
  unsigned color_mask = 0;
  for (unsigned ch = 0; ch < 4; ++ch) color_mask |= state.color_mask[ch] ? 1u << ch : 0u;
  c.color_write_mask = channel_bits(format, color_mask);
  const uint32_t all_color = channel_bits(format, 0xf);
  c.color_write = c.color_write_mask != 0;
  c.logic_op = state.logic_op;
  c.blend =
      state.blend && !state.logic_op && !(state.blend_src == BlendFactor::one && state.blend_dst == BlendFactor::zero);
  c.needs_destination =
      c.color_write &&
      ((c.blend && (state.blend_dst != BlendFactor::zero || factor_reads_destination(state.blend_src))) ||
       (c.logic_op && logic_op_reads_destination(state.logic_op_mode)) || c.color_write_mask != all_color);

  // A texture takes s/w, t/w and 1/w; each further unit its own s/w, t/w.
  c.attributes =
      (c.depth_test ? 1 : 0) + (c.gouraud ? 4 : 0) + (c.texture ? 1 + 2 * c.unit_count : 0) + (c.fog ? 1 : 0);
  for (unsigned i = 0; i < c.unit_count; ++i) {
    const gl::TextureUnit& unit = state.unit[c.units[i]];
    const gl::TexEnvMode env = unit.env;
    if (env == gl::TexEnvMode::combine) {
      ++c.combines;
      c.combine_arguments += combine_arguments(unit.combine_rgb.func);
      if (unit.combine_rgb.func != gl::CombineFunc::dot3_rgba)
        c.combine_arguments += combine_arguments(unit.combine_alpha.func);
    } else if (env != gl::TexEnvMode::replace) {
      ++c.environments;
    }
  }
  c.reads_destination = c.color_write && (c.needs_destination || c.blend || c.logic_op);
  return true;
}

}  // namespace tessera::arm
