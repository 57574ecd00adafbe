#include "run_watch.h"

#include <cxxabi.h>
#include <execinfo.h>
#include <pthread.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "progress_line.h"

namespace tessera {

namespace {

// Shared with the signal handlers, hence plain globals of lock-free atomics.
std::atomic<int> g_stop_signal{0};
std::atomic<int> g_stop_count{0};
std::atomic<int> g_crash_signal{0};
std::atomic<bool> g_crash_reported{false};
std::atomic<bool> g_watching{false};
std::atomic<bool> g_installed{false};  // the handlers, and g_main_thread
std::atomic<unsigned> g_frames_shown{0};
std::atomic<unsigned> g_frames_requested{0};
std::atomic<uint64_t> g_simulated_ps{0};
// Who ends the run: nobody yet, the simulation loop, or the watching thread.
enum class EndedBy { nobody, loop, watch };
std::atomic<EndedBy> g_end{EndedBy::nobody};
pthread_t g_main_thread;
pthread_t g_watch_thread;
// The crash report, written by the handler and copied into stats.json.
char g_crash_message[512];

// The call stack of the main thread, sampled by SAMPLE_SIGNAL.
constexpr int SAMPLE_SIGNAL = SIGURG;  // ignored by default: a late one is harmless
constexpr int MAX_STACK = 64;
void* g_stack[MAX_STACK];
std::atomic<int> g_stack_depth{-1};

// The crash handlers' stack: a stack overflow in the application leaves none.
constexpr size_t ALTERNATE_STACK_BYTES = 1 << 16;
char g_alternate_stack[ALTERNATE_STACK_BYTES];

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGSEGV: return "SIGSEGV (invalid memory access)";
    case SIGBUS: return "SIGBUS (bad memory access)";
    case SIGFPE: return "SIGFPE (arithmetic fault, e.g. integer division by zero)";
    case SIGILL: return "SIGILL (illegal instruction)";
    case SIGABRT: return "SIGABRT (abort)";
    default: return "a signal";
  }
}

// Appends to a fixed buffer without allocating (signal handlers).
struct FixedText {
  char* text;
  size_t size;
  size_t used = 0;
  void add(const char* part) {
    while (*part != '\0' && used + 1 < size) text[used++] = *part++;
    text[used] = '\0';
  }
  void add_number(uint64_t value, unsigned base = 10) {
    char digits[24];
    int count = 0;
    do {
      digits[count++] = "0123456789abcdef"[value % base];
      value /= base;
    } while (value != 0 && count < 24);
    char reversed[26];
    int out = 0;
    if (base == 16) reversed[out++] = '0', reversed[out++] = 'x';
    while (count > 0) reversed[out++] = digits[--count];
    reversed[out] = '\0';
    add(reversed);
  }
};

void write_stderr(const char* text) {
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t written = ::write(STDERR_FILENO, text, left);
    if (written <= 0) return;
    text += written;
    left -= static_cast<size_t>(written);
  }
}

void sleep_ms(long ms) {
  timespec pause{0, ms * 1000000L};
  while (::nanosleep(&pause, &pause) != 0) {
  }
}

void on_stop_signal(int signal) {
  int none = 0;
  g_stop_signal.compare_exchange_strong(none, signal);
  g_stop_count.fetch_add(1);
}

void on_sample(int) {
  g_stack_depth.store(::backtrace(g_stack, MAX_STACK));
}

void on_crash(int signal, siginfo_t* info, void*) {
  static std::atomic<bool> entered{false};
  if (!entered.exchange(true)) {
    FixedText message{g_crash_message, sizeof g_crash_message};
    message.add("crashed: ");
    message.add(signal_name(signal));
    if ((signal == SIGSEGV || signal == SIGBUS) && info != nullptr && info->si_code > 0) {
      message.add(" at address ");
      message.add_number(reinterpret_cast<uintptr_t>(info->si_addr), 16);
    }
    if (g_watching.load()) {
      message.add(" while simulating, after ");
      message.add_number(g_frames_shown.load());
      message.add(" of ");
      message.add_number(g_frames_requested.load());
      message.add(" frames were shown (simulated time ");
      const uint64_t us = g_simulated_ps.load() / 1000000;
      message.add_number(us / 1000);
      message.add(".");
      for (uint64_t digit = 100; digit > 0; digit /= 10) message.add_number(us / digit % 10);
      message.add(" ms): a fault in the application or in the model");
    }
    write_stderr("soc_sim: ");
    write_stderr(g_crash_message);
    write_stderr("\n");
    // The watching thread writes the outputs it can; it is given a few
    // seconds, in case the fault left a lock it needs held.
    if (g_watching.load() && !pthread_equal(pthread_self(), g_watch_thread)) {
      g_crash_signal.store(signal);
      for (int waited = 0; waited < 500 && !g_crash_reported.load(); ++waited) sleep_ms(10);
    }
  }
  // The signal takes its course: default action once the handler returns.
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  sigaction(signal, &action, nullptr);
  raise(signal);
}

