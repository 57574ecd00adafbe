// ap-tile with the system/array DMA, through soc_sim (system): the teapot
// without the DMA, with it, and with its broadcast. With the DMA the CIU
// carries nothing, both channels ran descriptors (records and constants on
// channel 0, the read-back on both), the array did the same work, and the
// broadcast writes fewer values than the reshuffled constants; without it
// the DMA is not in the SoC and the new counters are there all the same. A
// descriptor the DMA refuses ends the run with the renderer's name, not a
// crash. (The frames' identity is checked with image_diff in
// tests/system/CMakeLists.txt, ap_tile_dma_*.)
//
// Usage: ap_tile_dma_statistics <path to soc_sim> [GoogleTest options]
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "fixtures/soc_sim_test.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tessera::test::contains;
using tessera::test::describe;
using tessera::test::SimResult;

class ApTileDma : public tessera::test::SocSimTest {
 protected:
  // One frame of the teapot on ap-tile with the settings; the run's stats.json.
  json teapot(const std::string& folder, const std::vector<std::string>& settings) {
    std::vector<std::string> args = {"--backend", "ap-tile",     "--app", "teapot", "--frames",
                                     "1",         "--no-frames", "-q",    "--out",  folder};
    for (const std::string& setting : settings) args.insert(args.end(), {"--set", setting});
    const SimResult result = run(args);
    EXPECT_EQ(result.status, 0) << describe(result);
    std::ifstream in(m_dir / folder / "stats.json");
    return json::parse(in, nullptr, false);
  }
};

uint64_t counter(const json& stats, const std::string& name) {
  return stats["stats"]["driver"]["ap_tile"][name].get<uint64_t>();
}

TEST_F(ApTileDma, TheDmaCarriesTheArraysTrafficAndTheBroadcastWritesLess) {
  const json ciu = teapot("ciu", {"dma.enabled=false"});
  const json dma = teapot("dma", {"dma.enabled=true"});
  const json broadcast = teapot("broadcast", {"dma.enabled=true", "dma.broadcast=true"});
  ASSERT_FALSE(ciu.is_discarded());
  ASSERT_FALSE(dma.is_discarded());
  ASSERT_FALSE(broadcast.is_discarded());

  // Without the DMA: the CIU's words, values 4 per word and more (the
  // constants written at start-up), no descriptor, no DMA in the SoC.
  EXPECT_FALSE(ciu["stats"].contains("dma"));
  EXPECT_GT(counter(ciu, "ciu_words_written"), 0u);
  EXPECT_GE(counter(ciu, "values_written"), 4 * counter(ciu, "ciu_words_written"));
  EXPECT_EQ(counter(ciu, "values_read"), 4 * counter(ciu, "ciu_words_read"));
  EXPECT_EQ(counter(ciu, "dma_descriptors"), 0u);

  for (const json* run : {&dma, &broadcast}) {
    const json& s = *run;
    EXPECT_EQ(counter(s, "ciu_words_written"), 0u);
    EXPECT_EQ(counter(s, "ciu_words_read"), 0u);
    const uint64_t ch0 = s["stats"]["dma"]["ch0"]["descriptors"].get<uint64_t>();
    const uint64_t ch1 = s["stats"]["dma"]["ch1"]["descriptors"].get<uint64_t>();
    EXPECT_GT(ch0, 0u);
    EXPECT_GT(ch1, 0u);
    EXPECT_EQ(counter(s, "dma_descriptors"), ch0 + ch1);
    EXPECT_EQ(s["stats"]["dma"]["ch0"]["errors"], 0);
    EXPECT_EQ(s["stats"]["dma"]["ch1"]["errors"], 0);
    // The DMA's own count of what its CMEM side carried (every byte of a
    // broadcast counted once per CU there, once here).
    EXPECT_EQ(counter(s, "values_read"), s["stats"]["dma"]["cmem"]["bytes_read"].get<uint64_t>());
    // The array did the same work.
    for (const char* name : {"triangles", "cu_triangles", "passes", "busiest_cu_triangles"})
      EXPECT_EQ(counter(s, name), counter(ciu, name)) << name;
    EXPECT_EQ(s["stats"]["driver"]["ap_tile"]["cycles"], ciu["stats"]["driver"]["ap_tile"]["cycles"]);
    // Reading back costs the host far less than through the CIU.
    EXPECT_LT(counter(s, "host_read_ns"), counter(ciu, "host_read_ns"));
  }
  EXPECT_LT(counter(broadcast, "values_written"), counter(dma, "values_written"));
  EXPECT_EQ(counter(broadcast, "values_read"), counter(dma, "values_read"));
  EXPECT_EQ(counter(broadcast, "dma_descriptors"), counter(dma, "dma_descriptors"));

  // The frame record has the new figures on both paths.
  for (const json* run : {&ciu, &dma, &broadcast}) {
    const json& frame = (*run)["stats"]["frames"][0]["driver"];
    for (const char* name : {"values_written", "values_read", "dma_descriptors"})
      EXPECT_EQ(frame[name].get<double>(), static_cast<double>(counter(*run, name))) << name;
    EXPECT_DOUBLE_EQ(
        frame["values_written_per_triangle"].get<double>(),
        static_cast<double>(counter(*run, "values_written")) / static_cast<double>(counter(*run, "triangles")));
  }
}

// CMEM too small for the program's layout: the driver refuses the program
// as it loads it (ArrayDriver::load checks every CMEM variable once), before
// any descriptor reaches the DMA, with an error naming the program, the
// variable and the setting. (The DMA's own refusal of a descriptor outside
// CMEM is tested in tests/dma/test_dma.cpp.)
TEST_F(ApTileDma, ACmemTooSmallForTheProgramEndsTheRunNamingIt) {
  const SimResult result = run({"--backend", "ap-tile", "--app", "teapot", "--frames", "1", "--no-frames", "--set",
                                "dma.enabled=true", "--set", "array.cmem_bytes=2048", "--out", "out"});
  EXPECT_EQ(result.status, 1) << describe(result);
  for (const char* part : {"ap_tile.s: CMEM variable", "outside the array's 2048 bytes of CMEM", "array.cmem_bytes"})
    EXPECT_TRUE(contains(result.err, part)) << part << "\n" << describe(result);
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
