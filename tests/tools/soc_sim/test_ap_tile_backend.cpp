// System tests of the ap-tile back end's own configuration through soc_sim:
// ap.tile.texcoords=always runs the texcoord stage in every pass of a frame
// that has no texture, and changes no pixel; the default skips the stage; a
// value it does not know is rejected naming the key and the values allowed.
// ap.tile.program: tuned, named, is the default, frame and statistics; the
// study's program draws the same passes with more array cycles and reads
// the blue array back too; with the DMA, the same frame and array work
// without a CIU word.
//
// Usage: test_ap_tile_backend <path to soc_sim> [GoogleTest options]
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
using tessera::test::read_file;
using tessera::test::SimResult;

constexpr int EXIT_USAGE = 2;

class ApTileBackend : public tessera::test::SocSimTest {
 protected:
  // One frame of the untextured teapot (many passes) on ap-tile with the
  // extra settings; the run's stats.json.
  json teapot(const std::string& folder, const std::vector<std::string>& settings) {
    std::vector<std::string> args = {"--backend", "ap-tile", "--app", "teapot", "--frames", "1", "--out", folder};
    for (const std::string& setting : settings) args.insert(args.end(), {"--set", setting});
    const SimResult result = run(args);
    EXPECT_EQ(result.status, 0) << describe(result);
    std::ifstream in(m_dir / folder / "stats.json");
    return json::parse(in, nullptr, false);
  }
  // One frame of `app` on ap-tile with the settings; the run's stats.json
  // (the run itself in m_last).
  json scene(const std::string& folder, const std::string& app, const std::vector<std::string>& settings) {
    std::vector<std::string> args = {"--backend", "ap-tile", "--app", app, "--frames", "1", "--out", folder};
    for (const std::string& setting : settings) args.insert(args.end(), {"--set", setting});
    m_last = run(args);
    EXPECT_EQ(m_last.status, 0) << describe(m_last);
    std::ifstream in(m_dir / folder / "stats.json");
    return json::parse(in, nullptr, false);
  }
  SimResult m_last;
};

// How many times the array ran the stage: the executions of its first
// instruction in the array's profile (0 when it never ran).
uint64_t stage_runs(const json& stats, const std::string& stage) {
  uint64_t first_word = UINT64_MAX, runs = 0;
  for (const json& entry : stats["stats"]["array"]["profile"])
    if (entry["stage"] == stage && entry["word"].get<uint64_t>() < first_word) {
      first_word = entry["word"].get<uint64_t>();
      runs = entry["executions"].get<uint64_t>();
    }
  return runs;
}

TEST_F(ApTileBackend, TexcoordsAlwaysRunsTheStageInEveryPassAndChangesNoPixel) {
  const json textured = teapot("textured", {});
  const json always = teapot("always", {"ap.tile.texcoords=always"});
  ASSERT_FALSE(textured.is_discarded());
  ASSERT_FALSE(always.is_discarded());
  EXPECT_EQ(textured["config"]["ap"]["tile"]["texcoords"], "textured");
  EXPECT_EQ(always["config"]["ap"]["tile"]["texcoords"], "always");

  const json& counters_textured = textured["stats"]["driver"]["ap_tile"];
  const json& counters_always = always["stats"]["driver"]["ap_tile"];
  const uint64_t passes = counters_always["passes"].get<uint64_t>();
  EXPECT_GT(passes, 1u);
  EXPECT_EQ(counters_textured["passes"], passes);
  // The teapot has no texture: by default the stage never runs.
  EXPECT_EQ(counters_textured["cycles"]["texcoord"], 0);
  EXPECT_EQ(stage_runs(textured, "texcoord"), 0u);
  EXPECT_GT(counters_always["cycles"]["texcoord"].get<uint64_t>(), 0u);
  EXPECT_EQ(stage_runs(always, "texcoord"), passes);
  EXPECT_EQ(stage_runs(always, "fill"), passes);
  // The other stages are untouched; the extra stage only costs time.
  for (const char* stage : {"fill", "depth", "colour", "clear_colour", "clear_depth"})
    EXPECT_EQ(counters_always["cycles"][stage], counters_textured["cycles"][stage]) << stage;
  EXPECT_GT(always["stats"]["frames"][0]["render_ns"].get<double>(),
            textured["stats"]["frames"][0]["render_ns"].get<double>());
  // Computed, not applied: the frame is the same picture.
  const std::string frame_textured = read_file(m_dir / "textured/frame_0000.png");
  EXPECT_FALSE(frame_textured.empty());
  EXPECT_EQ(frame_textured, read_file(m_dir / "always/frame_0000.png"));
}

TEST_F(ApTileBackend, UnknownTexcoordsValueNamesTheKeyAndTheValues) {
  const SimResult result =
      run({"--backend", "ap-tile", "--app", "triangle", "--set", "ap.tile.texcoords=sometimes", "--out", "out"});
  EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
  for (const char* part : {"ap.tile.texcoords", "sometimes", "textured", "always"})
    EXPECT_TRUE(contains(result.err, part)) << part << "\n" << describe(result);
  EXPECT_FALSE(fs::exists(m_dir / "out/stats.json"));
}