std::string demangled(const std::string& symbol_line) {
  // backtrace_symbols: "binary(mangled+0x1a) [0x...]"
  const auto open = symbol_line.find('(');
  const auto plus = symbol_line.find('+', open);
  if (open == std::string::npos || plus == std::string::npos || plus == open + 1) return "";
  const std::string mangled = symbol_line.substr(open + 1, plus - open - 1);
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> name(abi::__cxa_demangle(mangled.c_str(), nullptr, nullptr, &status),
                                              std::free);
  std::string text = status == 0 && name ? name.get() : mangled;
  // The parameter list is long and says little here.
  if (text.size() > 1 && text.back() == ')') {
    int depth = 0;
    for (size_t i = text.size(); i-- > 0;) {
      depth += text[i] == ')' ? 1 : text[i] == '(' ? -1 : 0;
      if (depth == 0) {
        text.resize(i);
        break;
      }
    }
  }
  return text;
}

}  // namespace

const char* run_end_name(RunEnd end) {
  switch (end) {
    case RunEnd::completed: return "completed";
    case RunEnd::failed: return "failed";
    case RunEnd::interrupted: return "interrupted";
    case RunEnd::wall_limit: return "wall_limit";
    case RunEnd::stalled: return "stalled";
    case RunEnd::crashed: return "crashed";
  }
  return "failed";
}

void install_run_signal_handlers() {
  g_main_thread = pthread_self();
  stack_t stack{};
  stack.ss_sp = g_alternate_stack;
  stack.ss_size = sizeof g_alternate_stack;
  sigaltstack(&stack, nullptr);

  struct sigaction stop {};
  stop.sa_handler = on_stop_signal;
  sigemptyset(&stop.sa_mask);
  stop.sa_flags = SA_RESTART;
  sigaction(SIGINT, &stop, nullptr);
  sigaction(SIGTERM, &stop, nullptr);

  struct sigaction sample {};
  sample.sa_handler = on_sample;
  sigemptyset(&sample.sa_mask);
  sample.sa_flags = SA_RESTART | SA_ONSTACK;
  sigaction(SAMPLE_SIGNAL, &sample, nullptr);
  // backtrace() loads its unwinder on first use, which a handler must not.
  void* warm_up[1];
  ::backtrace(warm_up, 1);

  struct sigaction crash {};
  crash.sa_sigaction = on_crash;
  sigemptyset(&crash.sa_mask);
  crash.sa_flags = SA_SIGINFO | SA_ONSTACK;
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) sigaction(signal, &crash, nullptr);
  g_installed.store(true);
}

int stop_signal_received() {
  return g_stop_signal.load();
}

RunWatch::RunWatch(const WatchLimits& limits, unsigned frames_requested, HardStop hard_stop)
    : m_limits(limits), m_frames_requested(frames_requested), m_hard_stop(std::move(hard_stop)) {
  g_frames_requested.store(frames_requested);
  g_frames_shown.store(0);
  g_simulated_ps.store(0);
  g_watching.store(true);
  m_thread = std::thread([this] { watch(); });
}

RunWatch::~RunWatch() {
  finish();
}

void RunWatch::progress(uint64_t simulated_ps) {
  g_simulated_ps.store(simulated_ps, std::memory_order_relaxed);
}

void RunWatch::frame_shown(unsigned frames_shown) {
  g_frames_shown.store(frames_shown, std::memory_order_relaxed);
}

unsigned RunWatch::frames_shown() const {
  return g_frames_shown.load();
}

std::string RunWatch::describe_position() const {
  return "after " + std::to_string(g_frames_shown.load()) + " of " + std::to_string(m_frames_requested) +
         " frames were shown (simulated time " + format_duration(static_cast<double>(g_simulated_ps.load()) * 1e-12) +
         ")";
}

// Stops for good once the watching thread has begun to end the run.
static void wait_for_the_watch_to_exit() {
  for (;;) sleep_ms(1000);
}

std::optional<RunStop> RunWatch::stop_request() {
  const int signal = g_stop_signal.load();
  const bool wall = m_limits.wall_limit_s > 0 && m_wall_expired.load();
  if (signal == 0 && !wall) return std::nullopt;
  EndedBy open = EndedBy::nobody;
  if (!g_end.compare_exchange_strong(open, EndedBy::loop) && open == EndedBy::watch) wait_for_the_watch_to_exit();
  if (signal != 0)
    return RunStop{RunEnd::interrupted, 128 + signal,
                   std::string("interrupted by ") + signal_name(signal) + ": the run stopped " + describe_position() +
                       "; the outputs hold what was complete"};
  return RunStop{RunEnd::wall_limit, 1,
                 "wall-clock limit reached: sim.wall_limit_s = " + std::to_string(m_limits.wall_limit_s) +
                     " s stopped the run " + describe_position() +
                     "; raise it (--set sim.wall_limit_s=N), or set 0 for no limit"};
}

