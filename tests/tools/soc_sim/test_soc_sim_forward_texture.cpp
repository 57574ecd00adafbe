// System tests of study_forward_texture (sw_driver/apps/forward_texture.cpp):
// the warp the host runs is the fixed-point reference's (the library's own
// tests hold it to Eq. 3), the same picture on both host models, the same
// picture again from the array program (through the CIU and the DMA, on
// both host models; with the factors computed, and looked up in the shared
// table for the box and the tent, lockstep and skewed), its figures in
// stats.json, and bad input refused naming the value.
//
// Usage: test_soc_sim_forward_texture <path to soc_sim> [GoogleTest options]
#include <fstream>
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

constexpr int EXIT_USAGE = 2;

class SocSimForwardTexture : public tessera::test::SocSimTest {
 protected:
  json stats(const std::string& out) const {
    std::ifstream in(m_dir / out / "stats.json");
    return json::parse(in, nullptr, false)["stats"];
  }
  json study(const std::string& out) const { return stats(out)["driver"]["study"]; }
};

TEST_F(SocSimForwardTexture, BothHostModelsWarpTheSamePicture) {
  const std::vector<std::string> small = {"--app", "study_forward_texture", "--frames", "1",
                                          "--",    "--texture-size",        "48",       "--filter",
                                          "tent",  "--filter-width",        "3"};
  std::vector<std::string> native = {"--out", "native"}, iss = {"--out", "iss", "--set", "host.model=iss"};
  native.insert(native.end(), small.begin(), small.end());
  iss.insert(iss.end(), small.begin(), small.end());
  const SimResult on_native = run(native);
  ASSERT_EQ(on_native.status, 0) << describe(on_native);
  const SimResult on_iss = run(iss);
  ASSERT_EQ(on_iss.status, 0) << describe(on_iss);
  ASSERT_GT(frame("native", 0).size(), 1000u);
  EXPECT_EQ(frame("native", 0), frame("iss", 0));
  EXPECT_EQ(study("native")["texture_size"], 48);
  EXPECT_EQ(study("native")["filter_width"], 3);
  EXPECT_GT(study("native")["warp_ns"].get<double>(), 0.0);
  EXPECT_GT(study("iss")["warp_ns"].get<double>(), 0.0);
}

TEST_F(SocSimForwardTexture, TheArrayWarpsTheHostsPictureByteForByte) {
  // Rows first (the default matrix) and columns first (a quarter turn and
  // more), each on the host and on the array through the CIU (ap-pixel)
  // and the DMA (ap-tile), natively and on the ISS.
  const std::vector<std::vector<std::string>> warps = {
      {"--texture-size", "40", "--filter-width", "3"},
      {"--texture-size", "32", "--filter-width", "1", "--matrix", "0.3,-0.8,100,0.8,0.3,20,0,0.001,1"}};
  struct Run {
    std::string name;
    std::vector<std::string> settings;
  };
  const std::vector<Run> runs = {
      {"host", {"--backend", "arm", "--set", "display.width=192", "--set", "display.height=144"}},
      {"ciu", {"--backend", "ap-pixel"}},
      {"dma", {"--backend", "ap-tile", "--set", "dma.enabled=true"}},
      {"dma_iss", {"--backend", "ap-tile", "--set", "dma.enabled=true", "--set", "host.model=iss"}},
      {"ciu_iss", {"--backend", "ap-pixel", "--set", "host.model=iss"}}};
  for (std::size_t w = 0; w < warps.size(); ++w) {
    for (const Run& r : runs) {
      const std::string out = r.name + std::to_string(w);
      std::vector<std::string> args = {"--app", "study_forward_texture", "--frames", "1", "--out", out};
      args.insert(args.end(), r.settings.begin(), r.settings.end());
      args.push_back("--");
      args.insert(args.end(), warps[w].begin(), warps[w].end());
      const SimResult result = run(args);
      ASSERT_EQ(result.status, 0) << out << ": " << describe(result);
      EXPECT_TRUE(contains(result.out, r.name == "host" ? "on the host" : "on the array")) << describe(result);
      if (r.name == "host") {
        ASSERT_GT(frame(out, 0).size(), 1000u);
        continue;
      }
      EXPECT_EQ(frame(out, 0), frame("host" + std::to_string(w), 0)) << out;
      const json figures = study(out);
      EXPECT_GT(figures["array_runs"].get<int>(), 0) << out;
      EXPECT_GT(figures["array_cycles"].get<double>(), 0.0) << out;
      const bool dma = r.name.rfind("dma", 0) == 0;
      EXPECT_EQ(figures["through_dma"], dma ? 1 : 0) << out;
      EXPECT_EQ(figures["dma_descriptors"].get<int>() > 0, dma) << out;
      EXPECT_GT(figures["wait_ns"].get<double>(), 0.0) << out;
    }
  }
  EXPECT_EQ(study("host0")["columns_first"], 0);
  EXPECT_EQ(study("host1")["columns_first"], 1);
}

