#include "run_session.h"

#include <strings.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <systemc>

#include "common/activity_json.h"
#include "common/log.h"
#include "host/iss/gdb_server.h"
#include "html_report.h"
#include "output_file.h"
#include "progress_line.h"
#include "renderers/backends.h"
#include "soc/software_layout.h"

namespace fs = std::filesystem;

namespace tessera {

namespace {

// Creates `dir` if needed and proves it writable, or throws naming it.
void prepare_output_dir(const std::string& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw std::runtime_error("output folder '" + dir + "' cannot be created: " + error.message());
  const fs::path probe = fs::path(dir) / ".soc_sim_write_test";
  std::ofstream file(probe);
  if (!file) throw std::runtime_error("output folder '" + dir + "' is not writable");
  file.close();
  fs::remove(probe, error);
}

// Proves that `path` can be written without changing it: a file that was
// not there is removed again, so a run refused later leaves nothing behind.
void check_writable_file(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw std::runtime_error("cannot write '" + path + "': folder '" + parent.string() + "' does not exist");
  std::error_code error;
  const bool existed = fs::exists(path, error);
  if (!std::ofstream(path, std::ios::app)) throw std::runtime_error("cannot write '" + path + "'");
  if (!existed) fs::remove(path, error);
}

// Refuses to mix this run's outputs with an earlier run's (run_outputs.h);
// with --force removes the earlier ones. Throws with the message to print.
void clear_earlier_outputs(const OutputPaths& paths, bool force) {
  const EarlierOutputs earlier = find_earlier_outputs(paths);
  if (!earlier.foreign.empty()) {
    const fs::path& file = earlier.foreign.front();
    // What this run would write there, and the option that names the path.
    struct Kind {
      const fs::path& path;
      const char *what, *output, *option;
    };
    const Kind kinds[] = {{paths.stats, "a statistics file", "statistics", "--stats or --out"},
                          {paths.trace, "a VCD trace", "trace", "--vcd"},
                          {paths.fst, "an FST trace", "trace", "--fst"},
                          {paths.report, "a run report", "report", "--report"}};
    // (The report's when none of the others'.)
    const Kind& kind = *std::find_if(std::begin(kinds), std::end(kinds) - 1,
                                     [&](const Kind& k) { return !k.path.empty() && file == k.path; });
    throw std::runtime_error("'" + file.string() + "' was not written by soc_sim (it is not " + kind.what +
                             " of soc_sim), and this run would overwrite it with its " + kind.output +
                             "; soc_sim never overwrites such a file, even with --force: move it, or choose another " +
                             "path with " + kind.option);
  }
  if (earlier.empty()) return;
  if (!force)
    throw std::runtime_error("output folder '" + paths.out_dir.string() + "' already holds the outputs of an " +
                             "earlier run: " + describe_outputs(earlier, paths.out_dir) +
                             "; a new run would mix its outputs with them: add --force to remove them first, or " +
                             "choose another folder with --out");
  remove_earlier_outputs(earlier);
}

// The process's CPU time (every thread: the simulation and the PNG
// writer), cpu_ns with --wall-clock: on a machine with a core to spare the
// PNG thread costs little wall time, but its work shows here.
double cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

std::string format_megabytes(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / 1e6);
  return text;
}

}  // namespace

// The progress line on stderr (progress_line.h): redrawn at most every
// PROGRESS_REDRAW_SECONDS of wall time, at the terminal's current width, and
// once more at the end with the final state.
class RunSession::Progress {
 public:
  Progress(bool enabled, unsigned total) : m_enabled(enabled), m_total(total) {}
  bool enabled() const { return m_enabled; }
  void update(unsigned frames, double simulated, double wall) {
    if (!m_enabled || (m_drawn && wall - m_last_draw < PROGRESS_REDRAW_SECONDS)) return;
    draw(frames, simulated, wall);
  }
  void finish(unsigned frames, double simulated, double wall) {
    if (!m_enabled) return;
    draw(frames, simulated, wall);
    std::fputc('\n', stderr);
  }

