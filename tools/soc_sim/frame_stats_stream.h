// stats.json's per-frame records streamed to side files while the run goes
// on, and merged into stats.json at the end, so that a long run keeps no
// record per frame in memory (about 1.7 KiB a frame was kept: a million
// frames grew the process by gigabytes). stats.json itself is written once,
// through OutputFile: whole or absent at every moment, as before.
//
// Three JSON-lines files in the output folder (which the run has claimed),
// hidden and named after the process (".soc_sim-frames-<pid>.jsonl" and so
// on): the SoC's frame
// records, the driver's figures per frame and, with --wall-clock, each
// frame's wall and CPU time. Each is in frame order; write() joins line i
// of each into frame i, exactly as the records were joined in memory, and
// removes the files (so does the destructor, for a run that stops early).
// The file's bytes are those of the document dumped whole (nlohmann's
// dump(2)).
#pragma once

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace tessera {

class FrameStatsStream {
 public:
  // The side files in `folder`. Throws naming a file it cannot create.
  explicit FrameStatsStream(const std::filesystem::path& folder);
  ~FrameStatsStream();
  FrameStatsStream(const FrameStatsStream&) = delete;
  FrameStatsStream& operator=(const FrameStatsStream&) = delete;

  void add_frame(const nlohmann::json& record);    // the SoC's record of the next frame shown
  void add_driver(const nlohmann::json& figures);  // the driver's figures of its next frame
  void add_timing(double wall_seconds, double cpu_seconds);
  size_t frames() const { return m_frames; }

  // Per-frame figures summed while merging, for the summary's means.
  struct Sums {
    size_t frames = 0;
    double energy_total_j = 0;
    std::map<std::string, double> energy_unit_j;  // by energy unit
    size_t driver_frames = 0;                     // frames with driver figures
    std::map<std::string, double> driver;         // by figure, the numeric ones not named host_*
  };

  // The value to put where the frames go in the document before dumping it.
  static const nlohmann::json& placeholder();
  // Writes `document` (dumped with placeholder() as stats.frames) to
  // `stats_path`, the frames merged in its place; wall_ns and cpu_ns only
  // with `wall_clock` (as --wall-clock adds them). Throws naming the file.
  Sums write(const std::filesystem::path& stats_path, const std::string& document, bool wall_clock);
  // Removes the side files' names, without touching the files the
  // simulation's thread may be writing: for a run stopped from another
  // thread, which then exits.
  void unlink_from_other_thread() const noexcept;

 private:
  struct Side {
    std::filesystem::path path;
    std::FILE* file = nullptr;
  };
  void append(Side& side, const std::string& line);
  void remove_all() noexcept;

  Side m_frame_side, m_driver_side, m_timing_side;
  size_t m_frames = 0;
};

}  // namespace tessera