TEST_F(ApTileBackend, ExplicitTunedProgramIsTheDefault) {
  const json implicit = teapot("implicit", {});
  const json named = teapot("named", {"ap.tile.program=tuned"});
  ASSERT_FALSE(implicit.is_discarded());
  ASSERT_FALSE(named.is_discarded());
  EXPECT_EQ(implicit["config"]["ap"]["tile"]["program"], "tuned");
  EXPECT_EQ(named["config"]["ap"]["tile"]["program"], "tuned");
  EXPECT_EQ(implicit["stats"], named["stats"]);
  const std::string frame = read_file(m_dir / "implicit/frame_0000.png");
  EXPECT_FALSE(frame.empty());
  EXPECT_EQ(frame, read_file(m_dir / "named/frame_0000.png"));
}

TEST_F(ApTileBackend, StudyProgramRunsTheSamePassesInMoreCycles) {
  const json tuned = teapot("tuned", {});
  const json study = teapot("study", {"ap.tile.program=study"});
  ASSERT_FALSE(tuned.is_discarded());
  ASSERT_FALSE(study.is_discarded());
  EXPECT_EQ(study["config"]["ap"]["tile"]["program"], "study");
  const json& t = tuned["stats"]["driver"]["ap_tile"];
  const json& s = study["stats"]["driver"]["ap_tile"];
  const uint64_t passes = s["passes"].get<uint64_t>();
  EXPECT_GT(passes, 1u);
  // The same binning and passes: only the program and its records differ.
  for (const char* figure : {"passes", "triangles", "cu_triangles", "busiest_cu_triangles"})
    EXPECT_EQ(s[figure], t[figure]) << figure;
  EXPECT_EQ(stage_runs(study, "fill"), passes);
  EXPECT_EQ(stage_runs(study, "colour"), passes);
  // Every variable loaded and stored per statement: each stage is slower.
  for (const char* stage : {"fill", "depth", "colour"})
    EXPECT_GT(s["cycles"][stage].get<uint64_t>(), t["cycles"][stage].get<uint64_t>()) << stage;
  // Three CIU words per four pixels read back (red, green, blue) against
  // two (RGB565), and the CMEM each program declares.
  EXPECT_EQ(2 * s["ciu_words_read"].get<uint64_t>(), 3 * t["ciu_words_read"].get<uint64_t>());
  EXPECT_EQ(t["cmem_bytes_per_cu"], 2999);
  EXPECT_EQ(s["cmem_bytes_per_cu"], 3315);
  EXPECT_FALSE(read_file(m_dir / "study/frame_0000.png").empty());
}

TEST_F(ApTileBackend, UnknownProgramValueNamesTheKeyAndTheValues) {
  const SimResult result =
      run({"--backend", "ap-tile", "--app", "triangle", "--set", "ap.tile.program=fast", "--out", "out"});
  EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
  for (const char* part : {"ap.tile.program", "fast", "tuned", "study"})
    EXPECT_TRUE(contains(result.err, part)) << part << "\n" << describe(result);
  EXPECT_FALSE(fs::exists(m_dir / "out/stats.json"));
}

TEST_F(ApTileBackend, StudyProgramWithTheDmaMovesEveryCmemByteThroughIt) {
  const json ciu = teapot("study_ciu", {"ap.tile.program=study"});
  const json dma = teapot("study_dma", {"ap.tile.program=study", "dma.enabled=true"});
  ASSERT_FALSE(ciu.is_discarded());
  ASSERT_FALSE(dma.is_discarded());
  const json& c = ciu["stats"]["driver"]["ap_tile"];
  const json& d = dma["stats"]["driver"]["ap_tile"];
  EXPECT_EQ(d["ciu_words_written"], 0);
  EXPECT_EQ(d["ciu_words_read"], 0);
  EXPECT_GT(d["dma_descriptors"].get<uint64_t>(), 0u);
  // The array's work is the same program on the same records.
  EXPECT_EQ(d["passes"], c["passes"]);
  EXPECT_EQ(d["cycles"], c["cycles"]);
  EXPECT_EQ(read_file(m_dir / "study_ciu/frame_0000.png"), read_file(m_dir / "study_dma/frame_0000.png"));
}

// ap.tile.texture_warp: off, named, is the default: the textured quad's
// frame and statistics.
TEST_F(ApTileBackend, TextureWarpOffIsTheDefault) {
  const json implicit = scene("warp_implicit", "textured_quad", {});
  const json named = scene("warp_named", "textured_quad", {"ap.tile.texture_warp=off"});
  ASSERT_FALSE(implicit.is_discarded());
  ASSERT_FALSE(named.is_discarded());
  EXPECT_EQ(implicit["stats"], named["stats"]);
  EXPECT_FALSE(implicit["stats"]["driver"]["ap_tile"].contains("warp"));
  EXPECT_EQ(read_file(m_dir / "warp_implicit/frame_0000.png"), read_file(m_dir / "warp_named/frame_0000.png"));
}

