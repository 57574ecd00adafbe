// The reference oracle on built-in scenes compiled against Mesa
// (testbench_reference_scenes): the same bytes twice, the image top row
// first, the clear colour read back from GL, every frame up to the one
// asked for drawn, a scene's errors reported.
#include "reference/mesa_reference.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "scenes/scene.h"

namespace tessera::reference {
namespace {

const scenes::Scene& scene(const char* name) {
  const scenes::Scene* found = scenes::find_scene(name);
  if (found == nullptr) throw std::runtime_error(std::string("no built-in scene ") + name);
  return *found;
}

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
  const ReferenceFrame first = render_with_mesa(scene("cubes"), request(96, 64, 3));
  const ReferenceFrame second = render_with_mesa(scene("cubes"), request(96, 64, 3));
  EXPECT_NE(first.renderer.find("softpipe"), std::string::npos) << first.renderer;
  ASSERT_EQ(first.image.rgba.size(), 96u * 64u * 4u);
  EXPECT_EQ(first.image.rgba, second.image.rgba);
}

TEST(MesaReference, ImageIsTopRowFirst) {
  // The triangle's blue apex is near the top of the window and its red and
  // green base near the bottom, on black: row 0 must be the top.
  const ReferenceFrame frame = render_with_mesa(scene("triangle"), request(80, 60, 0));
  const Image& image = frame.image;
  for (unsigned x : {0u, 79u})
    for (unsigned y : {0u, 59u}) EXPECT_EQ(pixel(image, x, y)[2], 0) << x << "," << y;
  const uint8_t* near_apex = pixel(image, 40, 8);
  const uint8_t* near_base = pixel(image, 40, 48);
  EXPECT_GT(near_apex[2], near_apex[0]);
  EXPECT_GT(near_base[0] + near_base[1], 2 * near_base[2]);
}

TEST(MesaReference, ClearColourIsTheScenes) {
  // textured_quad: glClearColor(0.15, 0.15, 0.15, 1) as 8-bit unsigned
  // normalised values.
  const ReferenceFrame frame = render_with_mesa(scene("textured_quad"), request(80, 60, 0));
  EXPECT_EQ(frame.clear_colour[0], 38);
  EXPECT_EQ(frame.clear_colour[1], 38);
  EXPECT_EQ(frame.clear_colour[2], 38);
  EXPECT_EQ(frame.clear_colour[3], 255);
}

TEST(MesaReference, DrawsEveryFrameUpToTheRequestedOne) {
  const ReferenceFrame frame0 = render_with_mesa(scene("cubes"), request(64, 64, 0));
  const ReferenceFrame frame4 = render_with_mesa(scene("cubes"), request(64, 64, 4));
  EXPECT_NE(frame0.image.rgba, frame4.image.rgba) << "the cubes turn each frame";
}

TEST(MesaReference, ReportsSceneErrors) {
  ReferenceRequest bad = request(16, 16, 0);
  bad.args = {"unexpected"};
  EXPECT_THROW(render_with_mesa(scene("triangle"), bad), std::runtime_error);
  EXPECT_THROW(render_with_mesa(scene("triangle"), request(0, 16, 0)), std::runtime_error);
}

}  // namespace
}  // namespace tessera::reference
