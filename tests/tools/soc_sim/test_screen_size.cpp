// System tests of the screen's size limits through soc_sim: every size the
// parameter table accepts is drawn (tests/system compares 511 and 512 with
// Mesa on every back end that takes them), and every size it refuses is a
// usage error naming the key, on every back end, before anything runs.
//
// The limit is 512 pixels either way (contract/common/screen_size.h): screen x and
// y are 9.4 fixed point, the rasterizer's interface format, which the GL
// driver hands every back end. Each array back end has its own, smaller
// limit, checked here too.
//
// Usage: test_screen_size <path to soc_sim> [GoogleTest options]
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fixtures/backend_table.h"
#include "fixtures/soc_sim_test.h"

namespace {

namespace fs = std::filesystem;
using tessera::test::contains;
using tessera::test::describe;
using tessera::test::SimResult;

constexpr int EXIT_USAGE = 2;

using ScreenSize = tessera::test::SocSimTest;

// Exit status 2, the key and the limit named, no outputs.
void expect_refused(const SimResult& result, const fs::path& out, const std::string& key, const std::string& value) {
  EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
  EXPECT_TRUE(contains(result.err, "'" + key + "'")) << describe(result);
  EXPECT_TRUE(contains(result.err, "[16, 512]")) << describe(result);
  EXPECT_TRUE(contains(result.err, value)) << describe(result);
  EXPECT_FALSE(fs::exists(out / "stats.json")) << describe(result);
  EXPECT_FALSE(fs::exists(out / "frame_0000.png")) << describe(result);
}

// 513, 1024 and 2048 (the table's old maximum) on every back end: the
// display's width at each, its height at the ends (the rasterizer takes the
// display's size).
TEST_F(ScreenSize, SizesAbove512AreRejectedNamingTheKey) {
  struct Case {
    const char* key;
    std::vector<const char*> values;
  };
  const Case display_cases[] = {{"display.width", {"513", "1024", "2048"}}, {"display.height", {"513", "2048"}}};
  const auto check = [&](const std::string& backend, const std::string& id, const Case& c) {
    for (const char* value : c.values) {
      SCOPED_TRACE(backend + " " + c.key + "=" + value);
      const std::string out = id + "_" + c.key + "_" + value;
      const SimResult result = run({"--backend", backend, "--app", "triangle", "--frames", "1", "--set",
                                    std::string(c.key) + "=" + value, "--out", out});
      expect_refused(result, m_dir / out, c.key, value);
    }
  };
  for (const tessera::test::BackendEntry& backend : tessera::test::backend_table())
    for (const Case& c : display_cases) check(backend.name, backend.id, c);
}

// The smallest size the table accepts draws on the back ends that take any
// size (the array back ends take only their own frames).
TEST_F(ScreenSize, SmallestScreenDraws) {
  for (const char* backend : {"arm", "raster"}) {
    SCOPED_TRACE(backend);
    const SimResult result = run({"--backend", backend, "--app", "fullscreen_rect", "--frames", "1", "--set",
                                  "display.width=16", "--set", "display.height=16", "--out", backend});
    ASSERT_EQ(result.status, 0) << describe(result);
    EXPECT_TRUE(fs::is_regular_file(m_dir / backend / "frame_0000.png"));
  }
}

// ap-tile draws the array's frame, array.columns x 8 by array.rows x 36: 64
// columns make 512 pixels, but 15 and 16 rows (the array's table allows
// them) make 540 and 576 lines, which no screen has: an error naming the
// array's keys, not the display's.
TEST_F(ScreenSize, ApTileFrameTallerThan512IsRejected) {
  for (const char* rows : {"15", "16"}) {
    SCOPED_TRACE(rows);
    const SimResult result =
        run({"--backend", "ap-tile", "--set", std::string("array.rows=") + rows, "--out", std::string("rows") + rows});
    EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
    EXPECT_TRUE(contains(result.err, "impossible combination")) << describe(result);
    EXPECT_TRUE(contains(result.err, "array.rows=14")) << describe(result);
    EXPECT_TRUE(contains(result.err, "512")) << describe(result);
  }
  // 511 is not a whole number of 8-pixel tiles.
  const SimResult odd = run({"--backend", "ap-tile", "--set", "display.width=511", "--out", "odd"});
  EXPECT_EQ(odd.status, EXIT_USAGE) << describe(odd);
  EXPECT_TRUE(contains(odd.err, "impossible combination")) << describe(odd);
}

// ap-pixel's CUs address their blocks with signed byte offsets: frames up
// to 256 x 256, and 511 and 512 are errors naming the display's keys.
TEST_F(ScreenSize, ApPixelAbove256IsRejected) {
  for (const char* key : {"display.width", "display.height"}) {
    for (const char* value : {"257", "511", "512"}) {
      SCOPED_TRACE(std::string(key) + "=" + value);
      const SimResult result =
          run({"--backend", "ap-pixel", "--set", std::string(key) + "=" + value, "--out", std::string(key) + value});
      EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
      EXPECT_TRUE(contains(result.err, "impossible combination")) << describe(result);
      EXPECT_TRUE(contains(result.err, "256 x 256")) << describe(result);
      EXPECT_TRUE(contains(result.err, "display.width x display.height")) << describe(result);
    }
  }
  // The array's frame beyond 256 (8 rows: 288 lines; 16 rows: 576, beyond
  // any screen) names the array's keys.
  for (const char* rows : {"8", "16"}) {
    SCOPED_TRACE(std::string("array.rows=") + rows);
    const SimResult result =
        run({"--backend", "ap-pixel", "--set", std::string("array.rows=") + rows, "--out", std::string("rows") + rows});
    EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
    EXPECT_TRUE(contains(result.err, "impossible combination")) << describe(result);
    EXPECT_TRUE(contains(result.err, "array.rows=7")) << describe(result);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
