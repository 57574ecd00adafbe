// System tests of the raster back end: soc_sim runs GL applications with
// --backend raster, the driver bins their triangles into tile lists and the
// rasterizer block draws them. Checks what a user sees: exit status, the
// frames written, the rasterizer's statistics and bus traffic, the frame
// against the arm back end's for the same scene, and the configuration that
// cannot work (a rasterizer smaller than the display) rejected.
//
// Usage: test_raster_backend <path to soc_sim> [GoogleTest options]
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "fixtures/soc_sim_test.h"

#include "frame_writer.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int EXIT_USAGE = 2;
constexpr unsigned WIDTH = 320, HEIGHT = 240;

using tessera::test::contains;
using tessera::test::describe;
using tessera::test::read_file;
using tessera::test::SimResult;

class RasterBackend : public tessera::test::SocSimTest {
 protected:
  // Runs `app` on the raster back end for two frames and checks the frames
  // and the statistics; returns the statistics.
  json run_app(const std::string& app, const std::string& folder) {
    const SimResult result = run({"--backend", "raster", "--app", app, "--frames", "2", "--out", folder});
    EXPECT_EQ(result.status, 0) << describe(result);
    for (const char* frame : {"frame_0000.png", "frame_0001.png"}) {
      const fs::path path = m_dir / folder / frame;
      EXPECT_TRUE(fs::is_regular_file(path)) << path;
      if (!fs::is_regular_file(path)) continue;
      const tessera::Image image = tessera::read_image(path.string());
      EXPECT_EQ(image.width, WIDTH);
      EXPECT_EQ(image.height, HEIGHT);
    }
    EXPECT_FALSE(fs::exists(m_dir / folder / "frame_0002.png")) << "more frames than asked for";
    std::ifstream in(m_dir / folder / "stats.json");
    const json document = json::parse(in, nullptr, false);
    EXPECT_FALSE(document.is_discarded()) << "stats.json is not valid JSON";
    if (document.is_discarded()) return json::object();
    const json& stats = document["stats"];
    EXPECT_TRUE(stats.contains("raster")) << stats.dump(2);
    const json& raster = stats["raster"];
    // One rasterizer run per frame, every tile of the 10x15 grid visited.
    EXPECT_EQ(raster["runs"], 2) << raster.dump(2);
    EXPECT_EQ(raster["failed_runs"], 0) << raster.dump(2);
    EXPECT_GT(raster["triangles"].get<double>(), 0) << raster.dump(2);
    EXPECT_GT(raster["fragments"].get<double>(), 0) << raster.dump(2);
    EXPECT_GT(raster["busy_ns"].get<double>(), 0) << raster.dump(2);
    // Its traffic is real bus traffic: the bus counts it as an initiator.
    const json& bus = stats["bus"]["initiators"]["raster"];
    EXPECT_GT(bus["bytes"].get<double>(), 0) << stats["bus"].dump(2);
    EXPECT_EQ(bus["errors"], 0) << stats["bus"].dump(2);
    EXPECT_EQ(bus["bytes"].get<double>(),
              raster["bus"]["bytes_read"].get<double>() + raster["bus"]["bytes_written"].get<double>());
    EXPECT_EQ(stats["display"]["frames_shown"], 2);
    // The summary on stdout has the rasterizer's row with the same counts.
    const std::string row = "2 runs, " + std::to_string(raster["triangles"].get<unsigned long long>()) +
                            " triangles, " + std::to_string(raster["tiles"].get<unsigned long long>()) + " tiles";
    EXPECT_TRUE(contains(result.out, row)) << "no '" << row << "' in the summary:\n" << result.out;
    return stats;
  }
};

