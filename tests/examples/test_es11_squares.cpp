// The ordinary ES 1.1 program examples/es11_squares, built out of tree
// against the installed SDK (the fixture sdk_example_es11_build), run by the
// installed soc_sim on every back end: soc_sim calls its main, and the
// frames show what it draws. Where that is comes from the program's own
// coordinates, restated below: wherever a square has turned, it covers the
// circle inscribed in it and nothing outside the circle around it.
//
// Usage: test_es11_squares <installed soc_sim> <libes11_squares.so> [GoogleTest options]
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fixtures/backend_table.h"
#include "fixtures/soc_sim_test.h"
#include "frame_writer.h"

namespace {

namespace fs = std::filesystem;

std::string g_library;

using tessera::test::contains;
using tessera::test::describe;
using tessera::test::SimResult;

struct Rgb {
  int r, g, b;
};

// es11_squares.c: draw_square(width / 4, height / 2, 40, ..., red) and
// draw_square(3 * width / 4, height / 2, 30, ..., green) in a view of one
// unit per pixel, on glClearColorx(0, 0, 0.5, 1).
struct Square {
  double x_of_width, y_of_height, half;
  Rgb colour;
};
const Square SQUARES[] = {{0.25, 0.5, 40, {255, 0, 0}}, {0.75, 0.5, 30, {0, 255, 0}}};
const Rgb CLEAR = {0, 0, 128};
constexpr int FRAMES = 3;

// One RGB565 step on the 8-bit scale (5-bit channels differ by 8 or 9).
constexpr int TOLERANCE = 9;
// Pixel centres this close to a circle are left out: the edges of the
// squares are rasterized, not drawn exactly.
constexpr double MARGIN = 1.0;

bool near(const uint8_t* pixel, const Rgb& colour) {
  return std::abs(pixel[0] - colour.r) <= TOLERANCE && std::abs(pixel[1] - colour.g) <= TOLERANCE &&
         std::abs(pixel[2] - colour.b) <= TOLERANCE;
}

class Es11Squares : public tessera::test::SocSimTest {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(g_library))
        << "usage: test_es11_squares <installed soc_sim> <libes11_squares.so> (built by sdk_example_es11_build)";
    SocSimTest::SetUp();
  }
};

TEST_F(Es11Squares, SocSimRunsItsMainAndTheFramesShowTheSquares) {
  for (const std::string& backend : tessera::test::back_end_names()) {
    const SimResult result =
        run({"--backend", backend, "--app", g_library, "--frames", std::to_string(FRAMES), "--out", backend});
    ASSERT_EQ(result.status, 0) << backend << ": " << describe(result);
    // What the program prints of the GL, through glGetString and the
    // extension's query guarded by its macro from <GLES/glext.h>.
    EXPECT_TRUE(contains(result.out, "GL_VERSION    OpenGL ES-CM 1.1")) << backend << ": " << result.out;
    EXPECT_TRUE(contains(result.out, "GL_EXTENSIONS GL_OES_read_format")) << backend << ": " << result.out;
    EXPECT_TRUE(contains(result.out, "read format   0x1908, type 0x1401")) << backend << ": " << result.out;

    std::vector<uint8_t> previous;
    for (int frame = 0; frame < FRAMES; ++frame) {
      const fs::path path = m_dir / backend / ("frame_000" + std::to_string(frame) + ".png");
      ASSERT_TRUE(fs::is_regular_file(path)) << path;
      const tessera::Image image = tessera::read_image(path.string());
      size_t square_pixels = 0, clear_pixels = 0, wrong = 0;
      for (unsigned row = 0; row < image.height; ++row)
        for (unsigned column = 0; column < image.width; ++column) {
          // GL's y grows upwards; the image's first row is the top one.
          const double x = column + 0.5, y = image.height - row - 0.5;
          const uint8_t* pixel = &image.rgba[(size_t{row} * image.width + column) * 4];
          bool may_be_covered = false;
          for (const Square& square : SQUARES) {
            const double distance =
                std::hypot(x - square.x_of_width * image.width, y - square.y_of_height * image.height);
            if (distance <= square.half - MARGIN) {
              ++square_pixels;
              wrong += !near(pixel, square.colour);
            }
            may_be_covered = may_be_covered || distance < square.half * std::sqrt(2.0) + MARGIN;
          }
          if (!may_be_covered) {
            ++clear_pixels;
            wrong += !near(pixel, CLEAR);
          }
        }
      EXPECT_EQ(wrong, 0u) << backend << ", " << path << ": " << wrong << " of " << square_pixels << " square and "
                           << clear_pixels << " background pixels have the wrong colour";
      EXPECT_GT(square_pixels, 5000u);
      EXPECT_GT(clear_pixels, size_t{image.width} * image.height / 3);
      EXPECT_NE(image.rgba, previous) << backend << ": frame " << frame << " is the one before (the squares turn)";
      previous = image.rgba;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  tessera::test::init_soc_sim_test(argc, argv);
  if (argc >= 3) g_library = fs::absolute(argv[2]).string();
  return RUN_ALL_TESTS();
}
