// The files a run of soc_sim writes, and what an earlier run left where this
// one would write. soc_sim does not mix the outputs of two runs (a new
// stats.json beside the frames of an older, longer run would misdescribe
// them): it refuses to start, and with --force removes exactly what an
// earlier run wrote there, never another file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tessera {

// "frame_0012.png": the name of the frame shown with that index.
std::string frame_file_name(unsigned index);
// The names frame_file_name gives: "frame_", 4 or more digits, ".png".
bool is_frame_file_name(const std::string& name);
// A statistics file soc_sim wrote: a JSON object with "config", "stats" and
// "exit_status".
bool is_soc_sim_stats(const std::filesystem::path& path);
// A VCD trace soc_sim wrote: SystemC's header and the SoC ("soc") as the
// first module under SystemC's top scope.
bool is_soc_sim_trace(const std::filesystem::path& path);
// An FST trace soc_sim wrote: an FST that GTKWave's reader opens, written
// from SystemC's VCD.
bool is_soc_sim_fst(const std::filesystem::path& path);
// A run report soc_sim wrote (--report): an HTML page whose head names
// RUN_REPORT_GENERATOR as its generator.
constexpr const char* RUN_REPORT_GENERATOR = "tessera soc_sim --report";
bool is_soc_sim_report(const std::filesystem::path& path);

// Where this run writes.
struct OutputPaths {
  std::filesystem::path out_dir;  // frames, and statistics unless --stats says otherwise
  std::filesystem::path stats;
  std::filesystem::path trace;   // empty without --vcd
  std::filesystem::path fst;     // empty without --fst
  std::filesystem::path report;  // empty without --report
};

struct EarlierOutputs {
  std::vector<std::filesystem::path> frames;  // frame_NNNN.png in out_dir, sorted
  std::vector<std::filesystem::path> files;   // statistics and traces soc_sim wrote, in out_dir or at this run's paths
  // Files at this run's statistics or trace path that soc_sim did not write:
  // never removed, never overwritten.
  std::vector<std::filesystem::path> foreign;

  bool empty() const { return frames.empty() && files.empty(); }
};

// Looks in out_dir (not below it) for frames, the default stats.json and
// traces (VCD and FST), and at the statistics, trace and report paths of
// this run. An empty file
// at one of this run's paths holds nothing to lose and is not listed.
EarlierOutputs find_earlier_outputs(const OutputPaths& paths);

// For messages: "3 frames (frame_0000.png ... frame_0002.png), stats.json,
// trace.vcd"; names in out_dir relative to it, others as found.
std::string describe_outputs(const EarlierOutputs& outputs, const std::filesystem::path& out_dir);

// Removes outputs.frames and outputs.files (never outputs.foreign). Throws
// std::runtime_error naming the first file it cannot remove.
void remove_earlier_outputs(const EarlierOutputs& outputs);

// This run's claim on its output folder, held from before the check for an
// earlier run's outputs until the run has written everything: two runs
// started together into one folder cannot both pass the check (each used to
// find the folder empty, both ran and one run's outputs were lost). The
// claim is an exclusive flock(2) on OUTPUT_FOLDER_LOCK in the folder; the
// kernel drops it when the process ends however it ends, so a crashed run
// leaves no stale claim (at most the empty file, which the next run takes).
class OutputFolderClaim {
 public:
  static constexpr const char* OUTPUT_FOLDER_LOCK = ".soc_sim.lock";

  // Claims `out_dir` (which must exist), or throws std::runtime_error
  // naming the folder and the process holding it.
  explicit OutputFolderClaim(const std::filesystem::path& out_dir);
  // Removes the lock file and releases the claim.
  ~OutputFolderClaim();
  // Removes the lock file's name only, keeping the lock: for a run that
  // ends from another thread with _exit (no destructor runs; the kernel
  // releases the lock).
  void unlink_from_other_thread() const noexcept;
  OutputFolderClaim(const OutputFolderClaim&) = delete;
  OutputFolderClaim& operator=(const OutputFolderClaim&) = delete;

 private:
  std::filesystem::path m_path;
  int m_fd = -1;
};

}  // namespace tessera