TEST_F(SocSimForwardTexture, TheTableProgramWarpsTheHostsPictureByteForByte) {
  // --array-factors table: the box and the tent of width 3 (a table of 768
  // entries), lockstep and under delayed execution, through the DMA and the
  // CIU; F lookups a border, the table written once.
  const std::vector<std::string> lut = {"--set", "array.features.lut=true", "--set", "array.lut.entries=1024"};
  struct Run {
    std::string name;
    std::vector<std::string> settings;
  };
  const std::vector<Run> runs = {
      {"host", {"--backend", "arm", "--set", "display.width=192", "--set", "display.height=144"}},
      {"dma", {"--backend", "ap-tile", "--set", "dma.enabled=true"}},
      {"dma_skew", {"--backend", "ap-tile", "--set", "dma.enabled=true", "--set", "array.issue_skew=lane"}},
      {"ciu_skew", {"--backend", "ap-pixel", "--set", "array.issue_skew=lane"}}};
  const int texels = 40, width = 3;
  for (const std::string filter : {"box", "tent"}) {
    for (const Run& r : runs) {
      const std::string out = r.name + "_" + filter;
      const bool on_array = r.name != "host";
      std::vector<std::string> args = {"--app", "study_forward_texture", "--frames", "1", "--out", out};
      args.insert(args.end(), r.settings.begin(), r.settings.end());
      if (on_array) args.insert(args.end(), lut.begin(), lut.end());
      args.insert(args.end(), {"--", "--texture-size", std::to_string(texels), "--filter-width", std::to_string(width),
                               "--filter", filter});
      if (on_array) args.insert(args.end(), {"--array-factors", "table"});
      const SimResult result = run(args);
      ASSERT_EQ(result.status, 0) << out << ": " << describe(result);
      if (!on_array) continue;
      EXPECT_TRUE(contains(result.out, "on the array (factors from the lookup table)")) << describe(result);
      EXPECT_EQ(frame(out, 0), frame("host_" + filter, 0)) << out;
      const json array = stats(out)["array"];
      const int runs_made = study(out)["array_runs"].get<int>();
      EXPECT_EQ(array["mix"]["lut"].get<int>(), runs_made * (texels + 1) * width) << out;
      EXPECT_EQ(array["lut"]["host_writes"].get<int>(), 256 * width) << out;
      // Lockstep every lut waits for 95 more CUs; skewed the luts are far
      // enough apart on the J2210's cycles that no port is ever busy.
      EXPECT_EQ(array["lut"]["stall_cycles"].get<int>(), r.name == "dma" ? 95 * array["mix"]["lut"].get<int>() : 0)
          << out;
    }
  }
}

TEST_F(SocSimForwardTexture, TheChainMappingWarpsTheHostsPictureByteForByte) {
  // --array-mapping chain with the Image Blender's switches it needs
  // (delayed execution, the row ring, the selecting adds, the table): a
  // border per CU, four lines a run; box and tent of width 2, through the
  // DMA and the CIU.
  const std::vector<std::string> preset = {"--set", "array.issue_skew=lane",
                                           "--set", "array.row_ring=true",
                                           "--set", "array.features.neighbour_add=true",
                                           "--set", "array.features.lut=true",
                                           "--set", "array.lut.entries=1024"};
  struct Run {
    std::string name;
    std::vector<std::string> settings;
  };
  const std::vector<Run> runs = {
      {"host", {"--backend", "arm", "--set", "display.width=192", "--set", "display.height=144"}},
      {"chain_dma", {"--backend", "ap-tile", "--set", "dma.enabled=true"}},
      {"chain_ciu", {"--backend", "ap-pixel"}}};
  const int texels = 50, width = 2;
  for (const std::string filter : {"box", "tent"}) {
    for (const Run& r : runs) {
      const std::string out = r.name + "_" + filter;
      const bool on_array = r.name != "host";
      std::vector<std::string> args = {"--app", "study_forward_texture", "--frames", "1", "--out", out};
      args.insert(args.end(), r.settings.begin(), r.settings.end());
      if (on_array) args.insert(args.end(), preset.begin(), preset.end());
      args.insert(args.end(), {"--", "--texture-size", std::to_string(texels), "--filter-width", std::to_string(width),
                               "--filter", filter});
      if (on_array) args.insert(args.end(), {"--array-mapping", "chain"});
      const SimResult result = run(args);
      ASSERT_EQ(result.status, 0) << out << ": " << describe(result);
      if (!on_array) continue;
      EXPECT_TRUE(contains(result.out, "van Sinten's mapping")) << describe(result);
      EXPECT_EQ(frame(out, 0), frame("host_" + filter, 0)) << out;
      // A run holds one line per CU row.
      const json figures = study(out);
      EXPECT_LE(figures["array_lines"].get<int>(), 4 * figures["array_runs"].get<int>()) << out;
      EXPECT_GT(stats(out)["array"]["mix"]["nadds"].get<int>(), 0) << out;
    }
  }
}

