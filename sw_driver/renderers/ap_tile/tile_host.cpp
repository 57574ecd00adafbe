#include "renderers/ap_tile/tile_host.h"

#include <algorithm>

#include "renderers/common/texture_units.h"

namespace tessera::ap_tile {

uint8_t TextureTable::number(const gl::Texture& tex, gl::TexEnv env, const Unsupported& unsupported) {
  for (size_t k = 0; k < m_entries.size(); ++k) {
    const gl::Texture& t = m_entries[k].texture;
    if (t.address == tex.address && t.width == tex.width && t.height == tex.height && t.min_filter == tex.min_filter &&
        t.mag_filter == tex.mag_filter && t.wrap_s == tex.wrap_s && t.wrap_t == tex.wrap_t && m_entries[k].env == env)
      return static_cast<uint8_t>(k + 1);
  }
  if (m_entries.size() == 255) {
    unsupported("more than 255 textures between colour clears (the last one is reused)");
    return 255;
  }
  m_entries.push_back({tex, env});
  return static_cast<uint8_t>(m_entries.size());
}

ScissorCover scissor_cover(bool test, int x, int y, int box_width, int box_height, unsigned width, unsigned height) {
  if (!test) return ScissorCover::whole;
  const int64_t x0 = std::max<int64_t>(x, 0), y0 = std::max<int64_t>(y, 0);
  const int64_t x1 = std::min<int64_t>(int64_t{x} + box_width, width);
  const int64_t y1 = std::min<int64_t>(int64_t{y} + box_height, height);
  if (x1 <= x0 || y1 <= y0) return ScissorCover::none;
  return x0 == 0 && y0 == 0 && x1 == width && y1 == height ? ScissorCover::whole : ScissorCover::part;
}

std::optional<DrawFlags> draw_flags(const gl::RasterState& state, unsigned width, unsigned height,
                                    TextureTable& textures, const Unsupported& unsupported) {
  switch (scissor_cover(state.scissor_test, state.scissor_x, state.scissor_y, state.scissor_width, state.scissor_height,
                        width, height)) {
    case ScissorCover::none: return std::nullopt;
    case ScissorCover::part:
      unsupported("the scissor test (GL_SCISSOR_TEST) with a box smaller than the frame: drawn without it");
      break;
    case ScissorCover::whole: break;
  }
  if (state.blend) unsupported("blending (GL_BLEND): drawn without it");
  if (state.alpha_test) unsupported("the alpha test (GL_ALPHA_TEST): drawn without it");
  if (state.stencil_test) unsupported("the stencil test (GL_STENCIL_TEST): there is no stencil buffer");
  if (state.logic_op) unsupported("logic ops (GL_COLOR_LOGIC_OP): drawn without it");
  if (state.fog) unsupported("fog (GL_FOG): drawn without it");
  if (!state.color_mask[0] || !state.color_mask[1] || !state.color_mask[2])
    unsupported("colour masks (glColorMask): drawn with every channel");
  DrawFlags flags;
  flags.flat = state.flat_shading;
  flags.depth_test = state.depth_test;
  flags.depth_write = state.depth_write;
  if (state.depth_test) {
    switch (state.depth_func) {
      case gl::CompareFunc::less: break;
      case gl::CompareFunc::lequal: flags.depth_lequal = true; break;
      case gl::CompareFunc::never: return std::nullopt;
      case gl::CompareFunc::always:
        flags.depth_test = false;
        if (state.depth_write) unsupported("depth writes with GL_ALWAYS: the depth buffer keeps its values");
        break;
      default: unsupported("depth functions other than GL_LESS, GL_LEQUAL, GL_ALWAYS and GL_NEVER: drawn as GL_LESS");
    }
  }
  const renderers::SingleTextureUnit unit = renderers::single_texture_unit(state, unsupported);
  const gl::Texture tex = unit.index >= 0 ? state.unit[unit.index].tex : gl::Texture{};
  if (unit.index >= 0 && tex.width > 0 && tex.height > 0 && tex.width <= 256 && tex.height <= 256 &&
      (tex.width & (tex.width - 1)) == 0 && (tex.height & (tex.height - 1)) == 0) {
    if (renderers::texture_needs_lod(tex))
      unsupported(
          "mipmaps and a minification filter other than the magnification filter (GL_TEXTURE_MIN_FILTER): level 0 "
          "sampled with the magnification filter");
    if (renderers::env_needs_base_format(tex, unit.env))
      unsupported(
          "textures without alpha under GL_REPLACE and GL_ALPHA textures under GL_MODULATE or GL_REPLACE (ES 1.1 table "
          "3.15): drawn with the texel expanded to RGBA");
    flags.tex = textures.number(tex, unit.env, unsupported);
    flags.tex_width = tex.width;
    flags.tex_height = tex.height;
    flags.tex_unit = static_cast<uint8_t>(unit.index);
  }
  return flags;
}

void TileBins::add(const TriangleSetup& setup, const std::vector<unsigned>& tiles) {
  const auto index = static_cast<uint32_t>(m_triangles.size());
  m_triangles.push_back(setup);
  for (unsigned tile : tiles) m_queues[tile].push_back(index);
}

size_t TileBins::passes() const {
  size_t passes = 0;
  for (const auto& queue : m_queues) passes = std::max(passes, queue.size());
  return passes;
}

void TileBins::clear() {
  m_triangles.clear();
  for (auto& queue : m_queues) queue.clear();
}

}  // namespace tessera::ap_tile
