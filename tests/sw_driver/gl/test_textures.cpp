// Unit tests of the GL front end's textures: the errors glTexImage2D and
// glCompressedTexImage2D give (OpenGL ES 1.1 section 3.8.1 and
// OES_compressed_paletted_texture), the conversion of every format and type
// to the RGBA8 texels the back ends read, mipmap levels and texture
// completeness (section 3.8.10), GL_GENERATE_MIPMAP, paletted images with
// their level count, and the compressed-format queries. Expected texels are
// worked out by hand from the specification's conversion rules.
#include <GLES/gl.h>
#include <GLES/glext.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "gl/texture_formats.h"
#include "gl_test_fixture.h"

using namespace tessera;
using test::GlApi;

namespace {

uint32_t rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
  return r | g << 8 | b << 16 | a << 24;
}

uint32_t unpack(GLenum format, GLenum type, std::vector<uint8_t> bytes) {
  return gl::unpack_pixel(format, type, bytes.data());
}

uint32_t unpack16(GLenum format, GLenum type, uint16_t word) {
  uint8_t bytes[2];
  std::memcpy(bytes, &word, 2);
  return gl::unpack_pixel(format, type, bytes);
}

const float TRIANGLE[] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};

}  // namespace

TEST(TextureFormats, UnsignedByteFormatsExpandAsTheSpecificationSays) {
  EXPECT_EQ(unpack(GL_LUMINANCE, GL_UNSIGNED_BYTE, {77}), rgba(77, 77, 77, 255));
  EXPECT_EQ(unpack(GL_ALPHA, GL_UNSIGNED_BYTE, {9}), rgba(0, 0, 0, 9));
  EXPECT_EQ(unpack(GL_LUMINANCE_ALPHA, GL_UNSIGNED_BYTE, {10, 20}), rgba(10, 10, 10, 20));
  EXPECT_EQ(unpack(GL_RGB, GL_UNSIGNED_BYTE, {1, 2, 3}), rgba(1, 2, 3, 255));
  EXPECT_EQ(unpack(GL_RGBA, GL_UNSIGNED_BYTE, {1, 2, 3, 4}), rgba(1, 2, 3, 4));
}

TEST(TextureFormats, PackedTypesRoundEachComponentToNearest) {
  EXPECT_EQ(unpack16(GL_RGB, GL_UNSIGNED_SHORT_5_6_5, 0xF800), rgba(255, 0, 0, 255));
  EXPECT_EQ(unpack16(GL_RGB, GL_UNSIGNED_SHORT_5_6_5, 0x07E0), rgba(0, 255, 0, 255));
  EXPECT_EQ(unpack16(GL_RGB, GL_UNSIGNED_SHORT_5_6_5, 0x001F), rgba(0, 0, 255, 255));
  // r = 16: 16 * 255 / 31 = 131.6 -> 132; g = 32: 32 * 255 / 63 = 129.5 -> 130.
  EXPECT_EQ(unpack16(GL_RGB, GL_UNSIGNED_SHORT_5_6_5, 16 << 11 | 32 << 5 | 16), rgba(132, 130, 132, 255));
  // 4-bit components times 17.
  EXPECT_EQ(unpack16(GL_RGBA, GL_UNSIGNED_SHORT_4_4_4_4, 0x1234), rgba(17, 34, 51, 68));
  EXPECT_EQ(unpack16(GL_RGBA, GL_UNSIGNED_SHORT_5_5_5_1, 0x0001), rgba(0, 0, 0, 255));
  EXPECT_EQ(unpack16(GL_RGBA, GL_UNSIGNED_SHORT_5_5_5_1, 0xFFFE), rgba(255, 255, 255, 0));
  // r = 1, g = 2, b = 3 of 31: 8.23 -> 8, 16.45 -> 16, 24.68 -> 25.
  EXPECT_EQ(unpack16(GL_RGBA, GL_UNSIGNED_SHORT_5_5_5_1, 1 << 11 | 2 << 6 | 3 << 1 | 1), rgba(8, 16, 25, 255));
}