// The warp's lines and results through the DMA draw the frame the CIU's
// draw: the array's results are the same bit for bit.
TEST_F(ApTileBackend, TextureWarpThroughTheDmaDrawsTheCiusFrame) {
  const json ciu = scene("warp_ciu", "textured_quad", {"ap.tile.texture_warp=array"});
  const json dma = scene("warp_dma", "textured_quad", {"ap.tile.texture_warp=array", "dma.enabled=true"});
  ASSERT_FALSE(ciu.is_discarded());
  ASSERT_FALSE(dma.is_discarded());
  for (const json* stats : {&ciu, &dma}) {
    const json& warp = (*stats)["stats"]["driver"]["ap_tile"]["warp"];
    EXPECT_EQ(warp["textures"], 1);
    EXPECT_EQ(warp["refused"], 0);
    EXPECT_GT(warp["pixels"].get<uint64_t>(), 5000u);
    EXPECT_GT(warp["array_runs"].get<uint64_t>(), 0u);
  }
  EXPECT_EQ(ciu["stats"]["driver"]["ap_tile"]["warp"]["array_cycles"],
            dma["stats"]["driver"]["ap_tile"]["warp"]["array_cycles"]);
  EXPECT_GT(dma["stats"]["driver"]["ap_tile"]["dma_descriptors"].get<uint64_t>(),
            ciu["stats"]["driver"]["ap_tile"]["dma_descriptors"].get<uint64_t>());
  EXPECT_EQ(read_file(m_dir / "warp_ciu/frame_0000.png"), read_file(m_dir / "warp_dma/frame_0000.png"));
  // Perspective-correct where the look-ups' affine s and t are not: the
  // frames differ.
  const json lookups = scene("warp_off", "textured_quad", {});
  ASSERT_FALSE(lookups.is_discarded());
  EXPECT_NE(read_file(m_dir / "warp_ciu/frame_0000.png"), read_file(m_dir / "warp_off/frame_0000.png"));
}

// mipmap_floor's strips reach 9,966 texels along t, beyond the program's
// 512 a line: each strip's texture is warped in bands, each at the level
// of its scale; the frame is not the look-ups' frame.
TEST_F(ApTileBackend, TextureWarpCutsALongRegionIntoBands) {
  const json warped = scene("floor_warp", "mipmap_floor", {"ap.tile.texture_warp=array"});
  const json lookups = scene("floor_off", "mipmap_floor", {});
  ASSERT_FALSE(warped.is_discarded());
  ASSERT_FALSE(lookups.is_discarded());
  EXPECT_EQ(warped["stats"]["driver"]["ap_tile"]["warp"]["refused"], 0);
  EXPECT_EQ(warped["stats"]["driver"]["ap_tile"]["warp"]["textures"], 6);
  EXPECT_NE(read_file(m_dir / "floor_warp/frame_0000.png"), read_file(m_dir / "floor_off/frame_0000.png"));
}

// texture_formats draws two GL_ALPHA textures: their colour is the
// fragment's, so they keep the look-ups, each with a warning naming why.
TEST_F(ApTileBackend, TextureWarpLeavesAlphaTexturesToTheLookUps) {
  const json warped = scene("formats_warp", "texture_formats", {"ap.tile.texture_warp=array"});
  ASSERT_FALSE(warped.is_discarded());
  EXPECT_EQ(warped["stats"]["driver"]["ap_tile"]["warp"]["refused"], 2);
  EXPECT_GT(warped["stats"]["driver"]["ap_tile"]["warp"]["textures"].get<uint64_t>(), 0u);
  EXPECT_TRUE(contains(m_last.err + m_last.out,
                       "of this frame textured by look-ups on the host: an alpha texture (its colour is the "
                       "fragment's)"))
      << describe(m_last);
}

TEST_F(ApTileBackend, BadTextureWarpValuesNameTheKey) {
  for (const char* setting : {"ap.tile.texture_warp=host", "ap.tile.texture_warp_width=9"}) {
    const SimResult result = run({"--backend", "ap-tile", "--app", "triangle", "--set", setting, "--out", "out"});
    EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
    EXPECT_TRUE(contains(result.err, std::string(setting).substr(0, std::string(setting).find('='))))
        << describe(result);
  }
}

// The key belongs to the configuration whichever back end runs, so that one
// configuration file serves every back end of an experiment.
TEST_F(ApTileBackend, TheKeyIsAcceptedWithAnotherBackEnd) {
  const SimResult result = run({"--backend", "arm", "--app", "triangle", "--frames", "1", "--set",
                                "ap.tile.texcoords=always", "--no-frames", "--out", "out"});
  EXPECT_EQ(result.status, 0) << describe(result);
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
