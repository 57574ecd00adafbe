// The pixel formats and their one conversion rule (common/pixel_format.h),
// checked against the definitions: GL's round(c * (2^n - 1) / 255) computed
// in double precision, and bit replication written out bit by bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "common/pixel_format.h"

namespace {

using tessera::PixelFormat;

unsigned gl_reduce(unsigned c, unsigned bits) {
  return static_cast<unsigned>(std::lround(c * double((1u << bits) - 1) / 255.0));
}

// The code's bits repeated from bit 7 downwards until 8 bits are filled.
unsigned replicate(unsigned code, unsigned bits) {
  unsigned out = 0;
  for (int bit = 7; bit >= 0; --bit) {
    const int source = static_cast<int>(bits) - 1 - ((7 - bit) % static_cast<int>(bits));
    out |= ((code >> source) & 1u) << bit;
  }
  return out;
}

TEST(PixelFormat, ReductionRoundsToNearestForEveryValueAndWidth) {
  for (unsigned bits = 1; bits <= 8; ++bits)
    for (unsigned c = 0; c < 256; ++c)
      EXPECT_EQ(tessera::reduce_channel(c, bits), gl_reduce(c, bits)) << c << " " << bits;
}

TEST(PixelFormat, ExpansionReplicatesBitsAndReductionGivesTheCodeBack) {
  for (unsigned bits : {5u, 6u, 8u}) {
    for (unsigned code = 0; code < (1u << bits); ++code) {
      const unsigned wide = tessera::expand_channel(code, bits);
      EXPECT_EQ(wide, replicate(code, bits)) << code << " " << bits;
      EXPECT_EQ(tessera::reduce_channel(wide, bits), code) << code << " " << bits;
      // Within one step of the exactly scaled value.
      EXPECT_LE(std::fabs(wide - code * 255.0 / ((1u << bits) - 1)), 1.0) << code << " " << bits;
    }
  }
  EXPECT_EQ(tessera::expand_channel(31, 5), 255u);
  EXPECT_EQ(tessera::expand_channel(0, 5), 0u);
}

TEST(PixelFormat, Rgb565PacksRedHighAndReadsAlphaAsOne) {
  // Pure colours land in their fields: red 15:11, green 10:5, blue 4:0.
  EXPECT_EQ(tessera::pack_pixel(PixelFormat::rgb565, 0xff0000ffu), 0xf800u);
  EXPECT_EQ(tessera::pack_pixel(PixelFormat::rgb565, 0xff00ff00u), 0x07e0u);
  EXPECT_EQ(tessera::pack_pixel(PixelFormat::rgb565, 0xffff0000u), 0x001fu);
  // 7 rounds up to red code 1 (truncation would give 0).
  EXPECT_EQ(tessera::pack_pixel(PixelFormat::rgb565, 0x00000007u), 0x0800u);
  EXPECT_EQ(tessera::unpack_pixel(PixelFormat::rgb565, 0xf800u), 0xff0000ffu);
  EXPECT_EQ(tessera::unpack_pixel(PixelFormat::rgb565, 0x0000u), 0xff000000u);
  EXPECT_EQ(tessera::quantize_color(PixelFormat::rgba8888, 0x12345678u), 0x12345678u);
}

TEST(PixelFormat, MemoryIsLittleEndian) {
  uint8_t bytes[4] = {0, 0, 0, 0};
  tessera::store_pixel(PixelFormat::rgb565, bytes, 0xf81fu);
  EXPECT_EQ(bytes[0], 0x1f);
  EXPECT_EQ(bytes[1], 0xf8);
  EXPECT_EQ(bytes[2], 0);  // two bytes only
  EXPECT_EQ(tessera::load_pixel(PixelFormat::rgb565, bytes), 0xf81fu);
  tessera::store_pixel(PixelFormat::rgba8888, bytes, 0x11223344u);
  EXPECT_EQ(bytes[0], 0x44);
  EXPECT_EQ(bytes[3], 0x11);
  EXPECT_EQ(tessera::load_pixel(PixelFormat::rgba8888, bytes), 0x11223344u);
}

TEST(PixelFormat, ColorMaskSelectsEachChannelsBits) {
  EXPECT_EQ(tessera::channel_bits(PixelFormat::rgb565, 0xf), 0xffffu);
  EXPECT_EQ(tessera::channel_bits(PixelFormat::rgb565, 0x8), 0u) << "no alpha in RGB565";
  EXPECT_EQ(tessera::channel_bits(PixelFormat::rgb565, 0x2), 0x07e0u);
  EXPECT_EQ(tessera::channel_bits(PixelFormat::rgba8888, 0x9), 0xff0000ffu);
}

TEST(PixelFormat, NamesCodesAndSizesComeFromTheTable) {
  EXPECT_EQ(tessera::pixel_format_from_name("rgb565"), PixelFormat::rgb565);
  EXPECT_EQ(tessera::pixel_format_from_name("rgba8888"), PixelFormat::rgba8888);
  EXPECT_FALSE(tessera::pixel_format_from_name("rgb888").has_value());
  EXPECT_EQ(tessera::pixel_format_from_code(1), PixelFormat::rgba8888);
  EXPECT_FALSE(tessera::pixel_format_from_code(2).has_value());
  EXPECT_EQ(tessera::bytes_per_pixel(PixelFormat::rgb565), 2u);
  EXPECT_EQ(tessera::bytes_per_pixel(PixelFormat::rgba8888), 4u);
  EXPECT_EQ(tessera::pixel_format_names(), "rgb565, rgba8888");
  const tessera::PixelFormatInfo& info = tessera::pixel_format_info(PixelFormat::rgb565);
  EXPECT_EQ(info.red_bits + info.green_bits + info.blue_bits + info.alpha_bits, 8 * info.bytes);
}

}  // namespace
