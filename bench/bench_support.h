// What the benchmark drivers (bench_arm, bench_raster) share: running a child
// process with its stdout in a file and its wall time and peak memory
// measured, reading JSON, formatting figures, and describing the machine.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "process/scratch_folder.h"

namespace tessera::bench {

// Where a benchmark writes its children's outputs: --work-dir when given
// (made if missing, kept), else a fresh folder under the temporary folder,
// removed with everything in it when the object goes
// (testbench/process/scratch_folder.h, the one temporary-folder idiom).
class WorkFolder {
 public:
  // `work_dir`: the user's folder, or empty; `prefix`: the temporary
  // folder's name before its unique suffix ("bench_arm").
  WorkFolder(const std::string& work_dir, const std::string& prefix);
  const std::filesystem::path& path() const { return m_path; }

 private:
  std::optional<test::ScratchFolder> m_scratch;
  std::filesystem::path m_path;
};

struct ChildResult {
  double wall_s = 0;
  double cpu_s = 0;      // user + system CPU time of the child (every thread), from wait4
  long max_rss_kib = 0;  // ru_maxrss of the child
  std::string output;    // its stdout
};

// Runs `argv` with stdout captured in `output_file`, stderr shared with us
// (testbench/process/child_process.h does the running).
// Throws if it cannot start or does not exit with status 0.
ChildResult run_child(const std::vector<std::string>& argv, const std::filesystem::path& output_file);

struct MinMedian {
  double min = 0;
  double median = 0;  // of an even count: the mean of the two middle values
};
// Min and median of repeated measurements (at least one).
MinMedian min_median(std::vector<double> values);

// The median over the rounds of a[i] / b[i]: a ratio of two measurements
// paired by round (taken one after the other, so that a change in the
// machine's load hits both alike). Uses the common length of the two.
double paired_median(const std::vector<double>& a, const std::vector<double>& b);

// A measured duration or count must be positive: zero or less means the
// measurement is broken (a clock read in the wrong place, a difference of
// two runs), never a fast machine. Returns `value`, or throws naming `what`.
double positive(double value, const std::string& what);

nlohmann::json read_json_file(const std::filesystem::path& path);

// The folder of the running executable (the build tree puts the benchmarks
// and soc_sim side by side in bin/).
std::filesystem::path own_directory();

// The 1, 5 and 15 minute load averages: how busy the machine was.
std::string load_average();

// "Machine: <cpu>, <n> hardware threads, <build type> build; load average
// ... before, ... after; the benchmark took <s> s."
std::string machine_summary(const std::string& load_before, double total_s);

// Per frame over frames N..2N-1 of one soc_sim run of 2N frames with
// --wall-clock, from stats.json's frame records: (record 2N-1 minus record
// N-1) / N of `key` ("wall_ns" or "time_ns"), in seconds. Both readings come
// from the same process, so start-up, elaboration and the scene's set-up are
// left out without subtracting one run from another. Throws if the run has
// fewer than 2N records or lacks the key.
double per_frame_seconds(const nlohmann::json& document, unsigned n, const std::string& key);

std::string format_ms(double seconds);  // 3 significant digits
// "min / median" of repeated times, each as format_ms.
std::string format_min_median_ms(const std::vector<double>& seconds);
std::string format_ratio(double ratio);

}  // namespace tessera::bench