TEST_F(SocSimForwardTexture, BadInputIsRefusedNamingTheValue) {
  struct Case {
    std::vector<std::string> args;
    std::string names;
  };
  const Case cases[] = {
      {{"--matrix", "2,0,0,0,1,0,0,0,1"}, "magnification"},  // a texel two pixels wide
      {{"--matrix", "1,0,0,0,1,0"}, "nine decimals"},       {{"--matrix", "1,0,0,0,1,0,0,0,x"}, "'x' (entry I)"},
      {{"--matrix", "1,2,0,2,4,0,0,0,1"}, "singular"},      {{"--filter-width", "9"}, "--filter-width"},
      {{"--filter", "gauss"}, "--filter is box or tent"},   {{"--texture-size", "1"}, "--texture-size"},
      {{"--sharpen", "1"}, "unknown option '--sharpen'"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"--app", "study_forward_texture", "--frames", "1", "--out", "bad", "--force",
                                     "--"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const SimResult result = run(args);
    EXPECT_EQ(result.status, EXIT_USAGE) << c.names << ": " << describe(result);
    EXPECT_TRUE(contains(result.err, c.names) || contains(result.out, c.names)) << c.names << ": " << describe(result);
  }
  // What the array program cannot run, and a back end that has no warp.
  const Case array_cases[] = {
      {{"--backend", "ap-pixel", "--", "--filter", "tent"}, "box filter's factors only"},
      {{"--backend", "ap-tile", "--", "--texture-size", "600", "--matrix", "0.3,0,10,0,0.2,10,0,0,1"},
       "600 texels does not fit"},
      {{"--backend", "raster"}, "not on raster"},
      {{"--backend", "ap-pixel", "--set", "array.registers=4"}, "array.registers = 4"},
      // The table program needs the table, and one large enough for 256 F entries.
      {{"--backend", "ap-tile", "--", "--array-factors", "table"}, "array.features.lut = false"},
      {{"--backend", "ap-tile", "--set", "array.features.lut=true", "--", "--array-factors", "table", "--filter",
        "tent", "--filter-width", "2"},
       "filter width F = 2 needs 512 lookup table entries (256 phases x F), more than array.lut.entries = 256"},
      {{"--backend", "arm", "--", "--array-factors", "table"}, "--array-factors table is the array program's"},
      {{"--backend", "ap-tile", "--", "--array-factors", "lut"}, "--array-factors is computed or table, not 'lut'"},
      // The chain needs the Image Blender's switches.
      {{"--backend", "ap-tile", "--", "--array-mapping", "chain"},
       "--array-mapping chain: van Sinten's mapping (resample_chain.s) needs array.issue_skew=lane"},
      {{"--backend", "ap-tile", "--set", "array.issue_skew=lane", "--", "--array-mapping", "chain"},
       "needs array.row_ring=true"},
      {{"--backend", "ap-tile", "--", "--array-mapping", "chain", "--array-factors", "computed"},
       "--array-mapping chain looks its factors up"},
      {{"--backend", "arm", "--", "--array-mapping", "chain"}, "--array-mapping chain is an array program's"},
      {{"--backend", "ap-tile", "--", "--array-mapping", "rows"}, "--array-mapping is lines or chain, not 'rows'"},
  };
  for (const Case& c : array_cases) {
    std::vector<std::string> args = {"--app", "study_forward_texture", "--frames", "1", "--out", "bad", "--force"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const SimResult result = run(args);
    EXPECT_EQ(result.status, EXIT_USAGE) << c.names << ": " << describe(result);
    EXPECT_TRUE(contains(result.err, c.names)) << c.names << ": " << describe(result);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
