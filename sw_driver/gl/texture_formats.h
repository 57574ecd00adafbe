// The texel formats glTexImage2D and glCompressedTexImage2D accept, and their
// conversion to the RGBA8 texels every back end samples (OpenGL ES 1.1
// section 3.6 for the external formats and packed types, section 3.8.1 for
// the conversion to RGBA; OES_compressed_paletted_texture for the ten
// paletted formats), and the box filter of GL_GENERATE_MIPMAP. Plain
// functions without a context, so that the unit tests check them directly.
#pragma once

#include <GLES/gl.h>

#include <cstddef>
#include <cstdint>

namespace tessera::gl {

// Bytes per pixel of an external format and type, 0 when either is not
// accepted or the pair does not go together.
unsigned pixel_bytes(GLenum format, GLenum type);

// The error glTexImage2D / glTexSubImage2D give for a format and type, 0 for
// an accepted pair: GL_INVALID_ENUM for a format or type that is not one of
// ES 1.1's, GL_INVALID_OPERATION for a packed type with the wrong format
// (5_6_5 needs GL_RGB, 4_4_4_4 and 5_5_5_1 need GL_RGBA).
GLenum format_type_error(GLenum format, GLenum type);

// One pixel of `format` / `type` at `in` (an accepted pair; a packed type is
// a 16-bit word in the host's byte order, as GL unpacks it) as RGBA8,
// r | g << 8 | b << 16 | a << 24. A component of n bits becomes
// round(c * 255 / (2^n - 1)); a missing colour is 0 (ALPHA) or the
// luminance, a missing alpha 255.
uint32_t unpack_pixel(GLenum format, GLenum type, const uint8_t* in);

// A paletted compressed format of OES_compressed_paletted_texture: indices
// of 4 or 8 bits into a palette of 16 or 256 entries, each entry a pixel of
// `entry_format` / `entry_type`.
struct PaletteFormat {
  GLenum name;
  unsigned index_bits;
  GLenum entry_format, entry_type;
};
inline constexpr unsigned PALETTE_FORMAT_COUNT = 10;
extern const PaletteFormat PALETTE_FORMATS[PALETTE_FORMAT_COUNT];
// nullptr for a name that is not one of the ten.
const PaletteFormat* find_palette_format(GLenum name);

// Bytes glCompressedTexImage2D expects for `levels` levels from width x
// height down: the palette, then each level's indices packed without row
// padding (two 4-bit indices a byte, the first in the high nibble).
size_t paletted_image_size(const PaletteFormat& format, unsigned width, unsigned height, unsigned levels);

// Level `level` (0-based) of a paletted image as RGBA8 words into `out`
// (max(1, width >> level) x max(1, height >> level), row t = 0 first).
void decode_paletted_level(const PaletteFormat& format, const uint8_t* data, unsigned width, unsigned height,
                           unsigned level, uint32_t* out);

// The next mipmap level of an RGBA8 image: each texel the average of the
// 2 x 2 (or 2 x 1 once one side is 1) texels it covers, per channel,
// rounded to nearest. Mesa's GL_GENERATE_MIPMAP on softpipe blits each level
// from the one before with a bilinear filter at the texel corners, which is
// the same average computed in float and rounded once when stored.
void box_filter_level(const uint32_t* in, unsigned width, unsigned height, uint32_t* out);

}  // namespace tessera::gl
