// ap.tile.texture_warp=array (README.md, "Textures warped on the array"):
// a planar textured primitive's texture mapped onto the frame by the
// two-pass forward texture mapping (forward_texture/), so that the host
// reads its pixels' texels from the warped image instead of looking them up
// at the interpolated s and t. Plain C++ (floats for the plane, no double),
// shared by the renderer and the tests.
//
//   draw:      TexturePlane of each textured triangle (texture_plane), kept
//              per texture number while the triangles agree (WarpPlan::add)
//   read-back: WarpPlan::job -> WarpJob: the texture region around the
//              triangles' texels, upscaled until no texel covers more than
//              a pixel, and the fixed-point matrix of that region
//              WarpJob::run: one warp per colour channel (warp_texture with
//              the caller's LineResampler) -> WarpedTexture
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "forward_texture/filter.h"
#include "forward_texture/warp.h"
#include "gl/renderer.h"

namespace tessera::ap_tile {

// The projective map of a textured plane from texel coordinates (u = s x
// width, v = t x height of the base level) to window coordinates (x, y; y
// up, pixel (p, q) covering [p, p+1) x [q, q+1), the warp's own output
// grid): (x w, y w, w) = m (u, v, 1), w = the clip w, row-major.
struct TexturePlane {
  std::array<float, 9> m{};
  // The window point of texel point (u, v); false behind the eye (w <= 0).
  bool map(float u, float v, float& x, float& y) const;
};

// The plane through a triangle's three vertices (texture unit 0), or
// nullopt when its texture coordinates are collinear or a vertex has no
// positive w.
std::optional<TexturePlane> texture_plane(const gl::Triangle& triangle, const gl::Texture& texture);

// Within a quarter of a pixel (the vertices are snapped to 1/16 pixel):
// `triangle` lies on `plane` with its texture coordinates.
bool on_plane(const TexturePlane& plane, const gl::Triangle& triangle, const gl::Texture& texture);

// The texels a warp maps: [u0, u0 + width) x [v0, v0 + height) of the base
// level (wrapped or clamped as the texture's wrap modes say), in `bands`
// (one: the base texels, each made `upscale` x `upscale` texels of the
// warp's texture; more: cut across the longer side, each at its own level
// and upscale, the largest upscale here).
struct WarpRegion {
  int u0 = 0, v0 = 0, width = 0, height = 0, upscale = 1, bands = 0;
};

// A band of a region in texels of its level: [u0, u0 + width) x [v0, v0 +
// height), each made `upscale` x `upscale` texels of the warp's texture,
// and its matrix.
struct WarpBand {
  int u0 = 0, v0 = 0, width = 0, height = 0, level = 0, upscale = 1;
  forward_texture::PerspectiveMatrix matrix;
};

// The warped colour channels of a texture, each the frame's size, row 0 at
// the bottom (GL's window rows).
struct WarpedTexture {
  std::array<forward_texture::Image, 3> channels;
  WarpRegion region;
  forward_texture::PassOrder order = forward_texture::PassOrder::rows_first;
  uint64_t lines = 0, borders = 0;  // both passes' lines and texel borders, every channel
  // The texel (RGBA, alpha 255: the colour buffer has no alpha) at window
  // pixel (x, y).
  void texel(int x, int y, uint8_t out[4]) const;
};

// A texture's warp: its region, the region's matrix in the warp's fixed
// point, and the filter.
class WarpJob {
 public:
  explicit WarpJob(forward_texture::FilterTable table) : m_table(std::move(table)) {}
  // Empty, or why this texture's triangles cannot be warped (the region
  // beyond the program's texels a line at every level, the plane behind
  // the eye at a band's corners, a singular or out-of-range matrix). A
  // region whose lines do not fit at the base level is cut into bands.
  std::string prepare(const TexturePlane& plane, const gl::Texture& texture, float u_min, float u_max, float v_min,
                      float v_max, int frame_width, int frame_height, int max_texels);
  // source(level, i, j, out) gives texel (i, j) of `level`, wrapped or
  // clamped at that level's size, and true; or false when the texture has
  // no such level (level 0 it always has): the job then averages the base
  // texels under it.
  using TexelSource = std::function<bool(int level, int i, int j, uint8_t out[4])>;
  // Warps the three channels of every band with `resampler` (nullptr: on
  // the host) and adds the bands up. A band's warp refused for
  // magnification is retried at twice its upscale while its lines fit;
  // `texels_loaded` counts the texels fetched.
  std::string run(const TexelSource& source, forward_texture::LineResampler* resampler, WarpedTexture& out,
                  uint64_t& texels_loaded);
  const WarpRegion& region() const { return m_region; }

  const std::vector<WarpBand>& bands() const { return m_bands; }

 private:
  std::string fit_band(WarpBand& band) const;
  std::string cut_bands();
  std::string band_matrix(WarpBand& band) const;
  std::vector<uint8_t> band_texels(const WarpBand& band, const TexelSource& source, uint64_t& texels_loaded) const;

  TexturePlane m_plane;
  forward_texture::FilterTable m_table;
  WarpRegion m_region;
  std::vector<WarpBand> m_bands;
  int m_top_level = 0;
  int m_frame_width = 0, m_frame_height = 0, m_max_texels = 0;
};

// Base-level texel (i, j) of `texture` wrapped or clamped by its wrap modes.
int wrap_texel(int i, int size, gl::TexWrap wrap);

// The filter the warp uses: the box of width `width` (the J2210 program's).
forward_texture::FilterTable warp_filter(int width);

// The draws of a frame, per texture number: the plane of its first
// triangle and the texel bounds of all, or the reason its triangles cannot
// be warped as one plane.
class WarpPlan {
 public:
  void add(unsigned tid, const gl::Triangle& triangle, const gl::Texture& texture);
  // Texture number `tid` has one plane (so far): its pixels take the warp.
  bool warped(unsigned tid) const;
  // Why texture `tid` is drawn with texel lookups ("" when it is warped).
  const std::string& reason(unsigned tid) const;
  // Prepares `tid`'s job; empty or the reason, which then also marks it.
  std::string job(unsigned tid, const gl::Texture& texture, int frame_width, int frame_height, int max_texels,
                  WarpJob& job);
  void refuse(unsigned tid, const std::string& why);
  void clear() { m_entries.clear(); }

 private:
  struct Entry {
    bool used = false;
    std::string refused;  // not empty: texel lookups
    TexturePlane plane;
    float u_min = 0, u_max = 0, v_min = 0, v_max = 0;
  };
  std::vector<Entry> m_entries;  // indexed by texture number
  std::string m_none;
};

}  // namespace tessera::ap_tile
