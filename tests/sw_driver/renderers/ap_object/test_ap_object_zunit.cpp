// ap-object's z path through the z-buffer unit (ap.object.zpath=unit)
// through soc_sim (system): on scenes the unit can draw (untextured, opaque,
// GL_LESS, a clear of colour and depth first) the frame is the host path's
// byte for byte, through the CIU and the DMA and in bands; nothing is read
// back from CMEM; a frame needing more falls back to the host path with a
// warning naming why; the configurations the path cannot run are refused
// naming the key.
//
// Usage: ap_object_zunit <path to soc_sim> [GoogleTest options]
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "fixtures/soc_sim_test.h"

namespace {

using nlohmann::json;
using tessera::test::contains;
using tessera::test::describe;
using tessera::test::SimResult;

class ApObjectZunit : public tessera::test::SocSimTest {
 protected:
  // One frame of `scene` in `folder`; the unit is on in every run, so that
  // the two paths run the same SoC.
  json draw(const std::string& folder, const std::string& scene, const std::vector<std::string>& settings,
            SimResult* result_out = nullptr) {
    std::vector<std::string> args = {"--backend",
                                     "ap-object",
                                     "--app",
                                     scene,
                                     "--frames",
                                     "1",
                                     "-q",
                                     "--out",
                                     folder,
                                     "--set",
                                     "zbuf.enabled=true",
                                     "--set",
                                     "array.features.zsend=true"};
    for (const std::string& setting : settings) {
      args.push_back("--set");
      args.push_back(setting);
    }
    // -q keeps the warnings too: a caller that reads them runs without it.
    if (result_out != nullptr) args.erase(args.begin() + 6);
    const SimResult result = run(args);
    EXPECT_EQ(result.status, 0) << describe(result);
    if (result_out != nullptr) *result_out = result;
    std::ifstream in(m_dir / folder / "stats.json");
    return json::parse(in, nullptr, false);
  }
  std::string frame(const std::string& folder) {
    std::ifstream in(m_dir / folder / "frame_0000.png", std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
};

const json& driver(const json& stats) {
  return stats["stats"]["driver"]["ap_object"];
}

uint64_t zbuf_counter(const json& stats, const std::string& name) {
  return driver(stats)["zbuf"][name].get<uint64_t>();
}

TEST_F(ApObjectZunit, TheUnitDrawsTheHostPathsFrame) {
  for (const char* scene : {"teapot", "cubes"}) {
    const std::string host_folder = std::string("host_") + scene;
    const json host = draw(host_folder, scene, {"ap.object.zpath=host"});
    ASSERT_FALSE(host.is_discarded());
    EXPECT_FALSE(driver(host).contains("zbuf"));
    for (const char* dma : {"false", "true"}) {
      const std::string folder = std::string("unit_") + scene + "_dma_" + dma;
      const json unit = draw(folder, scene, {"ap.object.zpath=unit", std::string("dma.enabled=") + dma});
      ASSERT_FALSE(unit.is_discarded());
      EXPECT_TRUE(frame(folder) == frame(host_folder)) << scene << ", dma " << dma << ": the frames differ";
      EXPECT_EQ(zbuf_counter(unit, "frames_unit"), 1u);
      EXPECT_EQ(zbuf_counter(unit, "frames_host"), 0u);
      EXPECT_EQ(zbuf_counter(unit, "bands"), 1u);
      EXPECT_EQ(zbuf_counter(unit, "clears"), 1u);
      EXPECT_EQ(zbuf_counter(unit, "copied_bytes"), 192u * 144u * 2u);
      EXPECT_GT(zbuf_counter(unit, "pixels_sent"), 0u);
      EXPECT_EQ(zbuf_counter(unit, "pixels_sent"), unit["stats"]["zbuf"]["pixels"].get<uint64_t>());
      // Every covered pixel the host path read back went to the unit, and
      // those beyond the frame's sides, which the unit clips.
      EXPECT_EQ(zbuf_counter(unit, "pixels_sent") - unit["stats"]["zbuf"]["clipped"].get<uint64_t>(),
                driver(host)["pixels_emitted"].get<uint64_t>());
      EXPECT_EQ(driver(unit)["ciu_words_read"].get<uint64_t>(), 0u);
      EXPECT_EQ(driver(unit)["pieces"], driver(host)["pieces"]);
      EXPECT_TRUE(unit["stats"]["array"]["zbuf"].contains("stall_cycles"));
    }
  }
}

// A window of 4,096 entries holds 21 rows of the 192-pixel frame: seven
// bands, each drawing the whole frame again, the unit clipping the rest.
TEST_F(ApObjectZunit, BandsDrawTheSameFrame) {
  const json host = draw("host", "teapot", {});
  const json bands = draw("bands", "teapot", {"ap.object.zpath=unit", "zbuf.entries=4096"});
  ASSERT_FALSE(bands.is_discarded());
  EXPECT_TRUE(frame("bands") == frame("host")) << "the frames differ";
  EXPECT_EQ(zbuf_counter(bands, "bands"), 7u);
  EXPECT_EQ(zbuf_counter(bands, "clears"), 7u);
  EXPECT_EQ(zbuf_counter(bands, "pixels_sent"), 7 * driver(host)["pixels_emitted"].get<uint64_t>());
  EXPECT_GT(bands["stats"]["zbuf"]["clipped"].get<uint64_t>(), 0u);
}

// textured_quad textures its quad (and clears colour alone first): the
// frame goes to the host path, said once, and is the host path's.
TEST_F(ApObjectZunit, AFrameTheUnitCannotDrawFallsBackWithAWarning) {
  const json host = draw("host", "textured_quad", {});
  SimResult result;
  const json unit = draw("unit", "textured_quad", {"ap.object.zpath=unit"}, &result);
  ASSERT_FALSE(unit.is_discarded());
  EXPECT_TRUE(frame("unit") == frame("host")) << "the frames differ";
  EXPECT_EQ(zbuf_counter(unit, "frames_unit"), 0u);
  EXPECT_EQ(zbuf_counter(unit, "frames_host"), 1u);
  EXPECT_EQ(zbuf_counter(unit, "pixels_sent"), 0u);
  const json& fallback = driver(unit)["zbuf"]["fallback"];
  ASSERT_EQ(fallback.size(), 1u);
  EXPECT_EQ(fallback.begin().value().get<uint64_t>(), 1u);
  const std::string log = result.out + result.err;
  EXPECT_TRUE(contains(log, "ap.object.zpath=unit: ")) << log;
  EXPECT_TRUE(contains(log, "drawn on the host path")) << log;
  EXPECT_EQ(driver(unit)["pixels_emitted"], driver(host)["pixels_emitted"]);
}

TEST_F(ApObjectZunit, RefusalsNameTheKey) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"zbuf.enabled=false", "array.features.zsend=false"}, "zbuf.enabled=false"},
      {{"array.features.zsend=false"}, "array.features.zsend=false"},
      {{"display.format=rgba8888"}, "display.format=rgba8888"},
      {{"zbuf.entries=100"}, "zbuf.entries=100"},
  };
  for (const auto& [settings, named] : cases) {
    std::vector<std::string> args = {"--backend",
                                     "ap-object",
                                     "--app",
                                     "teapot",
                                     "--frames",
                                     "1",
                                     "-q",
                                     "--set",
                                     "zbuf.enabled=true",
                                     "--set",
                                     "array.features.zsend=true",
                                     "--set",
                                     "ap.object.zpath=unit"};
    for (const std::string& setting : settings) {
      args.push_back("--set");
      args.push_back(setting);
    }
    const SimResult result = run(args);
    EXPECT_NE(result.status, 0) << named;
    EXPECT_TRUE(contains(result.err, "ap.object.zpath=unit")) << describe(result);
    EXPECT_TRUE(contains(result.err, named)) << describe(result);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
