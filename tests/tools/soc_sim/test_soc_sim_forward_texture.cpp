// System tests of study_forward_texture (sw_driver/apps/forward_texture.cpp):
// the warp the host runs is the fixed-point reference's (the library's own
// tests hold it to Eq. 3), the same picture on both host models, its figures
// in stats.json, and bad input refused naming the value.
//
// Usage: test_soc_sim_forward_texture <path to soc_sim> [GoogleTest options]
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

constexpr int EXIT_USAGE = 2;

class SocSimForwardTexture : public tessera::test::SocSimTest {
 protected:
  std::string frame(const std::string& out, unsigned index) const {
    std::ifstream in(m_dir / out / ("frame_000" + std::to_string(index) + ".png"), std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  json study(const std::string& out) const {
    std::ifstream in(m_dir / out / "stats.json");
    return json::parse(in, nullptr, false)["stats"]["driver"]["study"];
  }
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
  const SimResult array =
      run({"--app", "study_forward_texture", "--backend", "ap-pixel", "--frames", "1", "--out", "array"});
  EXPECT_EQ(array.status, EXIT_USAGE) << describe(array);
  EXPECT_TRUE(contains(array.err, "--backend arm")) << describe(array);
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
