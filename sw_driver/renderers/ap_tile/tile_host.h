// The host's side of a frame that does not depend on how the array is
// reached, shared by ApTileRenderer (the array over the bus) and the speed
// benchmark's native renderer (bench/bench_ap_tile_native.cpp: tile_reference
// on CMEM images in memory): the records' flags a draw's GL state gives, the
// frame's texture numbers, the binning into per-CU queues run in passes, and
// the texturing of a pixel read back. Plain C++.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/pixel_format.h"
#include "gl/renderer.h"
#include "renderers/ap_tile/tile_setup.h"
#include "renderers/common/texturing.h"

namespace tessera::ap_tile {

// Reports state the algorithm does not have ("blending (GL_BLEND): drawn
// without it").
using Unsupported = std::function<void(const std::string& what)>;

// A texture of the frame and the environment it was drawn with.
struct TextureEntry {
  gl::Texture texture;
  gl::TexEnv env = gl::TexEnv::modulate;
};

// The textures drawn since the last colour clear, numbered 1..255 as the
// CMEM's `tid` plane holds them (0: untextured).
class TextureTable {
 public:
  // The number of a texture and environment, added if new.
  uint8_t number(const gl::Texture& tex, gl::TexEnv env, const Unsupported& unsupported);
  // The entry numbered `number`, or nullptr.
  const TextureEntry* find(unsigned number) const {
    return number != 0 && number <= m_entries.size() ? &m_entries[number - 1] : nullptr;
  }
  void clear() { m_entries.clear(); }

 private:
  std::vector<TextureEntry> m_entries;
};

// What the scissor test leaves of a `width` x `height` frame: all of it
// (test off, or a box covering the frame), none (a box of zero width or
// height, or one wholly outside the frame: GL draws and clears nothing), or
// a part, which the algorithm cannot draw exactly (no per-pixel scissor in
// the CUs' program).
enum class ScissorCover { whole, none, part };
ScissorCover scissor_cover(bool test, int x, int y, int box_width, int box_height, unsigned width, unsigned height);

// The records' flags for a draw with `state` on a `width` x `height` frame,
// reporting the state the algorithm does not have; nullopt when the draw
// draws nothing (GL_NEVER, an empty scissor box). A texture the CU's 8.8
// coordinates can wrap (a power of two, at most 256 texels a side) gets its
// number from `textures`.
std::optional<DrawFlags> draw_flags(const gl::RasterState& state, unsigned width, unsigned height,
                                    TextureTable& textures, const Unsupported& unsupported);

// The triangles of a flush, binned: per CU the triangles that reach its
// tile, in order. Pass p gives every CU the p-th triangle of its queue, so
// the order per tile is kept and the passes are the triangles of the
// busiest CU.
class TileBins {
 public:
  explicit TileBins(unsigned cus) : m_queues(cus) {}

  // Adds `setup`, which reaches the tiles (CU indices) `tiles`.
  void add(const TriangleSetup& setup, const std::vector<unsigned>& tiles);
  // The passes the flush needs: the longest queue.
  size_t passes() const;
  // CU `cu`'s triangle in pass `pass`, or nullptr (the CU has none).
  const TriangleSetup* at(unsigned cu, size_t pass) const {
    const std::vector<uint32_t>& queue = m_queues[cu];
    return pass < queue.size() ? &m_triangles[queue[pass]] : nullptr;
  }
  void clear();

 private:
  std::vector<TriangleSetup> m_triangles;       // in the order drawn
  std::vector<std::vector<uint32_t>> m_queues;  // per CU: its triangles
};

// A pixel read back: `rgba` (its RGB565 colour, unpacked) textured by
// `entry` at s, t (texels, 8.8, as the CMEM holds them) with the texture's
// magnification filter (the CU does not know the footprint) and its
// environment. fetch(address) returns the texel at `address` in system
// memory (four bytes, RGBA).
template <class Fetch>
uint32_t texture_pixel(const TextureEntry& entry, uint32_t rgba, int16_t s, int16_t t, Fetch&& fetch) {
  const gl::Texture& tex = entry.texture;
  auto texel_at = [&](int ti, int tj, uint8_t out[4]) { copy_word(fetch(renderers::texel_address(tex, ti, tj)), out); };
  uint8_t texel[4];
  renderers::sample_texture(tex, s, t, texel_at, texel);
  return renderers::apply_tex_env(entry.env, rgba, texel);
}

// glReadPixels from a frame read back out of the array (`frame`: RGBA,
// row 0 at the top, `width` x `height`): the rectangle (x, y, w, h) in GL
// rows (0 at the bottom), each pixel as the display's `format` holds it,
// 0 outside the frame.
inline void read_frame_pixels(const std::vector<uint32_t>& frame, unsigned width, unsigned height, PixelFormat format,
                              int x, int y, int w, int h, uint8_t* rgba) {
  const int fw = static_cast<int>(width), fh = static_cast<int>(height);
  for (int row = 0; row < h; ++row)
    for (int column = 0; column < w; ++column) {
      const int gx = x + column, gy = y + row;
      uint32_t value = 0;
      if (gx >= 0 && gx < fw && gy >= 0 && gy < fh)
        value = quantize_color(format, frame[static_cast<size_t>(fh - 1 - gy) * fw + gx]);
      std::memcpy(rgba + (static_cast<size_t>(row) * w + column) * 4, &value, 4);
    }
}

}  // namespace tessera::ap_tile
