// Runs a program as a child process: the one launcher of the tests, the
// benchmarks and render_compare. Its output goes to files (no pipe to
// drain, so no deadlock however much it prints), or its standard error to a
// pseudo-terminal of a given width, as a user at a terminal sees it. The
// result has the exit status, the output and what the run cost (wall time,
// CPU time, peak memory).
//
// Plain C++ and POSIX, no GoogleTest: the benchmarks and render_compare,
// which are not tests, use it as they are.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace tessera::test {

struct ChildCommand {
  std::vector<std::string> argv;      // argv[0] is the program's path
  std::filesystem::path working_dir;  // empty: ours
  std::filesystem::path stdout_file;  // empty: ours
  enum class Stderr { ours, file, with_stdout, terminal };
  Stderr stderr_to = Stderr::ours;
  std::filesystem::path stderr_file;     // for Stderr::file
  unsigned short terminal_columns = 0;   // for Stderr::terminal; 0: a terminal that reports no size
  bool stdin_from_null = false;          // else ours
  std::vector<std::string> environment;  // "NAME=value", added to ours
  // Runs in the child between fork and exec (to set a resource limit, say);
  // only async-signal-safe calls belong there. Without it the child is
  // started by posix_spawn, which shares our memory until the exec, so that
  // the peak memory measured is the program's own and not a copy of ours.
  void (*in_child)() = nullptr;
};

struct ChildResult {
  bool started = false;
  std::string start_error;  // why it did not start
  int status = -1;          // exit status, or 128 + signal
  int signal = 0;           // the signal that ended it, 0 if it exited
  double wall_s = 0;
  double cpu_s = 0;      // user + system CPU time of the child (every thread)
  long max_rss_kib = 0;  // its peak resident memory
  std::string out;       // stdout_file's contents
  // stderr_file's contents, or every byte the terminal received (output
  // post-processing off: no "\r" added before "\n", so that what the
  // program wrote can be counted).
  std::string err;

  bool exited_zero() const { return started && signal == 0 && status == 0; }
};

// A started child. Destroying one that was not waited for kills it (and
// collects it), so that a test stopped by a failed assertion leaves no run
// behind.
class ChildProcess {
 public:
  explicit ChildProcess(ChildCommand command);
  ~ChildProcess();
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&&) = delete;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return m_pid; }  // -1 if it did not start
  // Waits for the child to end (reading the terminal meanwhile) and reads
  // its output files. Once only.
  ChildResult wait();

 private:
  ChildCommand m_command;
  pid_t m_pid = -1;
  int m_terminal = -1;
  double m_start_s = 0;
  ChildResult m_result;
  bool m_waited = false;
};

// Starts `command` and waits for it.
ChildResult run_child(const ChildCommand& command);

// "exit status N", then the output and the error text, for a test's message.
std::string describe(const ChildResult& result);

// The whole file, as bytes (empty if it cannot be read).
std::string read_file(const std::filesystem::path& path);

}  // namespace tessera::test