 private:
  void draw(unsigned frames, double simulated, double wall) {
    winsize size{};
    const unsigned reported = ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 ? size.ws_col : 0;
    const unsigned columns = choose_columns(reported, std::getenv("COLUMNS"));
    std::fprintf(stderr, "\r%s", progress_line({frames, m_total, simulated, wall}, columns).c_str());
    std::fflush(stderr);
    m_drawn = true;
    m_last_draw = wall;
  }

  bool m_enabled;
  unsigned m_total;
  bool m_drawn = false;
  double m_last_draw = 0;
};

RunSession::RunSession(RunPlan plan)
    : m_plan(std::move(plan)),
      m_options(m_plan.options),
      m_config(m_plan.config),
      m_frames(static_cast<unsigned>(m_config.get_uint("sim.frames"))) {
  // The trace is written under exactly the name given (TracePipe copies
  // SystemC's output there, whatever SystemC appends to its own name); the
  // functions' names go beside the VCD, or beside the FST without one.
  m_vcd_base = m_options.vcd.empty() ? m_options.fst : m_options.vcd;
  if (const fs::path extension = fs::path(m_vcd_base).extension();
      extension.string().size() == 4 &&
      (strcasecmp(extension.c_str(), ".vcd") == 0 || strcasecmp(extension.c_str(), ".fst") == 0))
    m_vcd_base.resize(m_vcd_base.size() - 4);
  m_stats_path = m_options.stats.empty() ? (fs::path(m_options.out_dir) / "stats.json").string() : m_options.stats;
}

RunSession::~RunSession() = default;

int RunSession::run() {
  if (const std::optional<int> status = claim_outputs()) return *status;
  if (const std::optional<int> status = listen_for_gdb()) return *status;
  log::install(log::parse_level(m_config.get_string("sim.log_level")));
  install_run_signal_handlers();
  if (const std::optional<int> status = build_soc()) return *status;
  start_application();
  simulate();
  close_outputs();
  judge();
  int status = write_stats_schema(write_statistics(m_outcome.exit_status));
  if (!m_options.report.empty()) status = write_html_page(status);
  if (!m_options.quiet) print_report();
  return flush_standard_output(status);
}

std::optional<int> RunSession::claim_outputs() {
  try {
    prepare_output_dir(m_options.out_dir);
    m_folder_claim.emplace(m_options.out_dir);
    check_writable_file(m_stats_path);
    for (const std::string* path : {&m_options.vcd, &m_options.fst, &m_options.report, &m_options.stats_schema})
      if (!path->empty()) check_writable_file(*path);
    clear_earlier_outputs({m_options.out_dir, m_stats_path, m_options.vcd, m_options.fst, m_options.report},
                          m_options.force);
    if (!m_options.timeline.empty()) check_writable_file(m_options.timeline);
    if (!m_options.trace_transactions.empty())
      check_writable_file(parse_transaction_trace(m_options.trace_transactions).path);
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }
  return std::nullopt;
}

// Listening before the SoC is built: a port in use is bad input, found
// before anything runs.
std::optional<int> RunSession::listen_for_gdb() {
  if (m_options.gdb_port < 0) return std::nullopt;
  try {
    m_gdb_server = std::make_unique<iss::GdbServer>();
    const unsigned port = m_gdb_server->listen(static_cast<unsigned>(m_options.gdb_port));
    if (!m_options.gdb_port_file.empty() && !(std::ofstream(m_options.gdb_port_file) << port << "\n"))
      throw std::runtime_error("cannot write the GDB port to '" + m_options.gdb_port_file + "'");
    if (!m_options.quiet) std::cerr << "soc_sim: waiting for GDB on 127.0.0.1:" << port << "\n";
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: --gdb: " << e.what() << "\n";
    return EXIT_USAGE;
  }
  return std::nullopt;
}