void RunWatch::finish() {
  if (!m_thread.joinable()) return;
  EndedBy open = EndedBy::nobody;
  if (!g_end.compare_exchange_strong(open, EndedBy::loop) && open == EndedBy::watch) wait_for_the_watch_to_exit();
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_done = true;
  }
  m_wake.notify_all();
  m_thread.join();
  g_watching.store(false);
}

std::string RunWatch::host_call_stack() {
  if (!g_installed.load()) return "";
  g_stack_depth.store(-1);
  if (pthread_kill(g_main_thread, SAMPLE_SIGNAL) != 0) return "";
  for (int waited = 0; waited < 100 && g_stack_depth.load() < 0; ++waited) sleep_ms(10);
  const int depth = g_stack_depth.load();
  if (depth <= 2) return "";
  // Frame 0 is the sampling handler, frame 1 the kernel's signal return.
  std::unique_ptr<char*, void (*)(void*)> lines(::backtrace_symbols(g_stack + 2, depth - 2), std::free);
  if (!lines) return "";
  std::string stack;
  unsigned shown = 0;
  for (int i = 0; i < depth - 2 && shown < 8; ++i) {
    const std::string name = demangled(lines.get()[i]);
    // Below the host's thread is only SystemC's own machinery.
    if (name.rfind("sc_core::", 0) == 0 || name.rfind("qt_", 0) == 0) break;
    if (name.empty() || name.rfind("std::", 0) == 0) continue;
    stack += (stack.empty() ? "" : " < ") + name;
    ++shown;
  }
  return stack;
}

void RunWatch::stop_from_here(const RunStop& stop) {
  EndedBy open = EndedBy::nobody;
  if (!g_end.compare_exchange_strong(open, EndedBy::watch)) return;  // the loop is ending the run itself
  m_hard_stop(stop);
  if (stop.end == RunEnd::crashed) return;
  std::fflush(nullptr);
  ::_exit(stop.exit_status);
}

void RunWatch::watch() {
  g_watch_thread = pthread_self();
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_progress = start;
  uint64_t last_ps = 0;
  std::optional<clock::time_point> stop_asked;  // when the loop was first asked to stop
  const auto seconds = [](clock::duration d) { return std::chrono::duration<double>(d).count(); };
  std::unique_lock<std::mutex> lock(m_mutex);
  while (!m_done) {
    m_wake.wait_for(lock, std::chrono::milliseconds(50));
    if (m_done) break;
    lock.unlock();
    const auto now = clock::now();
    if (const int crash = g_crash_signal.load(); crash != 0) {
      stop_from_here({RunEnd::crashed, 128 + crash, g_crash_message});
      g_crash_reported.store(true);
      lock.lock();
      m_wake.wait(lock, [this] { return m_done; });
      break;
    }
    if (g_end.load() != EndedBy::nobody) {  // the loop is ending the run itself
      lock.lock();
      continue;
    }
    const uint64_t ps = g_simulated_ps.load(std::memory_order_relaxed);
    if (ps != last_ps) last_ps = ps, last_progress = now;
    if (m_limits.wall_limit_s > 0 && seconds(now - start) >= static_cast<double>(m_limits.wall_limit_s))
      m_wall_expired.store(true);
    const int signal = g_stop_signal.load();
    if ((signal != 0 || m_wall_expired.load()) && !stop_asked) stop_asked = now;
    const bool overdue = stop_asked && seconds(now - *stop_asked) >= STOP_GRACE_SECONDS;
    const std::string host_state =
        "the host does not come back to the simulation: it is computing without calling "
        "the host model, or waiting on it without letting simulated time pass";
    if (signal != 0 && (g_stop_count.load() > 1 || overdue)) {
      const std::string stack = host_call_stack();
      stop_from_here({RunEnd::interrupted, 128 + signal,
                      std::string("interrupted by ") + signal_name(signal) + " " + describe_position() + "; " +
                          host_state + (stack.empty() ? "" : "; the host was running " + stack) +
                          "; the SoC's statistics could not be read"});
    } else if (overdue) {
      const std::string stack = host_call_stack();
      stop_from_here({RunEnd::wall_limit, 1,
                      "wall-clock limit reached: sim.wall_limit_s = " + std::to_string(m_limits.wall_limit_s) +
                          " s stopped the run " + describe_position() + "; " + host_state +
                          (stack.empty() ? "" : "; the host was running " + stack) +
                          "; the SoC's statistics could not be read"});
    } else if (m_limits.stall_limit_s > 0 &&
               seconds(now - last_progress) >= static_cast<double>(m_limits.stall_limit_s)) {
      const std::string stack = host_call_stack();
      stop_from_here({RunEnd::stalled, 1,
                      "no simulated progress: simulated time has not advanced for sim.stall_limit_s = " +
                          std::to_string(m_limits.stall_limit_s) + " s of wall time, " + describe_position() + "; " +
                          host_state + (stack.empty() ? "" : "; the host was running " + stack) +
                          "; the SoC's statistics could not be read"});
    }
    lock.lock();
  }
}

}  // namespace tessera
