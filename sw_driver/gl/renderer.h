// The interface between the GL front end and the renderer back ends (arm,
// raster, ap-tile, ap-pixel). The front end hands over triangles that are
// already lit, clipped, projected, culled and in the rasterizer's interface
// formats; each back end turns them into pixels its own way, so the same
// application runs on every renderer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "common/fixed_function.h"
#include "common/pixel_format.h"

namespace tessera::gl {

// The most texture units the front end and the back ends hold state for.
// How many a context offers (GL_MAX_TEXTURE_UNITS) is the configuration's
// driver.texture_units, from 1 to this (the ES 1.1 minimum is 2).
inline constexpr unsigned MAX_TEXTURE_UNITS = 4;
inline constexpr unsigned DEFAULT_TEXTURE_UNITS = 2;

struct TexCoord {
  float s = 0, t = 0;
};

// A vertex in window coordinates. Pixel (i, j) covers [i, i+1) x [j, j+1)
// with its centre at (i + 0.5, j + 0.5); j = 0 is the BOTTOM row, as in GL.
struct ScreenVertex {
  int32_t x, y;        // 9.4 fixed point
  uint32_t z;          // 0.24 fixed point, 0 = near
  float inv_w;         // 1 / w_clip, for perspective-correct texture coordinates
  uint8_t r, g, b, a;  // 0.8
  // Per texture unit, after the unit's texture matrix; not divided by w.
  // Units that are not enabled carry zeros.
  TexCoord tex[MAX_TEXTURE_UNITS];
  // The fog coordinate: the eye distance |z_eye| (Mesa's default, the eye
  // plane's absolute value), 0 when fog is off. Back ends interpolate it
  // (as the fog argument of renderers/common/fog.h) perspective-correctly.
  float fog;
  // The window position before snapping to 9.4 (pixels), for attribute
  // planes that follow the unsnapped triangle as the reference's do; NaN
  // when unknown.
  float x_window = std::numeric_limits<float>::quiet_NaN(), y_window = std::numeric_limits<float>::quiet_NaN();
};

// Either winding; v[2] is the provoking vertex for flat shading.
struct Triangle {
  ScreenVertex v[3];
};

// The fixed-function state in the hardware codes of
// common/fixed_function.def, the numbers every back end and the rasterizer's
// state blocks take; the GL front end converts GL enums with that table.
using tessera::BlendFactor;
using tessera::CompareFunc;
using tessera::FogMode;
using tessera::LogicOp;
using tessera::StencilOp;
using tessera::TexEnv;
using tessera::TexFilter;
using tessera::TexWrap;

// How a minification filter chooses mipmap levels: none (GL_NEAREST,
// GL_LINEAR: level 0 only), the nearest level (*_MIPMAP_NEAREST) or a blend
// of the two nearest (*_MIPMAP_LINEAR). Not a hardware code: the raster
// driver writes it as the TexMipmap code of a texture unit state.
enum class MipmapFilter : uint8_t { none, nearest, linear };

// One mipmap level: RGBA8 texels in system memory, row t = 0 first.
struct TextureLevel {
  uint32_t address = 0;
  unsigned width = 0, height = 0;
};

// Levels of a 256 x 256 texture: 256, 128, ..., 1.
inline constexpr unsigned MAX_TEXTURE_LEVELS = 9;

// A texture as the back ends see it: RGBA8 texels in system memory, row
// t = 0 first, power-of-two sizes from 1 to 256. address, width and height
// are level 0's; a mipmapped texture (min_mipmap != none) is complete and
// carries its whole chain in level[0 .. levels - 1], each level half the
// size of the one before (at least 1), down to 1 x 1.
struct Texture {
  uint32_t address = 0;
  unsigned width = 0, height = 0;
  TexFilter min_filter = TexFilter::nearest;  // the filter within a level
  TexFilter mag_filter = TexFilter::linear;
  TexWrap wrap_s = TexWrap::repeat, wrap_t = TexWrap::repeat;
  MipmapFilter min_mipmap = MipmapFilter::none;  // a texture object starts with GL_NEAREST_MIPMAP_LINEAR
  // The base format's components: RGB and LUMINANCE have no alpha, ALPHA no
  // colour. The texels hold them expanded (0 colour, 255 alpha), which is
  // what GL_COMBINE takes; GL_MODULATE and GL_REPLACE take the fragment's
  // instead (table 3.15, renderers/common/texturing.h: fill_missing_components).
  bool has_color = true, has_alpha = true;
  unsigned levels = 1;
  TextureLevel level[MAX_TEXTURE_LEVELS];
};

// The texture environment of a unit (glTexEnv GL_TEXTURE_ENV_MODE) and the
// GL_COMBINE function, its argument sources and operands (ES 1.1, section
// 3.7.12, tables 3.17 and 3.18): the hardware codes of
// common/fixed_function.def, one encoding for the front end, the software
// back ends and the rasterizer's texture unit states.
using TexEnvMode = tessera::TexEnv;
using tessera::CombineFunc;
using tessera::CombineOperand;
using tessera::CombineSource;
using tessera::TexBaseFormat;

// One half (RGB or alpha) of a unit's combiner. The defaults are GL's.
struct CombineStage {
  CombineFunc func = CombineFunc::modulate;
  CombineSource source[3] = {CombineSource::texture, CombineSource::previous, CombineSource::constant};
  CombineOperand operand[3] = {CombineOperand::src_color, CombineOperand::src_color, CombineOperand::src_alpha};
  uint8_t scale = 1;  // 1, 2 or 4
};

// One texture unit as the back ends see it: drawn only if `enabled` (the
// unit's GL_TEXTURE_2D is on and its texture is complete). Units are
// applied in order, each to the previous one's result.
struct TextureUnit {
  bool enabled = false;
  Texture tex;
  TexEnvMode env = TexEnvMode::modulate;
  uint8_t env_color[4] = {0, 0, 0, 0};  // GL_TEXTURE_ENV_COLOR, 0.8
  CombineStage combine_rgb;
  CombineStage combine_alpha{CombineFunc::modulate,
                             {CombineSource::texture, CombineSource::previous, CombineSource::constant},
                             {CombineOperand::src_alpha, CombineOperand::src_alpha, CombineOperand::src_alpha},
                             1};
};

// Whether `env` is one of the environments the rasterizer's StateBlock
// carries (REPLACE, MODULATE, DECAL: its 2-bit field); *code is `env`.
inline bool hardware_tex_env(TexEnvMode env, TexEnv* code) {
  switch (env) {
    case TexEnv::modulate:
    case TexEnv::replace:
    case TexEnv::decal: *code = env; return true;
    default: return false;
  }
}

// The base format code (table 3.15) of `tex`'s components: LUMINANCE
// follows RGB's rules and LUMINANCE_ALPHA RGBA's, so the components decide.
inline TexBaseFormat tex_base_format(const Texture& tex) {
  if (!tex.has_color) return TexBaseFormat::alpha;
  return tex.has_alpha ? TexBaseFormat::rgba : TexBaseFormat::rgb;
}

struct RasterState {
  bool flat_shading = false;
  bool depth_test = false;
  CompareFunc depth_func = CompareFunc::less;
  bool depth_write = true;
  bool alpha_test = false;
  CompareFunc alpha_func = CompareFunc::always;
  uint8_t alpha_ref = 0;
  bool stencil_test = false;
  CompareFunc stencil_func = CompareFunc::always;
  uint8_t stencil_ref = 0, stencil_value_mask = 0xff, stencil_write_mask = 0xff;
  StencilOp stencil_fail = StencilOp::keep, depth_fail = StencilOp::keep, depth_pass = StencilOp::keep;
  bool blend = false;
  BlendFactor blend_src = BlendFactor::one, blend_dst = BlendFactor::zero;
  bool logic_op = false;
  LogicOp logic_op_mode = LogicOp::copy;
  bool color_mask[4] = {true, true, true, true};
  bool scissor_test = false;
  int scissor_x = 0, scissor_y = 0, scissor_width = 0, scissor_height = 0;
  // Texture units 0 .. MAX_TEXTURE_UNITS - 1; those beyond the context's
  // driver.texture_units are never enabled.
  TextureUnit unit[MAX_TEXTURE_UNITS];
  bool polygon_smooth = false;  // antialiased edges (rasterizers that support it)
  // Fog (glFog), applied after texturing: factor from the vertices'
  // ScreenVertex::fog by renderers/common/fog.h; colour in 0.8, alpha unused.
  bool fog = false;
  FogMode fog_mode = FogMode::exp;
  float fog_density = 1, fog_start = 0, fog_end = 1;
  uint8_t fog_color[4] = {0, 0, 0, 0};
};

struct ClearRequest {
  bool color = false, depth = false, stencil = false;
  uint8_t rgba[4] = {0, 0, 0, 0};
  uint32_t depth_value = 0xffffff;  // 0.24
  uint8_t stencil_value = 0;
  bool color_mask[4] = {true, true, true, true};
  bool depth_write = true;
  uint8_t stencil_write_mask = 0xff;
  bool scissor_test = false;
  int scissor_x = 0, scissor_y = 0, scissor_width = 0, scissor_height = 0;
};

// What a back end's buffers hold. EGL offers configurations before any
// surface (and so any renderer) exists, so the back-end table states them
// (sw_driver/renderers/backends.def) and the launcher hands them over with
// the factory (AppEnvironment::capabilities).
struct RendererCapabilities {
  unsigned depth_bits = 0;
  unsigned stencil_bits = 0;
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual const char* name() const = 0;
  virtual RendererCapabilities capabilities() const = 0;
  virtual unsigned width() const = 0;
  virtual unsigned height() const = 0;
  // The colour buffer's format (the display's).
  virtual PixelFormat color_format() const = 0;
  virtual void clear(const ClearRequest& request) = 0;
  virtual void draw(const RasterState& state, const Triangle* triangles, size_t count) = 0;
  // RGBA8, rows from y upwards (GL order), w * h * 4 bytes.
  virtual void read_pixels(int x, int y, int width, int height, uint8_t* rgba) = 0;
  // Completes all drawing (glFinish).
  virtual void finish() = 0;
  // Shows the frame and moves drawing to the next buffer (eglSwapBuffers).
  virtual void present() = 0;
};

}  // namespace tessera::gl