TEST(TextureFormats, FormatTypePairs) {
  EXPECT_EQ(gl::format_type_error(GL_RGB, GL_UNSIGNED_SHORT_5_6_5), 0u);
  EXPECT_EQ(gl::format_type_error(GL_RGBA, GL_UNSIGNED_SHORT_5_6_5), static_cast<GLenum>(GL_INVALID_OPERATION));
  EXPECT_EQ(gl::format_type_error(GL_RGB, GL_UNSIGNED_SHORT_4_4_4_4), static_cast<GLenum>(GL_INVALID_OPERATION));
  EXPECT_EQ(gl::format_type_error(GL_LUMINANCE, GL_UNSIGNED_SHORT_5_5_5_1), static_cast<GLenum>(GL_INVALID_OPERATION));
  EXPECT_EQ(gl::format_type_error(GL_RGBA, GL_FLOAT), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(gl::format_type_error(0x80E1 /* desktop GL_BGRA */, GL_UNSIGNED_BYTE),
            static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(gl::pixel_bytes(GL_LUMINANCE_ALPHA, GL_UNSIGNED_BYTE), 2u);
  EXPECT_EQ(gl::pixel_bytes(GL_RGBA, GL_UNSIGNED_SHORT_4_4_4_4), 2u);
}

TEST(TextureFormats, PalettedSizesFollowTheExtension) {
  // PALETTE4_RGB8 8 x 8, one level: 16 entries of 3 bytes, 64 indices of 4 bits.
  EXPECT_EQ(gl::paletted_image_size(*gl::find_palette_format(GL_PALETTE4_RGB8_OES), 8, 8, 1), 48u + 32u);
  // PALETTE8_RGBA8 8 x 8, four levels: 1024 + 64 + 16 + 4 + 1.
  EXPECT_EQ(gl::paletted_image_size(*gl::find_palette_format(GL_PALETTE8_RGBA8_OES), 8, 8, 4), 1109u);
  // PALETTE4_RGBA4 4 x 4, three levels: 32 + 8 + 2 + 1 (a lone index takes a byte).
  EXPECT_EQ(gl::paletted_image_size(*gl::find_palette_format(GL_PALETTE4_RGBA4_OES), 4, 4, 3), 43u);
  EXPECT_EQ(gl::find_palette_format(GL_RGBA), nullptr);
}

TEST(TextureFormats, BoxFilterRoundsTheAverage) {
  // Red 0, 1, 2, 4: 7 / 4 = 1.75 -> 2; green 10, 11, 10, 10: 10.25 -> 10.
  const uint32_t in[4] = {rgba(0, 10, 0, 255), rgba(1, 11, 0, 255), rgba(2, 10, 0, 255), rgba(4, 10, 0, 255)};
  uint32_t out = 0;
  gl::box_filter_level(in, 2, 2, &out);
  EXPECT_EQ(out, rgba(2, 10, 0, 255));
  // A 2 x 1 level averages its two texels: (1 + 2) / 2 = 1.5 -> 2.
  const uint32_t row[2] = {rgba(1, 0, 0, 0), rgba(2, 0, 0, 0)};
  gl::box_filter_level(row, 2, 1, &out);
  EXPECT_EQ(out, rgba(2, 0, 0, 0));
}

TEST_F(GlApi, TexImageErrorsForFormatsTypesAndLevels) {
  std::vector<uint8_t> pixels(4 * 4 * 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, 4, 4, 0, GL_RGB, GL_UNSIGNED_SHORT_4_4_4_4, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 4, 4, 0, GL_RGBA, GL_UNSIGNED_SHORT_5_6_5, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 4, 4, 0, GL_RGBA, GL_FLOAT, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glTexImage2D(GL_TEXTURE_2D, 0, 3, 4, 4, 0, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());  // desktop's "3 components"
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexImage2D(GL_TEXTURE_2D, -1, GL_RGBA, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexImage2D(GL_TEXTURE_2D, 9, GL_RGBA, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // 256 has 0..8
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, 4, 4, 0, GL_RGB, GL_UNSIGNED_SHORT_5_6_5, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 2, 2, GL_RGB, GL_UNSIGNED_SHORT_5_5_5_1, pixels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  glTexSubImage2D(GL_TEXTURE_2D, 1, 0, 0, 1, 1, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());  // level 1 undefined
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
}

TEST_F(GlApi, MipmapFilterNeedsEveryLevelOfTheSameFormat) {
  std::vector<uint8_t> pixels(4 * 4 * 4, 100);
  glEnable(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  draw_triangle(TRIANGLE);  // default GL_NEAREST_MIPMAP_LINEAR, levels 1 and 2 missing: texturing off
  EXPECT_FALSE(renderer.state.unit[0].enabled);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  draw_triangle(TRIANGLE);
  ASSERT_TRUE(renderer.state.unit[0].enabled);
  EXPECT_EQ(renderer.state.unit[0].tex.levels, 1u);
  EXPECT_EQ(renderer.state.unit[0].tex.min_mipmap, gl::MipmapFilter::none);

  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
  glTexImage2D(GL_TEXTURE_2D, 1, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glTexImage2D(GL_TEXTURE_2D, 2, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());  // should be 1 x 1
  draw_triangle(TRIANGLE);
  EXPECT_FALSE(renderer.state.unit[0].enabled);
  glTexImage2D(GL_TEXTURE_2D, 2, GL_RGB, 1, 1, 0, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());  // another format
  draw_triangle(TRIANGLE);
  EXPECT_FALSE(renderer.state.unit[0].enabled);
  const uint8_t texel[4] = {1, 2, 3, 4};
  glTexImage2D(GL_TEXTURE_2D, 2, GL_RGBA, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
  draw_triangle(TRIANGLE);
  ASSERT_TRUE(renderer.state.unit[0].enabled);
  const gl::Texture& t = renderer.state.unit[0].tex;
  EXPECT_EQ(t.levels, 3u);
  EXPECT_EQ(t.min_filter, gl::TexFilter::linear);
  EXPECT_EQ(t.min_mipmap, gl::MipmapFilter::nearest);
  EXPECT_EQ(t.level[0].address, t.address);
  EXPECT_EQ(t.level[1].width, 2u);
  EXPECT_EQ(t.level[2].width, 1u);
  EXPECT_EQ(host.read32(t.level[2].address), rgba(1, 2, 3, 4));
  GLint filter = 0;
  glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &filter);
  EXPECT_EQ(filter, GL_LINEAR_MIPMAP_NEAREST);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, GenerateMipmapFillsEveryLevelFromLevelZero) {
  glEnable(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_GENERATE_MIPMAP, GL_TRUE);
  GLint generate = 0;
  glGetTexParameteriv(GL_TEXTURE_2D, GL_GENERATE_MIPMAP, &generate);
  EXPECT_EQ(generate, GL_TRUE);
  // 4 x 2 luminance: level 1 is 2 x 1, level 2 is 1 x 1.
  const uint8_t luminance[8] = {0, 2, 100, 101, 4, 6, 100, 100};
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, 4, 2, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, luminance);
  draw_triangle(TRIANGLE);
  ASSERT_TRUE(renderer.state.unit[0].enabled);  // GL_NEAREST_MIPMAP_LINEAR with generated levels
  const gl::Texture& t = renderer.state.unit[0].tex;
  ASSERT_EQ(t.levels, 3u);
  // (0 + 2 + 4 + 6) / 4 = 3; (100 + 101 + 100 + 100) / 4 = 100.25 -> 100; then (3 + 100) / 2 = 51.5 -> 52.
  EXPECT_EQ(host.read32(t.level[1].address), rgba(3, 3, 3, 255));
  EXPECT_EQ(host.read32(t.level[1].address + 4), rgba(100, 100, 100, 255));
  EXPECT_EQ(host.read32(t.level[2].address), rgba(52, 52, 52, 255));
  // A change to level 0 generates them again.
  const uint8_t two[2] = {200, 200};
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 2, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE, two);
  // Level 1's first texel: (200 + 200 + 4 + 6) / 4 = 102.5 -> 103.
  EXPECT_EQ(host.read32(t.level[1].address), rgba(103, 103, 103, 255));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlApi, PalettedTexturesDecodeEveryLevel) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_COMPRESSED_TEXTURE_FORMATS, &count);
  ASSERT_EQ(count, 10);
  std::vector<GLint> formats(10);
  glGetIntegerv(GL_COMPRESSED_TEXTURE_FORMATS, formats.data());
  for (int i = 0; i < 10; ++i) EXPECT_EQ(formats[i], GL_PALETTE4_RGB8_OES + i);

  // PALETTE4_RGBA8, 2 x 2 and its 1 x 1 level (level -1): entry k = (k, 2k, 3k, 255 - k).
  std::vector<uint8_t> data;
  for (int k = 0; k < 16; ++k)
    data.insert(data.end(), {static_cast<uint8_t>(k), static_cast<uint8_t>(2 * k), static_cast<uint8_t>(3 * k),
                             static_cast<uint8_t>(255 - k)});
  data.insert(data.end(), {0x12, 0x3F, 0x70});  // level 0: 1, 2 / 3, 15; level 1: 7
  glEnable(GL_TEXTURE_2D);
  glCompressedTexImage2D(GL_TEXTURE_2D, -1, GL_PALETTE4_RGBA8_OES, 2, 2, 0, static_cast<GLsizei>(data.size()) - 1,
                         data.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));  // one byte short
  glCompressedTexImage2D(GL_TEXTURE_2D, -2, GL_PALETTE4_RGBA8_OES, 2, 2, 0, static_cast<GLsizei>(data.size()),
                         data.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));  // 2 x 2 has two levels, not three
  glCompressedTexImage2D(GL_TEXTURE_2D, 1, GL_PALETTE4_RGBA8_OES, 2, 2, 0, static_cast<GLsizei>(data.size()),
                         data.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));  // level > 0
  glCompressedTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 2, 2, 0, static_cast<GLsizei>(data.size()), data.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  glCompressedTexImage2D(GL_TEXTURE_2D, -1, GL_PALETTE4_RGBA8_OES, 2, 2, 0, static_cast<GLsizei>(data.size()),
                         data.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  draw_triangle(TRIANGLE);
  ASSERT_TRUE(renderer.state.unit[0].enabled);
  const gl::Texture& t = renderer.state.unit[0].tex;
  ASSERT_EQ(t.levels, 2u);
  EXPECT_EQ(host.read32(t.address), rgba(1, 2, 3, 254));
  EXPECT_EQ(host.read32(t.address + 4), rgba(2, 4, 6, 253));
  EXPECT_EQ(host.read32(t.address + 8), rgba(3, 6, 9, 252));
  EXPECT_EQ(host.read32(t.address + 12), rgba(15, 30, 45, 240));
  EXPECT_EQ(host.read32(t.level[1].address), rgba(7, 14, 21, 248));
  glCompressedTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 1, 1, GL_PALETTE4_RGBA8_OES, 1, data.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));

  // PALETTE8_R5_G6_B5, 1 x 1: entry 0 red, a 16-bit word in the host's order.
  std::vector<uint8_t> red(256 * 2 + 1, 0);
  const uint16_t word = 0xF800;
  std::memcpy(red.data(), &word, 2);
  glCompressedTexImage2D(GL_TEXTURE_2D, 0, GL_PALETTE8_R5_G6_B5_OES, 1, 1, 0, static_cast<GLsizei>(red.size()),
                         red.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  draw_triangle(TRIANGLE);
  ASSERT_TRUE(renderer.state.unit[0].enabled);
  EXPECT_EQ(host.read32(renderer.state.unit[0].tex.address), rgba(255, 0, 0, 255));
  EXPECT_FALSE(renderer.state.unit[0].tex.has_alpha);  // an RGB palette makes an RGB texture
}

TEST_F(GlApi, CopyTexImageDefinesALevelInTheInternalFormatAskedFor) {
  const uint8_t luminance[4] = {10, 20, 30, 40};
  glEnable(GL_TEXTURE_2D);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of 2 bytes, packed (the default 4 would read 6 bytes)
  glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, 2, 2, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, luminance);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  // The recording renderer reads every byte as 0x5a: luminance 0x5a.
  glCopyTexImage2D(GL_TEXTURE_2D, 1, GL_LUMINANCE, 0, 0, 1, 1, 0);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  draw_triangle(TRIANGLE);
  ASSERT_TRUE(renderer.state.unit[0].enabled);  // both levels GL_LUMINANCE: complete
  EXPECT_EQ(host.read32(renderer.state.unit[0].tex.level[1].address), rgba(0x5a, 0x5a, 0x5a, 255));
  EXPECT_FALSE(renderer.state.unit[0].tex.has_alpha);
}