// The trace pipe, the SoC, the PNG writer and the frame records' stream,
// and the display's frames to them.
std::optional<int> RunSession::build_soc() {
  try {
    if (!m_options.vcd.empty() || !m_options.fst.empty())
      m_trace_pipe = std::make_unique<TracePipe>(m_options.vcd, m_options.fst);
    if (!m_options.timeline.empty())
      m_timeline =
          std::make_unique<TimelineWriter>(m_options.timeline, parse_timeline_detail(m_options.timeline_detail));
    if (!m_options.trace_transactions.empty())
      m_transactions = std::make_unique<TransactionWriter>(parse_transaction_trace(m_options.trace_transactions));
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_SIM_FAILED;
  }
  if (m_config.get_string("sim.platform") == "cluster")
    m_cluster = std::make_unique<ClusterRun>(m_config, [this](const Frame& frame) {
      m_frame_stream->add_frame(m_cluster->frame_record(frame));
      frame_shown(frame);
    });
  else
    m_soc = std::make_unique<Soc>("soc", m_config);
  m_png_writer = std::make_unique<PngWriterThread>();
  m_wall_start = std::chrono::steady_clock::now();
  try {
    m_frame_stream = std::make_unique<FrameStatsStream>(m_options.out_dir);
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_SIM_FAILED;
  }
  if (m_cluster) return std::nullopt;
  Soc& soc = *m_soc;
  soc.recorder().stream_frames([this](const nlohmann::json& record) { m_frame_stream->add_frame(record); });
  soc.display.keep_pixels(!m_options.no_frames);
  soc.display.on_frame([this](const Frame& frame) { frame_shown(frame); });
  return std::nullopt;
}

void RunSession::frame_shown(const Frame& frame) {
  if (m_options.wall_clock) m_frame_stream->add_timing(wall_seconds(), cpu_seconds());
  if (!m_options.no_frames)
    m_png_writer->write((fs::path(m_options.out_dir) / frame_file_name(frame.index)).string(), frame.width,
                        frame.height, frame.rgba);
  ++m_frames_shown;
  if (m_watch) m_watch->frame_shown(m_frames_shown);
}

bool RunSession::platform_done() const {
  return m_cluster ? m_cluster->done() : m_soc->done();
}

// The application's environment (the boot loader's layout, the back end,
// the driver's statistics and warnings), the program on the host, and the
// trace.
void RunSession::start_application() {
  if (m_cluster) {
    m_cluster->start(m_plan.app, m_frames, m_options.iss_profile);
    if (m_trace_pipe) m_cluster->trace_to(m_trace_pipe->systemc_base());
    if (m_timeline) m_cluster->timeline_to(*m_timeline);
    if (m_transactions)
      for (unsigned i = 0; i < m_cluster->cluster().nodes(); ++i)
        m_cluster->cluster().node(i).bus.trace_transactions_to(*m_transactions);
    m_config_json = m_config.to_json();
    return;
  }
  Soc& soc = *m_soc;
  m_env.frames = m_frames;
  const software_layout::Layout layout = software_layout::layout(soc.memory.size(), soc.display.frame_bytes());
  m_env.frame_buffers[0] = layout.frame_buffers[0];
  m_env.frame_buffers[1] = layout.frame_buffers[1];
  m_env.heap_base = layout.heap_base;
  m_env.heap_end = layout.heap_end;
  m_env.memory_bytes = static_cast<uint32_t>(soc.memory.size());
  m_env.args = m_options.app_args;
  // The SoC's program is handed the SoC's parameters only (on the ISS, its
  // boot information), not the cluster platform's.
  m_soc_config.emplace(soc_view(m_config));
  m_env.config = &*m_soc_config;
  m_env.counters = &m_driver_counters;
  m_env.warn = [](const std::string& source, const std::string& message) { log::warning(source, message); };
  m_env.frame_statistics = [this](const std::vector<std::pair<std::string, double>>& figures) {
    nlohmann::json record = nlohmann::json::object();
    for (const auto& [name, value] : figures) record[name] = value;
    m_frame_stream->add_driver(record);
  };
  backends::hand_over(backends::backend(m_config.get_string("driver.backend")), m_env);
  soc.host.set_profiling_program(m_options.iss_profile);
  soc.set_program([this](HostApi& host) {
    m_env.host = &host;
    return m_plan.app.main(m_env, IssHost{m_soc->host, m_gdb_server.get()});
  });

  if (m_trace_pipe) soc.recorder().trace_to(m_trace_pipe->systemc_base());
  if (m_timeline) soc.recorder().timeline_to(*m_timeline);
  if (m_transactions) soc.bus.trace_transactions_to(*m_transactions);
  m_config_json = m_soc_config->to_json();
}

