#include "frame_writer.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {
namespace {

namespace fs = std::filesystem;

fs::path scratch_file(const std::string& name) {
  const char* binary_dir = std::getenv("TESSERA_BINARY_DIR");
  const fs::path dir = fs::path(binary_dir ? binary_dir : fs::temp_directory_path().string()) / "test_output" /
                       ("frame_writer_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir / name;
}

// An antialiased frame has fringe pixels with alpha between 0 and 255, and
// colour where alpha is 0: all of it must come back as written, not
// multiplied by alpha.
TEST(FrameWriter, PixelsComeBackAsWrittenWhateverTheirAlpha) {
  const std::vector<uint8_t> rgba = {10,  19,  0,   1,   126, 251, 0, 247, 200, 100, 50, 0,
                                     255, 255, 255, 255, 0,   0,   0, 0,   17,  34,  51, 128};
  const fs::path path = scratch_file("alpha.png");
  write_png(path.string(), 3, 2, rgba);
  const Image image = read_image(path.string());
  EXPECT_EQ(image.width, 3u);
  EXPECT_EQ(image.height, 2u);
  EXPECT_EQ(image.rgba, rgba);
  fs::remove_all(path.parent_path());
}

// The writer is libpng alone; OpenImageIO, an independent reader, must get
// back every pixel of an image whose compressed data spans several IDAT
// chunks (noise does not compress: more than libpng's 8 KiB chunk).
TEST(FrameWriter, ANoisyImageComesBackWholeThroughAnotherReader) {
  constexpr unsigned WIDTH = 97, HEIGHT = 61;
  std::vector<uint8_t> rgba(size_t{WIDTH} * HEIGHT * 4);
  uint32_t state = 12345;
  for (uint8_t& byte : rgba) {
    state = state * 1664525u + 1013904223u;
    byte = static_cast<uint8_t>(state >> 24);
  }
  const std::vector<unsigned char> png = encode_png(WIDTH, HEIGHT, rgba);
  EXPECT_GT(png.size(), 8192u + 100u) << "the data fits one IDAT chunk: the test does not cover several";
  const fs::path path = scratch_file("noise.png");
  write_png(path.string(), WIDTH, HEIGHT, rgba);
  const Image image = read_image(path.string());
  EXPECT_EQ(image.width, WIDTH);
  EXPECT_EQ(image.height, HEIGHT);
  EXPECT_EQ(image.rgba, rgba);
  fs::remove_all(path.parent_path());
}

TEST(FrameWriter, WrongPixelCountIsRefused) {
  EXPECT_THROW(encode_png(4, 4, std::vector<uint8_t>(4 * 4 * 4 - 1)), std::invalid_argument);
  EXPECT_THROW(encode_png(0, 0, {}), std::invalid_argument);
  try {
    write_png("frame_9.png", 2, 2, std::vector<uint8_t>(3));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("frame_9.png"), std::string::npos) << e.what();
  }
}

TEST(FrameWriter, UnwritableFileIsAnErrorNamingIt) {
  const fs::path path = scratch_file("no_such_folder") / "frame_0000.png";
  try {
    write_png(path.string(), 1, 1, {1, 2, 3, 4});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
  fs::remove_all(path.parent_path().parent_path());
}

TEST(FrameWriter, MissingFileIsAnErrorNamingIt) {
  try {
    read_image("no_such_frame.png");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_frame.png"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessera
