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