// A stop from the watching thread: the frames already shown are written,
// the trace is dropped (it is not whole) and stats.json says how the run
// ended.
void RunSession::stop_from_outside(const RunStop& stop) {
  if (stop.end != RunEnd::crashed)
    std::fprintf(stderr, "%ssoc_sim: %s\n", m_progress->enabled() ? "\n" : "", stop.message.c_str());
  m_png_writer->finish();
  if (m_trace_pipe) m_trace_pipe->abandon_from_other_thread();
  try {
    write_file_atomically(m_stats_path, statistics_document(m_plan, m_config_json,
                                                            {stop.exit_status, stop.end, stop.message,
                                                             m_watch->frames_shown(), m_png_writer->written()},
                                                            nullptr));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "soc_sim: %s\n", e.what());
  }
  // The run exits with _exit: no destructor removes the side files or the
  // lock file (the kernel drops the lock itself).
  m_frame_stream->unlink_from_other_thread();
  m_folder_claim->unlink_from_other_thread();
}

void RunSession::simulate() {
  m_progress = std::make_unique<Progress>(!m_options.quiet && isatty(STDERR_FILENO), m_frames);
  // Under GDB simulated time stands still while GDB holds the program, for
  // as long as the user likes: that is no stall.
  const uint64_t stall_limit_s = m_gdb_server ? 0 : m_config.get_uint("sim.stall_limit_s");
  m_watch = std::make_unique<RunWatch>(WatchLimits{stall_limit_s, m_config.get_uint("sim.wall_limit_s")}, m_frames,
                                       [this](const RunStop& stop) { stop_from_outside(stop); });
  m_wall_start = std::chrono::steady_clock::now();
  const sc_core::sc_time limit(static_cast<double>(m_plan.time_limit.ms), sc_core::SC_MS);
  const sc_core::sc_time slice(1, sc_core::SC_MS);
  try {
    while (!platform_done() && sc_core::sc_get_status() != sc_core::SC_STOPPED && sc_core::sc_time_stamp() < limit) {
      sc_core::sc_start(slice);
      if (m_timeline && m_soc) m_soc->recorder().sample_timeline();
      m_watch->progress(static_cast<uint64_t>(sc_core::sc_time_stamp().to_seconds() * 1e12));
      m_progress->update(m_frames_shown, sc_core::sc_time_stamp().to_seconds(), wall_seconds());
      m_stopped = m_watch->stop_request();
      if (m_stopped || m_png_writer->failed()) break;
    }
  } catch (const std::exception& e) {
    fail(RunEnd::failed, EXIT_SIM_FAILED, std::string("simulation failed: ") + e.what());
  }
  m_watch->finish();
  // The run ended with the program still running under GDB (the time
  // limit, say): GDB is told, not left waiting.
  if (m_gdb_server) m_gdb_server->abandon();
  m_progress->finish(m_frames_shown, sc_core::sc_time_stamp().to_seconds(), wall_seconds());
}

// The trace (and, for a program on the ISS, its functions' names by
// soc.host.function's value, as a GTKWave translate-filter file beside the
// VCD) and the frames.
void RunSession::close_outputs() {
  if (m_cluster)
    m_cluster->close_trace();
  else
    m_soc->recorder().close_trace();
  m_trace_error = m_trace_pipe ? m_trace_pipe->finish() : "";
  if (m_timeline) {
    if (m_cluster)
      m_cluster->finish_timeline();
    else
      m_soc->recorder().finish_timeline();
    m_timeline_error = m_timeline->finish();
  }
  if (m_transactions) m_transactions_error = m_transactions->finish();
  if (m_soc && m_trace_pipe && m_trace_error.empty() && !m_soc->host.function_names().empty()) {
    std::string names;
    for (size_t i = 0; i < m_soc->host.function_names().size(); ++i)
      names += std::to_string(i) + " " + m_soc->host.function_names()[i] + "\n";
    try {
      write_file_atomically(m_vcd_base + ".functions.txt", names);
    } catch (const std::exception& e) {
      m_trace_error = e.what();
    }
  }
  m_png_error = m_png_writer->finish();
  m_frames_written = m_png_writer->written();
  m_wall = wall_seconds();
}

