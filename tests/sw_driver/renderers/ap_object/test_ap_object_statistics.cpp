// ap-object through soc_sim (system): the teapot with a half per CU and
// with a triangle per CU. Both publish the back end's statistics, which
// agree with each other where they must (the same triangles and pixels: a
// triangle's two halves cover what the triangle covers), the utilisation is
// the ratio of the rows walked to the rows run, and the two frames are the
// same image byte for byte (the same pixels reach the host in the same
// draw order).
//
// Usage: ap_object_statistics <path to soc_sim> [GoogleTest options]
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
using tessera::test::describe;
using tessera::test::SimResult;

class ApObjectStatistics : public tessera::test::SocSimTest {
 protected:
  json teapot(const std::string& folder, const std::string& unit, bool dma = false) {
    const SimResult result =
        run({"--backend", "ap-object", "--app", "teapot", "--frames", "1", "-q", "--out", folder, "--set",
             "ap.object.unit=" + unit, "--set", std::string("dma.enabled=") + (dma ? "true" : "false")});
    EXPECT_EQ(result.status, 0) << describe(result);
    std::ifstream in(m_dir / folder / "stats.json");
    return json::parse(in, nullptr, false);
  }
  std::string frame(const std::string& folder) {
    std::ifstream in(m_dir / folder / "frame_0000.png", std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
};

uint64_t counter(const json& stats, const std::string& name) {
  return stats["stats"]["driver"]["ap_object"][name].get<uint64_t>();
}

TEST_F(ApObjectStatistics, HalvesAndTrianglesDrawTheSameFrame) {
  const json half = teapot("half", "half");
  const json triangle = teapot("triangle", "triangle");
  ASSERT_FALSE(half.is_discarded());
  ASSERT_FALSE(triangle.is_discarded());
  for (const json* run : {&half, &triangle}) {
    const json& s = *run;
    for (const char* name : {"triangles", "units", "pieces", "runs", "cycles", "busy_lanes", "lane_rows", "walked_rows",
                             "pixels_emitted", "pixels_written", "ciu_words_written", "ciu_words_read"})
      EXPECT_GT(counter(s, name), 0u) << name;
    EXPECT_LE(counter(s, "walked_rows"), counter(s, "lane_rows"));
    // The driver divides in floating point (no 64-bit division on the ARM).
    const uint64_t permille = counter(s, "walked_rows") * 1000 / counter(s, "lane_rows");
    EXPECT_LE(counter(s, "cu_utilisation_permille"), permille + 1);
    EXPECT_GE(counter(s, "cu_utilisation_permille") + 1, permille);
    EXPECT_LE(counter(s, "pixels_written"), counter(s, "pixels_emitted"));
    EXPECT_LE(counter(s, "busy_lanes"), 96 * counter(s, "runs"));
    EXPECT_EQ(counter(s, "runs"), counter(s, "runs_w8") + counter(s, "runs_w16") + counter(s, "runs_w32"));
  }
  EXPECT_EQ(counter(half, "triangles"), counter(triangle, "triangles"));
  EXPECT_EQ(counter(half, "pixels_emitted"), counter(triangle, "pixels_emitted"));
  EXPECT_EQ(counter(half, "pixels_written"), counter(triangle, "pixels_written"));
  EXPECT_EQ(counter(triangle, "units"), counter(triangle, "triangles"));
  EXPECT_GT(counter(half, "units"), counter(half, "triangles"));
  const std::string a = frame("half"), b = frame("triangle");
  EXPECT_FALSE(a.empty());
  EXPECT_TRUE(a == b) << "the frames differ";
  EXPECT_EQ(counter(half, "values_written"), 4 * counter(half, "ciu_words_written"));
  EXPECT_EQ(counter(half, "values_read"), 4 * counter(half, "ciu_words_read"));
}

// With the DMA: the CIU carries nothing, the DMA's own counts are the back
// end's, the array did the same work and the frame is the same.
TEST_F(ApObjectStatistics, TheDmaCarriesTheSameFrame) {
  for (const char* unit : {"half", "triangle"}) {
    const std::string ciu_folder = std::string("ciu_") + unit, dma_folder = std::string("dma_") + unit;
    const json ciu = teapot(ciu_folder, unit);
    const json dma = teapot(dma_folder, unit, true);
    ASSERT_FALSE(ciu.is_discarded());
    ASSERT_FALSE(dma.is_discarded());
    EXPECT_EQ(counter(dma, "ciu_words_written"), 0u);
    EXPECT_EQ(counter(dma, "ciu_words_read"), 0u);
    EXPECT_GT(counter(dma, "dma_descriptors"), 0u);
    EXPECT_EQ(counter(ciu, "dma_descriptors"), 0u);
    EXPECT_EQ(dma["stats"]["dma"]["ch0"]["errors"], 0);
    EXPECT_EQ(counter(dma, "values_written"), dma["stats"]["dma"]["cmem"]["bytes_written"].get<uint64_t>());
    EXPECT_EQ(counter(dma, "values_read"), dma["stats"]["dma"]["cmem"]["bytes_read"].get<uint64_t>());
    for (const char* name : {"runs", "cycles", "pieces", "pixels_emitted", "pixels_written", "walked_rows"})
      EXPECT_EQ(counter(dma, name), counter(ciu, name)) << unit << " " << name;
    EXPECT_TRUE(frame(ciu_folder) == frame(dma_folder)) << unit << ": the frames differ";
  }
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
