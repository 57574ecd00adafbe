// What an earlier run of soc_sim left (tools/soc_sim/run_outputs.h): its
// frames, statistics and traces are found by name and content, files soc_sim
// did not write are never taken for them, and removal takes exactly the
// files found.
#include "run_outputs.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "fixtures/scratch_folder_test.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

const char* const STATS = R"({"application": "pattern", "config": {}, "exit_status": 0, "stats": {}})";
const char* const TRACE =
    "$date\n     --- --- ----       --------\n$end\n\n$version\n SystemC 2.3.4-Accellera --- Jan 13 2023 17:28:48\n"
    "$end\n\n$timescale\n     1 ps\n$end\n\n$scope module SystemC $end\n$scope module soc $end\n"
    "$scope module bus $end\n$var wire    1  aaaaa  host_request       $end\n";

class RunOutputs : public tessera::test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    fs::create_directory(m_dir / "out");
  }

  fs::path write(const std::string& name, const std::string& text) {
    fs::path path = m_dir / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  OutputPaths paths(const std::string& stats = "out/stats.json", const std::string& trace = "") const {
    return {m_dir / "out", m_dir / stats, trace.empty() ? fs::path() : m_dir / trace, {}, {}};
  }
};

TEST(FrameNames, AreFrameUnderscoreFourOrMoreDigitsPng) {
  EXPECT_EQ(frame_file_name(0), "frame_0000.png");
  EXPECT_EQ(frame_file_name(12345), "frame_12345.png");
  for (const char* name : {"frame_0000.png", "frame_0399.png", "frame_12345.png"})
    EXPECT_TRUE(is_frame_file_name(name));
  for (const char* name : {"frame_000.png", "frame_.png", "frame_00a0.png", "frame_0000.png.bak", "frame_0000.jpg",
                           "myframe_0000.png", "frame-0000.png", "frame_final.png", "Frame_0000.png"})
    EXPECT_FALSE(is_frame_file_name(name)) << name;
}

TEST_F(RunOutputs, AnEmptyFolderHoldsNothing) {
  EXPECT_TRUE(find_earlier_outputs(paths()).empty());
  EXPECT_TRUE(
      find_earlier_outputs({m_dir / "no_such_folder", m_dir / "no_such_folder/stats.json", {}, {}, {}}).empty());
}

TEST_F(RunOutputs, FindsFramesStatisticsAndTracesAndNothingElse) {
  for (const char* frame : {"out/frame_0002.png", "out/frame_0000.png", "out/frame_0001.png"}) write(frame, "png");
  write("out/stats.json", STATS);
  write("out/trace.vcd", TRACE);
  write("out/other_run.vcd", TRACE);
  // Not soc_sim's: other names, other content, another folder.
  write("out/notes.txt", "mine");
  write("out/frame_final.png", "mine");
  write("out/results.json", STATS);
  write("out/gtkwave.vcd", "$date\n today\n$end\n$version\n Icarus Verilog\n$end\n$scope module top $end\n");
  write("out/empty.vcd", "");
  fs::create_directory(m_dir / "out/sub");
  write("out/sub/frame_0000.png", "png");
  write("out/sub/stats.json", STATS);

  const EarlierOutputs found = find_earlier_outputs(paths());
  ASSERT_EQ(found.frames.size(), 3u);
  EXPECT_EQ(found.frames[0], m_dir / "out/frame_0000.png");
  EXPECT_EQ(found.frames[2], m_dir / "out/frame_0002.png");
  ASSERT_EQ(found.files.size(), 3u);
  EXPECT_EQ(found.files[0], m_dir / "out/other_run.vcd");
  EXPECT_EQ(found.files[1], m_dir / "out/stats.json");
  EXPECT_EQ(found.files[2], m_dir / "out/trace.vcd");
  EXPECT_TRUE(found.foreign.empty());
  EXPECT_EQ(describe_outputs(found, m_dir / "out"),
            "3 frames (frame_0000.png ... frame_0002.png), other_run.vcd, stats.json, trace.vcd");

  remove_earlier_outputs(found);
  for (const char* gone : {"out/frame_0000.png", "out/frame_0001.png", "out/frame_0002.png", "out/stats.json",
                           "out/trace.vcd", "out/other_run.vcd"})
    EXPECT_FALSE(fs::exists(m_dir / gone)) << gone;
  for (const char* kept : {"out/notes.txt", "out/frame_final.png", "out/results.json", "out/gtkwave.vcd",
                           "out/empty.vcd", "out/sub/frame_0000.png", "out/sub/stats.json"})
    EXPECT_TRUE(fs::exists(m_dir / kept)) << kept;
  EXPECT_TRUE(find_earlier_outputs(paths()).empty());
}

