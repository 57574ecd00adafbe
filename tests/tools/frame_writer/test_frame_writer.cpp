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