// How the run ended: the first failure decides the status and run_status.
void RunSession::judge() {
  const TimeLimit& time_limit = m_plan.time_limit;
  const bool limit_reached =
      sc_core::sc_time_stamp() >= sc_core::sc_time(static_cast<double>(time_limit.ms), sc_core::SC_MS);
  if (!m_failures.empty()) {
    // An exception from the simulation: reported above all else.
  } else if (m_stopped) {
    m_failures.push_back(*m_stopped);
  } else if (!m_png_error.empty()) {
    // Reported below; the run stopped at it.
  } else if (!platform_done() && limit_reached) {
    fail(RunEnd::failed, EXIT_SIM_FAILED,
         "simulated-time limit reached: sim.time_limit_ms = " + std::to_string(time_limit.ms) + " ms (" +
             (time_limit.automatic ? "automatic, " + TimeLimit::automatic_rule() : std::string("given")) + ") " +
             "stopped the run after " + std::to_string(m_frames_shown) + " of " + std::to_string(m_frames) +
             " frames; " +
             (time_limit.automatic ? "set sim.time_limit_ms to a larger value (--set sim.time_limit_ms=N)"
                                   : "raise it, or leave sim.time_limit_ms unset for the automatic limit"));
  } else if (!platform_done()) {
    fail(RunEnd::failed, EXIT_SIM_FAILED,
         "the simulation stopped after " + std::to_string(m_frames_shown) + " of " + std::to_string(m_frames) +
             " frames, before the application finished");
  } else if (const int code = m_cluster ? m_cluster->exit_code() : m_soc->host.exit_code(); code != 0) {
    // An application reports bad input (an unreadable file, a bad argument)
    // with status 2, like soc_sim itself.
    fail(RunEnd::failed, code == EXIT_USAGE ? EXIT_USAGE : EXIT_SIM_FAILED,
         "application failed: " + (m_cluster ? m_cluster->failure() : m_soc->host.failure()));
  }
  if (!m_png_error.empty())
    fail(RunEnd::failed, EXIT_SIM_FAILED,
         m_png_error + "; the run stopped after " + std::to_string(m_frames_shown) + " of " + std::to_string(m_frames) +
             " frames were shown, " + std::to_string(m_frames_written) + " written");
  if (!m_trace_error.empty()) fail(RunEnd::failed, EXIT_SIM_FAILED, m_trace_error + " (the trace is not kept)");
  if (!m_transactions_error.empty())
    fail(RunEnd::failed, EXIT_SIM_FAILED, m_transactions_error + " (the transaction trace is not kept)");
  if (!m_timeline_error.empty())
    fail(RunEnd::failed, EXIT_SIM_FAILED, m_timeline_error + " (the timeline is not kept)");
  if (m_failures.empty() && m_frames_shown == 0)
    log::warning("soc_sim", "the application '" + m_config.get_string("sim.app") +
                                "' finished without showing a frame (" + std::to_string(m_frames) +
                                " requested): nothing was drawn");
  for (const RunStop& failure : m_failures) std::cerr << "soc_sim: " << failure.message << "\n";
  m_outcome = {m_failures.empty() ? 0 : m_failures.front().exit_status,
               m_failures.empty() ? RunEnd::completed : m_failures.front().end,
               m_failures.empty() ? "" : m_failures.front().message, m_frames_shown, m_frames_written};
}

