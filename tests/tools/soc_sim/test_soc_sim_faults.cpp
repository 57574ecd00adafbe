// System tests of how soc_sim ends when something goes wrong around the
// simulation (issue 14): a write that fails, a signal, an application that
// never comes back or crashes, an empty option value. Every fault is made
// for real: a file that is a link to /dev/full (every write fails with
// ENOSPC, as on a full disk), a file-size limit (RLIMIT_FSIZE: writes past
// it fail with EFBIG), SIGINT and SIGTERM sent to a running soc_sim, and the
// diagnostic applications stuck_loop and crash.
//
// Usage: test_soc_sim_faults <path to soc_sim> [GoogleTest options]
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "fixtures/soc_sim_test.h"

#include "frame_writer.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tessera::test::contains;
using tessera::test::describe;
using tessera::test::SimResult;

constexpr int EXIT_USAGE = 2;
constexpr int EXIT_FAILED = 1;

json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) {
    ADD_FAILURE() << "missing " << path;
    return json::object();
  }
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    ADD_FAILURE() << path << " is not valid JSON: " << e.what();
    return json::object();
  }
}

// Files in `folder` by name.
std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += name + " ";
  return text;
}

// Waits until `path` exists, the run has ended or a minute has passed. An
// ended run is left for ChildProcess::wait to collect (WNOWAIT).
bool wait_for_file(const fs::path& path, const tessera::test::ChildProcess& child) {
  for (int i = 0; i < 6000; ++i) {
    if (fs::exists(path)) return true;
    siginfo_t info{};
    if (waitid(P_PID, static_cast<id_t>(child.pid()), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid != 0)
      return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

// In the child: every file may grow to 4000 bytes, and a write past that
// fails with EFBIG instead of killing the process (SIGXFSZ ignored).
void limit_file_size() {
  rlimit limit{4000, 4000};
  setrlimit(RLIMIT_FSIZE, &limit);
  signal(SIGXFSZ, SIG_IGN);
}

// In the child: standard output on a device where every write fails.
void stdout_to_full_device() {
  const int full = open("/dev/full", O_WRONLY);
  if (full >= 0) dup2(full, STDOUT_FILENO);
}

// In the child: no core file from the crash made on purpose.
void no_core_dump() {
  rlimit limit{0, 0};
  setrlimit(RLIMIT_CORE, &limit);
}

class SocSimFaults : public tessera::test::SocSimTest {
 protected:
  // Every frame in `folder` is a whole PNG of the display's size, there are
  // `count` of them, and no temporary file was left behind.
  void expect_whole_frames(const fs::path& folder, unsigned count) {
    unsigned frames = 0;
    for (const std::string& name : names_in(folder)) {
      EXPECT_NE(name[0], '.') << "temporary file left behind: " << name;
      if (name.rfind("frame_", 0) != 0) continue;
      ++frames;
      const tessera::Image image = tessera::read_image((folder / name).string());
      EXPECT_EQ(image.width, 320u) << name;
      EXPECT_EQ(image.height, 240u) << name;
    }
    EXPECT_EQ(frames, count) << joined(names_in(folder));
  }
};

// --stats on a device where every write fails: an error naming the file and
// the reason, never exit status 0.
TEST_F(SocSimFaults, StatisticsOnAFullDeviceFail) {
  const SimResult result = run({"--app", "pattern", "--frames", "1", "--out", "out", "--stats", "/dev/full"});
  EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
  EXPECT_TRUE(contains(result.err, "cannot write '/dev/full': No space left on device")) << describe(result);
  EXPECT_TRUE(contains(result.out, "statistics: none")) << result.out;
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

// A frame that cannot be written stops the run: the message names the file,
// the reason and the frames reached; the statistics say so; the frame
// before it is whole.
TEST_F(SocSimFaults, FrameOnAFullDiskFailsAndStopsTheRun) {
  fs::create_directory(m_dir / "out");
  fs::create_symlink("/dev/full", m_dir / "out/frame_0001.png");
  const SimResult result = run({"--app", "pattern", "--frames", "200", "--out", "out"});
  EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
  EXPECT_TRUE(contains(result.err, "cannot write 'out/frame_0001.png': No space left on device")) << describe(result);
  EXPECT_TRUE(contains(result.err, "of 200 frames were shown")) << describe(result);
  const json stats = read_json(m_dir / "out/stats.json");
  EXPECT_EQ(stats["exit_status"], EXIT_FAILED);
  EXPECT_EQ(stats["run_status"], "failed");
  EXPECT_TRUE(contains(stats.value("error", ""), "frame_0001.png")) << stats.value("error", "");
  // The run stopped at the failure instead of simulating the other frames.
  EXPECT_LT(stats["frames_shown"].get<unsigned>(), 200u);
  // Every frame shown but frame 1 was written (the writer goes on).
  EXPECT_EQ(stats["frames_written"].get<unsigned>() + 1, stats["frames_shown"].get<unsigned>());
  EXPECT_TRUE(fs::is_symlink(m_dir / "out/frame_0001.png"));
  const tessera::Image first = tessera::read_image((m_dir / "out/frame_0000.png").string());
  EXPECT_EQ(first.width, 320u);
}

// Files past a size limit fail to grow (EFBIG), as on a nearly full disk:
// every output that does not fit is reported and absent, not a truncated
// file, and the run fails.
TEST_F(SocSimFaults, OutputsThatDoNotFitAreReportedAndAbsent) {
  const SimResult result = start({"--app", "pattern", "--frames", "2", "--out", "out", "--vcd", "out/trace.vcd",
                                  "--set", "power.trace_window_us=0", "--quiet"},
                                 limit_file_size)
                               .wait();
  EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
  EXPECT_TRUE(contains(result.err, "File too large")) << describe(result);
  EXPECT_TRUE(contains(result.err, "cannot write 'out/stats.json'")) << describe(result);
  EXPECT_TRUE(contains(result.err, "cannot write 'out/trace.vcd'")) << describe(result);
  // Nothing is left half written: the folder holds no output at all.
  EXPECT_EQ(joined(names_in(m_dir / "out")), "") << describe(result);
}

TEST_F(SocSimFaults, VcdTraceOnAFullDiskFails) {
  fs::create_directory(m_dir / "out");
  fs::create_symlink("/dev/full", m_dir / "out/trace.vcd");
  const SimResult result = run({"--app", "pattern", "--frames", "1", "--out", "out", "--vcd", "out/trace.vcd"});
  EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
  EXPECT_TRUE(contains(result.err, "cannot write 'out/trace.vcd': No space left on device")) << describe(result);
  EXPECT_EQ(read_json(m_dir / "out/stats.json")["exit_status"], EXIT_FAILED);
}

// The VCD trace goes through a pipe (tools/soc_sim/trace_pipe.h): what
// arrives is what SystemC wrote, with the date blanked.
TEST_F(SocSimFaults, VcdTraceIsWholeAndDateless) {
  const SimResult result = run({"--app", "pattern", "--frames", "2", "--out", "out", "--vcd", "out/trace.vcd"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const std::string trace = tessera::test::read_file(m_dir / "out/trace.vcd");
  ASSERT_EQ(trace.rfind("$date\n", 0), 0u) << trace.substr(0, 200);
  const std::string date = trace.substr(5, trace.find("$end") - 5);
  EXPECT_EQ(date.find_first_not_of("- \n"), std::string::npos) << date;
  EXPECT_TRUE(contains(trace, "$enddefinitions")) << trace.substr(0, 200);
  // The last timestamp is the end of the run, as stats.json has it.
  const json stats = read_json(m_dir / "out/stats.json");
  const auto last = trace.rfind("\n#");
  ASSERT_NE(last, std::string::npos);
  EXPECT_LE(std::stod(trace.substr(last + 2)) * 1e-3, stats["stats"]["simulated_ns"].get<double>());
  EXPECT_EQ(stats["run_status"], "completed");
  EXPECT_FALSE(stats.contains("error"));
}

TEST_F(SocSimFaults, StandardOutputOnAFullDeviceFails) {
  const SimResult result = start({"--app", "pattern", "--frames", "1", "--out", "out"}, stdout_to_full_device).wait();
  EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
  EXPECT_TRUE(contains(result.err, "cannot write to standard output: No space left on device")) << describe(result);
}

// SIGINT or SIGTERM: the run stops between two slices, writes the frames
// shown and the statistics up to there with run_status "interrupted", and
// exits with 128 + the signal.
void expect_interrupted(SocSimFaults& test, const fs::path& dir, tessera::test::ChildProcess& child, int signal,
                        const std::string& name) {
  ASSERT_TRUE(wait_for_file(dir / "out/frame_0002.png", child)) << "no third frame appeared";
  ASSERT_EQ(kill(child.pid(), signal), 0);
  const SimResult result = child.wait();
  EXPECT_EQ(result.status, 128 + signal) << describe(result);
  EXPECT_TRUE(contains(result.err, "interrupted by " + name + ": the run stopped after")) << describe(result);
  const json stats = read_json(dir / "out/stats.json");
  EXPECT_EQ(stats["exit_status"], 128 + signal);
  EXPECT_EQ(stats["run_status"], "interrupted");
  const unsigned shown = stats["frames_shown"].get<unsigned>();
  EXPECT_GE(shown, 3u);
  EXPECT_LT(shown, 100000u);
  EXPECT_EQ(stats["frames_written"], shown);
  EXPECT_EQ(stats["stats"]["frames"].size(), shown);
  (void)test;
}

TEST_F(SocSimFaults, SigintStopsAtASafePointKeepingWhatIsComplete) {
  tessera::test::ChildProcess child = start({"--app", "pattern", "--frames", "100000", "--out", "out"});
  expect_interrupted(*this, m_dir, child, SIGINT, "SIGINT");
  expect_whole_frames(m_dir / "out", read_json(m_dir / "out/stats.json")["frames_written"].get<unsigned>());
}

TEST_F(SocSimFaults, SigtermStopsAtASafePointKeepingWhatIsComplete) {
  tessera::test::ChildProcess child =
      start({"--app", "pattern", "--frames", "100000", "--out", "out", "--vcd", "out/trace.vcd"});
  expect_interrupted(*this, m_dir, child, SIGTERM, "SIGTERM");
  // The trace up to the stop is kept, whole.
  const std::string trace = tessera::test::read_file(m_dir / "out/trace.vcd");
  EXPECT_TRUE(contains(trace, "$enddefinitions")) << trace.substr(0, 200);
}

// An application that computes forever in its own code never lets the
// simulation loop run again; the stall limit ends the run from outside,
// naming the limit, the frame reached and what the host was running.
TEST_F(SocSimFaults, StuckApplicationEndsAtTheStallLimit) {
  const SimResult result = run({"--app", "stuck_loop", "--set", "sim.stall_limit_s=1", "--out", "out"});
  EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
  EXPECT_TRUE(contains(result.err, "no simulated progress")) << describe(result);
  EXPECT_TRUE(contains(result.err, "sim.stall_limit_s = 1 s")) << describe(result);
  EXPECT_TRUE(contains(result.err, "after 1 of 3 frames were shown")) << describe(result);
  EXPECT_TRUE(contains(result.err, "the host was running tessera::stuck_loop_app")) << describe(result);
  const json stats = read_json(m_dir / "out/stats.json");
  EXPECT_EQ(stats["exit_status"], EXIT_FAILED);
  EXPECT_EQ(stats["run_status"], "stalled");
  EXPECT_EQ(stats["frames_shown"], 1);
  EXPECT_EQ(stats["frames_written"], 1);
  EXPECT_TRUE(stats["stats"].is_null());
  expect_whole_frames(m_dir / "out", 1);
}

// Ctrl-C while the application is stuck: the loop never reaches its safe
// point, so after the grace period the run is stopped from outside.
TEST_F(SocSimFaults, SigintEndsAStuckApplication) {
  tessera::test::ChildProcess child = start({"--app", "stuck_loop", "--set", "sim.stall_limit_s=0", "--out", "out"});
  ASSERT_TRUE(wait_for_file(m_dir / "out/frame_0000.png", child));
  ASSERT_EQ(kill(child.pid(), SIGINT), 0);
  const SimResult result = child.wait();
  EXPECT_EQ(result.status, 128 + SIGINT) << describe(result);
  EXPECT_TRUE(contains(result.err, "interrupted by SIGINT after 1 of 3 frames were shown")) << describe(result);
  EXPECT_TRUE(contains(result.err, "tessera::stuck_loop_app")) << describe(result);
  const json stats = read_json(m_dir / "out/stats.json");
  EXPECT_EQ(stats["run_status"], "interrupted");
  EXPECT_EQ(stats["exit_status"], 128 + SIGINT);
}

// The wall-clock limit stops a run that would go on for hours; the run
// writes its statistics up to there.
TEST_F(SocSimFaults, WallClockLimitStopsTheRunWithItsStatistics) {
  const SimResult result =
      run({"--app", "pattern", "--frames", "100000", "--no-frames", "--set", "sim.wall_limit_s=1", "--out", "out"});
  EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
  EXPECT_TRUE(contains(result.err, "wall-clock limit reached: sim.wall_limit_s = 1 s stopped the run after"))
      << describe(result);
  const json stats = read_json(m_dir / "out/stats.json");
  EXPECT_EQ(stats["run_status"], "wall_limit");
  const unsigned shown = stats["frames_shown"].get<unsigned>();
  EXPECT_GT(shown, 0u);
  EXPECT_LT(shown, 100000u);
  EXPECT_EQ(stats["stats"]["frames"].size(), shown);
}

// A crash in the application is reported as one, with the frame reached,
// and the process still ends by its signal (a core dump stays possible).
TEST_F(SocSimFaults, CrashInTheApplicationIsReportedWithTheFrame) {
  const SimResult result = start({"--app", "crash", "--out", "out"}, no_core_dump).wait();
  EXPECT_EQ(result.status, 128 + SIGSEGV) << describe(result);
  EXPECT_TRUE(contains(result.err,
                       "soc_sim: crashed: SIGSEGV (invalid memory access) at address 0x0 while "
                       "simulating, after 1 of 3 frames were shown"))
      << describe(result);
  const json stats = read_json(m_dir / "out/stats.json");
  EXPECT_EQ(stats["run_status"], "crashed");
  EXPECT_EQ(stats["exit_status"], 128 + SIGSEGV);
  EXPECT_TRUE(contains(stats.value("error", ""), "SIGSEGV")) << stats.value("error", "");
  expect_whole_frames(m_dir / "out", 1);
}

// An empty value is a mistake, not a request for the default.
TEST_F(SocSimFaults, EmptyApplicationOrBackEndIsAnError) {
  for (const char* option : {"--app", "--backend", "--log-level"}) {
    const SimResult result = run({option, "", "--out", "out"});
    EXPECT_EQ(result.status, EXIT_USAGE) << option << "\n" << describe(result);
    EXPECT_TRUE(contains(result.err, std::string("soc_sim: ") + option + " was given an empty value"))
        << describe(result);
    EXPECT_FALSE(fs::exists(m_dir / "out/stats.json")) << option;
  }
}

// An application that finishes without showing a frame succeeds with a
// warning.
TEST_F(SocSimFaults, ApplicationWithoutAFrameIsWarnedAbout) {
  const SimResult result = run({"--app", "calib_add", "--out", "out"});
  EXPECT_EQ(result.status, 0) << describe(result);
  EXPECT_TRUE(contains(result.err, "the application 'calib_add' finished without showing a frame (3 requested)"))
      << describe(result);
  EXPECT_EQ(read_json(m_dir / "out/stats.json")["run_status"], "completed");
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
