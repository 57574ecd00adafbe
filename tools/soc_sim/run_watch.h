// How a run of soc_sim ends when it cannot finish by itself, or when it is
// told to stop. A thread watches the simulation loop from outside:
//
// - SIGINT or SIGTERM: the loop stops at its next safe point (between two
//   slices of simulated time) and the run writes what is complete, with
//   run_status "interrupted"; a second signal, or a loop that does not come
//   back within STOP_GRACE_SECONDS (an application stuck in its own code),
//   stops the process from the watching thread.
// - sim.wall_limit_s: the same at a wall-clock limit ("wall_limit").
// - sim.stall_limit_s: simulated time has not advanced for that long. Only
//   an application that computes without ever calling the host model (or
//   polls it without letting time pass) does that, so the loop is not
//   coming back: the watching thread stops the process ("stalled").
// - a crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) while the simulation
//   runs: reported naming the signal and the frame reached ("crashed"),
//   then the signal takes its course.
//
// A stop from the watching thread reports what the host was running (its
// call stack, sampled with a signal), writes the outputs it can through the
// HardStop callback and exits; the SoC's own statistics cannot be read then.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace tessera {

constexpr double STOP_GRACE_SECONDS = 3;

// How a run ended, as stats.json's run_status.
enum class RunEnd { completed, failed, interrupted, wall_limit, stalled, crashed };
const char* run_end_name(RunEnd end);

struct RunStop {
  RunEnd end = RunEnd::completed;
  int exit_status = 0;
  std::string message;  // for stderr, without "soc_sim: "
};

struct WatchLimits {
  uint64_t stall_limit_s = 0;  // 0: not watched
  uint64_t wall_limit_s = 0;   // 0: none
};

// Installs the handlers of SIGINT, SIGTERM and the crash signals. Call once,
// before the threads that should inherit the crash handlers' stack exist.
void install_run_signal_handlers();
// The first SIGINT or SIGTERM received (0: none).
int stop_signal_received();

class RunWatch {
 public:
  // Called on the watching thread when it stops the run itself: writes
  // what can be written. For a crash it returns and the signal takes its
  // course; otherwise the process exits with stop.exit_status after it.
  using HardStop = std::function<void(const RunStop& stop)>;

  RunWatch(const WatchLimits& limits, unsigned frames_requested, HardStop hard_stop);
  ~RunWatch();

  // From the simulation loop, after each slice.
  void progress(uint64_t simulated_ps);
  // From the display's frame callback.
  void frame_shown(unsigned frames_shown);
  unsigned frames_shown() const;
  // After each slice: the reason to stop now, if any.
  std::optional<RunStop> stop_request();
  // The simulation loop is over: stop watching. If the watching thread has
  // already begun to stop the process, this never returns.
  void finish();

 private:
  void watch();
  void stop_from_here(const RunStop& stop);
  std::string describe_position() const;
  std::string host_call_stack();

  WatchLimits m_limits;
  unsigned m_frames_requested;
  HardStop m_hard_stop;
  std::mutex m_mutex;
  std::condition_variable m_wake;
  bool m_done = false;
  std::atomic<bool> m_wall_expired{false};
  std::thread m_thread;
};

}  // namespace tessera