// stats.json; a failure to write it fails a run that had not failed.
int RunSession::write_statistics(int status) {
  if (m_cluster) {
    m_stats = m_cluster->stats_json();
  } else {
    m_stats = m_soc->recorder().stats_json();
    m_stats["driver"] = to_json(m_driver_counters);
  }
  // The frames streamed (every one: streaming began before the first) are
  // merged in where the placeholder is.
  m_stats["frames"] = FrameStatsStream::placeholder();
  try {
    m_frame_sums = m_frame_stream->write(m_stats_path, statistics_document(m_plan, m_config_json, m_outcome, m_stats),
                                         m_options.wall_clock);
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << " (statistics)\n";
    m_stats_written = false;
    if (status == 0) status = EXIT_SIM_FAILED;
  }
  return status;
}

// --report: the page is rendered from stats.json and the frames once they
// are written; a page that cannot be fails a run that had not failed, and
// every other output stays.
int RunSession::write_html_page(int status) {
  m_report_error = m_stats_written ? write_html_report({m_stats_path, m_options.out_dir, m_options.report})
                                   : "the run report is not written: the statistics it is drawn from were not";
  if (m_report_error.empty()) return status;
  std::cerr << "soc_sim: " << m_report_error << " (the run's other outputs are kept)\n";
  return status == 0 ? EXIT_SIM_FAILED : status;
}

// --stats-schema; a failure to write it fails a run that had not failed.
int RunSession::write_stats_schema(int status) {
  if (m_options.stats_schema.empty()) return status;
  try {
    StatsSchema stats;
    m_soc->recorder().describe_stats(stats);
    write_file_atomically(m_options.stats_schema, statistics_document_schema(stats, m_driver_counters).dump(2) + "\n");
  } catch (const std::exception& e) {
    std::cerr << "soc_sim: " << e.what() << " (--stats-schema)\n";
    if (status == 0) status = EXIT_SIM_FAILED;
  }
  return status;
}

void RunSession::print_report() {
  std::vector<std::string> outputs;
  if (m_frames_written)
    outputs.push_back(std::to_string(m_frames_written) +
                      " frame(s): " + (fs::path(m_options.out_dir) / frame_file_name(0)).string() +
                      (m_frames_written > 1 ? " ..." : ""));
  if (m_options.no_frames)
    outputs.push_back(std::to_string(m_frames_shown) + " frame(s) shown, none written (--no-frames)");
  outputs.push_back(m_stats_written ? "statistics: " + m_stats_path : "statistics: none (" + m_stats_path + " failed)");
  if (!m_options.vcd.empty())
    outputs.push_back(m_trace_error.empty() ? "VCD trace: " + m_options.vcd : "VCD trace: none");
  if (!m_options.fst.empty())
    outputs.push_back(m_trace_error.empty() ? "FST trace: " + m_options.fst : "FST trace: none");
  if (!m_options.report.empty())
    outputs.push_back(m_report_error.empty() ? "run report: " + m_options.report : "run report: none");
  if (m_timeline)
    outputs.push_back(m_timeline_error.empty()
                          ? "timeline: " + m_options.timeline + " (" + std::to_string(m_timeline->events()) +
                                " events, " + format_megabytes(m_timeline->bytes()) + ")"
                          : "timeline: none");
  if (m_transactions)
    outputs.push_back(m_transactions_error.empty()
                          ? "transactions: " + parse_transaction_trace(m_options.trace_transactions).path + " (" +
                                std::to_string(m_transactions->rows()) + " rows)"
                          : "transactions: none");
  if (m_cluster)
    m_cluster->print_summary(m_stats, m_wall, outputs);
  else
    print_summary(*m_soc, m_stats, m_frame_sums, m_config.get_string("sim.app"), m_wall, m_plan.time_limit, outputs);
}

// The summary (and anything the application printed) must have arrived.
int RunSession::flush_standard_output(int status) {
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || !std::cout) {
    std::cerr << "soc_sim: cannot write to standard output: " << std::strerror(errno) << "\n";
    if (status == 0) status = EXIT_SIM_FAILED;
  }
  return status;
}

void RunSession::fail(RunEnd end, int status, const std::string& message) {
  m_failures.push_back({end, status, message});
}

double RunSession::wall_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_wall_start).count();
}

}  // namespace tessera
