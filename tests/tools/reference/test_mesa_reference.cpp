#include "mesa_reference.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "test_scene.h"

namespace tessera::reference {
namespace {

ReferenceRequest request(unsigned width, unsigned height, int frame) {
  ReferenceRequest r;
  r.width = width;
  r.height = height;
  r.frame = frame;
  return r;
}

const uint8_t* pixel(const Image& image, unsigned x, unsigned y) {
  return &image.rgba[(size_t{y} * image.width + x) * 4];
}

TEST(MesaReference, RendersTheSameBytesTwiceWithSoftpipe) {
  // The reference overrides the caller's choice of driver.
  setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  const ReferenceFrame first = render_with_mesa(test_scene(), request(96, 64, 3));
  const ReferenceFrame second = render_with_mesa(test_scene(), request(96, 64, 3));
  EXPECT_NE(first.renderer.find("softpipe"), std::string::npos) << first.renderer;
  ASSERT_EQ(first.image.rgba.size(), 96u * 64u * 4u);
  EXPECT_EQ(first.image.rgba, second.image.rgba);
}

TEST(MesaReference, ImageIsTopRowFirstWithTheScenesClearColour) {
  const ReferenceFrame frame = render_with_mesa(test_scene(), request(80, 60, 0));
  // glClearColor(0.1, 0.1, 0.25, 1) as 8-bit unsigned normalised values.
  EXPECT_EQ(frame.clear_colour[0], 26);
  EXPECT_EQ(frame.clear_colour[1], 26);
  EXPECT_EQ(frame.clear_colour[2], 64);
  EXPECT_EQ(frame.clear_colour[3], 255);
  const Image& image = frame.image;
  for (unsigned x : {0u, 79u})
    for (unsigned y : {0u, 59u}) EXPECT_EQ(pixel(image, x, y)[2], 64) << x << "," << y;
  // The apex (blue) is near the top of the window and the base (red, green)
  // near the bottom: row 0 must be the top.
  const uint8_t* near_apex = pixel(image, 40, 8);
  const uint8_t* near_base = pixel(image, 40, 48);
  EXPECT_GT(near_apex[2], near_apex[0]);
  EXPECT_GT(near_base[0] + near_base[1], 2 * near_base[2]);
}

TEST(MesaReference, DrawsEveryFrameUpToTheRequestedOne) {
  const ReferenceFrame frame0 = render_with_mesa(test_scene(), request(64, 64, 0));
  const ReferenceFrame frame4 = render_with_mesa(test_scene(), request(64, 64, 4));
  EXPECT_NE(frame0.image.rgba, frame4.image.rgba) << "the triangle turns each frame";
}

TEST(MesaReference, ReportsSceneErrors) {
  ReferenceRequest bad = request(16, 16, 0);
  bad.args = {"unexpected"};
  EXPECT_THROW(render_with_mesa(test_scene(), bad), std::runtime_error);
  EXPECT_THROW(render_with_mesa(test_scene(), request(0, 16, 0)), std::runtime_error);
}

}  // namespace
}  // namespace tessera::reference