TEST_F(RunOutputs, ThisRunsOwnPathsOutsideTheFolderCount) {
  write("run.json", STATS);
  write("trace.vcd", TRACE);
  const EarlierOutputs found = find_earlier_outputs(paths("run.json", "trace.vcd"));
  ASSERT_EQ(found.files.size(), 2u);
  EXPECT_TRUE(found.frames.empty());
  EXPECT_EQ(describe_outputs(found, m_dir / "out"),
            (m_dir / "run.json").string() + ", " + (m_dir / "trace.vcd").string());
}

TEST_F(RunOutputs, FilesSocSimDidNotWriteAtItsPathsAreForeign) {
  write("out/stats.json", "my own notes");
  write("mine.vcd", "$date\n today\n$end\n");
  const EarlierOutputs found = find_earlier_outputs(paths("out/stats.json", "mine.vcd"));
  ASSERT_EQ(found.foreign.size(), 2u);
  EXPECT_EQ(found.foreign[0], m_dir / "out/stats.json");
  EXPECT_EQ(found.foreign[1], m_dir / "mine.vcd");
  EXPECT_TRUE(found.empty());
  remove_earlier_outputs(found);
  EXPECT_TRUE(fs::exists(m_dir / "out/stats.json"));
  EXPECT_TRUE(fs::exists(m_dir / "mine.vcd"));
  // stats.json in the folder that this run does not write to is left alone.
  EXPECT_TRUE(find_earlier_outputs(paths("elsewhere.json")).foreign.empty());
}

TEST_F(RunOutputs, EmptyFilesAtThisRunsPathsHoldNothingToLose) {
  write("out/stats.json", "");
  write("trace.vcd", "");
  const EarlierOutputs found = find_earlier_outputs(paths("out/stats.json", "trace.vcd"));
  EXPECT_TRUE(found.empty());
  EXPECT_TRUE(found.foreign.empty());
}

TEST_F(RunOutputs, StatisticsAndTracesAreRecognisedByContent) {
  EXPECT_TRUE(is_soc_sim_stats(write("a.json", STATS)));
  EXPECT_FALSE(is_soc_sim_stats(write("b.json", R"({"config": {}, "stats": {}})")));
  EXPECT_FALSE(is_soc_sim_stats(write("c.json", "[1, 2]")));
  EXPECT_FALSE(is_soc_sim_stats(write("d.json", "{\"config\": ")));
  EXPECT_FALSE(is_soc_sim_stats(m_dir / "missing.json"));
  EXPECT_TRUE(is_soc_sim_trace(write("a.vcd", TRACE)));
  std::string other_top = TRACE;
  other_top.replace(other_top.find("module soc"), 10, "module cpu");
  EXPECT_FALSE(is_soc_sim_trace(write("b.vcd", other_top)));
  EXPECT_FALSE(is_soc_sim_trace(write("c.vcd", std::string(TRACE).substr(1))));
  EXPECT_FALSE(is_soc_sim_trace(m_dir / "missing.vcd"));
}

// A folder is claimed by one run at a time: a second claim, from this
// process or another, is refused naming the folder and the holder; the
// claim ends with its object (or its process) and leaves no lock file. A
// lock file left by a run that was killed is taken over.
TEST_F(RunOutputs, AFolderIsClaimedByOneRunAtATime) {
  const fs::path out = m_dir / "out";
  const fs::path lock = out / OutputFolderClaim::OUTPUT_FOLDER_LOCK;
  {
    const OutputFolderClaim claim(out);
    EXPECT_TRUE(fs::exists(lock));
    try {
      const OutputFolderClaim second(out);
      ADD_FAILURE() << "a second claim of the same folder";
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("'" + out.string() + "' is in use by another run"), std::string::npos) << message;
      EXPECT_NE(message.find("process " + std::to_string(::getpid())), std::string::npos) << message;
    }
  }
  EXPECT_FALSE(fs::exists(lock));
  std::ofstream(lock) << "12345\n";  // a killed run's file, no lock held on it
  { const OutputFolderClaim again(out); }
  EXPECT_FALSE(fs::exists(lock));
  EXPECT_THROW(OutputFolderClaim(m_dir / "missing"), std::runtime_error);
}

}  // namespace
}  // namespace tessera