TEST_F(RasterBackend, TriangleRunsAndMatchesTheArmBackEnd) {
  const json stats = run_app("triangle", "raster");
  const SimResult arm = run({"--backend", "arm", "--app", "triangle", "--frames", "2", "--out", "arm"});
  ASSERT_EQ(arm.status, 0) << describe(arm);
  const tessera::Image ours = tessera::read_image((m_dir / "raster/frame_0001.png").string());
  const tessera::Image reference = tessera::read_image((m_dir / "arm/frame_0001.png").string());
  ASSERT_EQ(ours.rgba.size(), reference.rgba.size());
  // Both back ends follow the same fill rule and the same RGB565 rounding;
  // their interpolators round differently, so a colour may differ by one
  // unit before the reduction and by one RGB565 step (8 or 9 on the 8-bit
  // scale) after it, and a few pixels along the edges.
  constexpr int ONE_RGB565_STEP = 9;
  size_t differing = 0;
  for (size_t i = 0; i < ours.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c)
      if (std::abs(int(ours.rgba[i + c]) - int(reference.rgba[i + c])) > ONE_RGB565_STEP) {
        ++differing;
        break;
      }
  EXPECT_LT(differing, size_t{WIDTH} * HEIGHT / 100) << "pixels differing from the arm back end's frame";
  // The triangle is in the middle of the frame, the clear colour in the corner.
  const uint8_t* centre = &ours.rgba[(size_t{HEIGHT} / 2 * WIDTH + WIDTH / 2) * 4];
  const uint8_t* corner = &ours.rgba[0];
  EXPECT_NE(std::vector<uint8_t>(centre, centre + 3), std::vector<uint8_t>(corner, corner + 3));
}

TEST_F(RasterBackend, TeapotRuns) {
  const json stats = run_app("teapot", "out");
  EXPECT_GT(stats["raster"]["triangles"].get<double>(), 100) << stats["raster"].dump(2);
  EXPECT_EQ(stats["raster"]["tiles"], 2 * 10 * 15) << stats["raster"].dump(2);
}

// The rasterizer covers the display: its size is the display's, and has no
// key of its own to disagree with it.
TEST_F(RasterBackend, RasterizerTakesTheDisplaysSize) {
  const SimResult result = run({"--backend", "raster", "--set", "display.width=256", "--set", "display.height=200",
                                "--frames", "1", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const tessera::Image image = tessera::read_image((m_dir / "out" / "frame_0000.png").string());
  EXPECT_EQ(image.width, 256u);
  EXPECT_EQ(image.height, 200u);
  std::ifstream in(m_dir / "out" / "stats.json");
  const json document = json::parse(in, nullptr, false);
  ASSERT_FALSE(document.is_discarded()) << "stats.json is not valid JSON";
  EXPECT_EQ(document["stats"]["raster"]["width"], 256) << document["stats"]["raster"].dump(2);
  EXPECT_EQ(document["stats"]["raster"]["height"], 200) << document["stats"]["raster"].dump(2);
  // 256 x 200 in 32 x 16 tiles: 8 x 13.
  EXPECT_EQ(document["stats"]["raster"]["tiles"], 8 * 13) << document["stats"]["raster"].dump(2);

  const SimResult old_key = run({"--backend", "raster", "--set", "raster.width=256", "--out", "old"});
  EXPECT_EQ(old_key.status, EXIT_USAGE) << describe(old_key);
  EXPECT_TRUE(contains(old_key.err, "raster.width")) << describe(old_key);
}

// GL_MAX_TEXTURE_UNITS (driver.texture_units) beyond the rasterizer's
// units is refused up front, naming both keys; within them the multitexture
// scene runs, and on arm the rasterizer's count does not matter.
TEST_F(RasterBackend, MoreTextureUnitsThanTheRasterizerHasAreRejected) {
  const SimResult result = run({"--backend", "raster", "--set", "driver.texture_units=3", "--set",
                                "raster.texture_units=2", "--app", "multitexture", "--out", "out"});
  EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
  EXPECT_TRUE(contains(result.err, "impossible combination")) << describe(result);
  EXPECT_TRUE(contains(result.err, "driver.texture_units=3")) << describe(result);
  EXPECT_TRUE(contains(result.err, "raster.texture_units=2")) << describe(result);
  const SimResult four = run({"--backend", "raster", "--set", "driver.texture_units=4", "--set",
                              "raster.texture_units=4", "--app", "multitexture", "--frames", "1", "--out", "four"});
  EXPECT_EQ(four.status, 0) << describe(four);
  const SimResult arm = run({"--backend", "arm", "--set", "driver.texture_units=3", "--set", "raster.texture_units=1",
                             "--app", "multitexture", "--frames", "1", "--out", "arm"});
  EXPECT_EQ(arm.status, 0) << describe(arm);
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
