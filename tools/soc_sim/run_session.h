// One run of soc_sim, from a RunPlan (run_options.h) to its exit status:
// the output folder claimed, GDB listened for, the SoC built with the
// application on its host, the simulation run under the watch (run_watch.h)
// and the progress line, the outputs closed, the run judged, stats.json
// written and the summary printed (run_report.h).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cluster_run.h"
#include "common/activity_counters.h"
#include "device/app_environment.h"
#include "frame_stats_stream.h"
#include "png_writer_thread.h"
#include "run_options.h"
#include "run_outputs.h"
#include "run_report.h"
#include "run_watch.h"
#include "soc/soc.h"
#include "timeline_writer.h"
#include "trace_pipe.h"
#include "transaction_writer.h"

namespace tessera {

namespace iss {
class GdbServer;
}

class RunSession {
 public:
  explicit RunSession(RunPlan plan);
  ~RunSession();
  RunSession(const RunSession&) = delete;
  RunSession& operator=(const RunSession&) = delete;

  // Runs the application to its end (or to a limit, a stop or a failure),
  // writes the outputs and the summary; returns soc_sim's exit status.
  int run();

 private:
  class Progress;

  // The steps of run(), in order. Each that can refuse the run prints why
  // and returns the status to exit with.
  std::optional<int> claim_outputs();
  std::optional<int> listen_for_gdb();
  std::optional<int> build_soc();
  void start_application();
  void simulate();
  void close_outputs();
  void judge();
  int write_statistics(int status);
  int write_html_page(int status);
  int write_stats_schema(int status);
  void print_report();
  int flush_standard_output(int status);

  // Called from the watching thread (run_watch.h): the application holds
  // the simulation, so the SoC is not touched.
  void stop_from_outside(const RunStop& stop);
  void fail(RunEnd end, int status, const std::string& message);
  void frame_shown(const Frame& frame);
  bool platform_done() const;
  double wall_seconds() const;

  RunPlan m_plan;
  const Options& m_options;            // m_plan's
  const Config& m_config;              // m_plan's
  std::optional<Config> m_soc_config;  // soc_view(m_config), the SoC's program's
  unsigned m_frames;                   // sim.frames
  std::string m_stats_path;
  // The VCD's path without a ".vcd" in any case: the functions' names go beside it.
  std::string m_vcd_base;
  nlohmann::json m_config_json;
  // The resources of the run, in the order they are taken; each is released
  // after those taken later (the trace pipe after the SoC, whose destructor
  // closes the trace: the pipe's copier ends when SystemC closes its end).
  // The folder claim is held to the end of the run: no other run checks or
  // writes this folder meanwhile (run_outputs.h).
  std::optional<OutputFolderClaim> m_folder_claim;
  std::unique_ptr<iss::GdbServer> m_gdb_server;
  std::unique_ptr<TracePipe> m_trace_pipe;
  std::unique_ptr<TimelineWriter> m_timeline;  // --timeline
  std::string m_timeline_error;
  std::unique_ptr<TransactionWriter> m_transactions;  // --trace-transactions
  std::string m_transactions_error;
  std::unique_ptr<Soc> m_soc;
  // With sim.platform=cluster, the cluster platform instead of the SoC.
  std::unique_ptr<ClusterRun> m_cluster;
  std::unique_ptr<PngWriterThread> m_png_writer;
  std::unique_ptr<RunWatch> m_watch;
  // stats.json's frame records go to side files as the frames are shown and
  // are merged into stats.json at the end (frame_stats_stream.h): nothing
  // per frame is kept in memory.
  std::unique_ptr<FrameStatsStream> m_frame_stream;
  std::unique_ptr<Progress> m_progress;
  AppEnvironment m_env;
  ActivityCounters m_driver_counters;

  unsigned m_frames_shown = 0;
  // The wall clock from the start of the simulation; each frame's reading is
  // its wall_ns in stats.json with --wall-clock, so a benchmark times frames
  // N..2N-1 within one run instead of subtracting one run from another.
  std::chrono::steady_clock::time_point m_wall_start;
  // The reasons the run failed, the first deciding run_status and the exit status.
  std::vector<RunStop> m_failures;
  std::optional<RunStop> m_stopped;  // by the watch
  std::string m_trace_error;
  std::string m_report_error;  // --report: why the page was not written
  std::string m_png_error;
  unsigned m_frames_written = 0;
  double m_wall = 0;
  RunOutcome m_outcome;
  bool m_stats_written = true;
  FrameStatsStream::Sums m_frame_sums;
  nlohmann::json m_stats;
};

}  // namespace tessera
