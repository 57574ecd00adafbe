#include "process/child_process.h"

#include <fcntl.h>
#include <pty.h>
#include <signal.h>
#include <spawn.h>
#include <sys/ioctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

extern char** environ;

namespace tessera::test {

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Our environment with `additions` ("NAME=value") put in, each replacing
// a variable of the same name. The strings live in `storage`.
std::vector<char*> environment_with(const std::vector<std::string>& additions, std::vector<std::string>& storage) {
  for (char** variable = environ; *variable != nullptr; ++variable) storage.emplace_back(*variable);
  for (const std::string& addition : additions) {
    const std::string name = addition.substr(0, addition.find('=') + 1);
    bool replaced = false;
    for (std::string& variable : storage)
      if (variable.compare(0, name.size(), name) == 0) {
        variable = addition;
        replaced = true;
      }
    if (!replaced) storage.push_back(addition);
  }
  std::vector<char*> pointers;
  pointers.reserve(storage.size() + 1);
  for (std::string& variable : storage) pointers.push_back(variable.data());
  pointers.push_back(nullptr);
  return pointers;
}

constexpr int FILE_FLAGS = O_WRONLY | O_CREAT | O_TRUNC;
constexpr mode_t FILE_MODE = 0644;

// The child's side of fork: what posix_spawn's file actions do, then the
// hook and the exec.
[[noreturn]] void exec_in_child(const ChildCommand& command, char* const argv[], char* const envp[], int terminal,
                                int terminal_child_side) {
  if (command.stdin_from_null) {
    const int in = open("/dev/null", O_RDONLY);
    if (in < 0) _exit(127);
    dup2(in, STDIN_FILENO);
    close(in);
  }
  if (!command.stdout_file.empty()) {
    const int out = open(command.stdout_file.c_str(), FILE_FLAGS, FILE_MODE);
    if (out < 0) _exit(127);
    dup2(out, STDOUT_FILENO);
    close(out);
  }
  switch (command.stderr_to) {
    case ChildCommand::Stderr::ours: break;
    case ChildCommand::Stderr::file: {
      const int err = open(command.stderr_file.c_str(), FILE_FLAGS, FILE_MODE);
      if (err < 0) _exit(127);
      dup2(err, STDERR_FILENO);
      close(err);
      break;
    }
    case ChildCommand::Stderr::with_stdout: dup2(STDOUT_FILENO, STDERR_FILENO); break;
    case ChildCommand::Stderr::terminal:
      dup2(terminal_child_side, STDERR_FILENO);
      close(terminal_child_side);
      close(terminal);
      break;
  }
  if (!command.working_dir.empty() && chdir(command.working_dir.c_str()) != 0) _exit(127);
  command.in_child();
  execve(argv[0], argv, envp);
  _exit(127);
}

// posix_spawn with the same redirections; returns its error number.
int spawn(const ChildCommand& command, char* const argv[], char* const envp[], int terminal, int terminal_child_side,
          pid_t* pid) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (command.stdin_from_null) posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (!command.stdout_file.empty())
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, command.stdout_file.c_str(), FILE_FLAGS, FILE_MODE);
  switch (command.stderr_to) {
    case ChildCommand::Stderr::ours: break;
    case ChildCommand::Stderr::file:
      posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, command.stderr_file.c_str(), FILE_FLAGS, FILE_MODE);
      break;
    case ChildCommand::Stderr::with_stdout:
      posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
      break;
    case ChildCommand::Stderr::terminal:
      posix_spawn_file_actions_adddup2(&actions, terminal_child_side, STDERR_FILENO);
      posix_spawn_file_actions_addclose(&actions, terminal_child_side);
      posix_spawn_file_actions_addclose(&actions, terminal);
      break;
  }
  // Last, so that the files above are opened relative to our folder.
  if (!command.working_dir.empty()) posix_spawn_file_actions_addchdir_np(&actions, command.working_dir.c_str());
  const int error = posix_spawn(pid, argv[0], &actions, nullptr, argv, envp);
  posix_spawn_file_actions_destroy(&actions);
  return error;
}

}  // namespace

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

ChildProcess::ChildProcess(ChildCommand command) : m_command(std::move(command)) {
  if (m_command.argv.empty()) {
    m_result.start_error = "no program to run";
    return;
  }
  std::vector<char*> argv;
  for (const std::string& arg : m_command.argv) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  std::vector<std::string> environment_storage;
  std::vector<char*> envp = environment_with(m_command.environment, environment_storage);

  int child_side = -1;
  if (m_command.stderr_to == ChildCommand::Stderr::terminal) {
    winsize size{};
    size.ws_row = 24;
    size.ws_col = m_command.terminal_columns;
    if (openpty(&m_terminal, &child_side, nullptr, nullptr, &size) != 0) {
      m_result.start_error = std::string("openpty failed: ") + std::strerror(errno);
      return;
    }
    termios modes{};
    tcgetattr(child_side, &modes);
    modes.c_oflag &= ~static_cast<tcflag_t>(OPOST);
    tcsetattr(child_side, TCSANOW, &modes);
  }

  m_start_s = now_s();
  if (m_command.in_child != nullptr) {
    m_pid = fork();
    if (m_pid == 0) exec_in_child(m_command, argv.data(), envp.data(), m_terminal, child_side);
    if (m_pid < 0) m_result.start_error = std::string("fork failed: ") + std::strerror(errno);
  } else {
    const int error = spawn(m_command, argv.data(), envp.data(), m_terminal, child_side, &m_pid);
    if (error != 0) {
      m_pid = -1;
      m_result.start_error = "cannot start " + m_command.argv[0] + ": " + std::strerror(error);
    }
  }
  if (child_side >= 0) close(child_side);
  m_result.started = m_pid > 0;
  if (!m_result.started && m_terminal >= 0) {
    close(m_terminal);
    m_terminal = -1;
  }
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : m_command(std::move(other.m_command)),
      m_pid(std::exchange(other.m_pid, -1)),
      m_terminal(std::exchange(other.m_terminal, -1)),
      m_start_s(other.m_start_s),
      m_result(std::move(other.m_result)),
      m_waited(std::exchange(other.m_waited, true)) {}

ChildProcess::~ChildProcess() {
  // A child nobody waited for (a test that stopped at a failed assertion)
  // is ended rather than left running.
  if (!m_waited && m_pid > 0) kill(m_pid, SIGKILL);
  if (!m_waited) wait();
}

ChildResult ChildProcess::wait() {
  if (m_waited) return m_result;
  m_waited = true;
  if (!m_result.started) return m_result;
  if (m_terminal >= 0) {
    // Read until the child's side is closed (EIO): the terminal's buffer is
    // small, and a child that cannot write would never finish.
    char buffer[4096];
    for (;;) {
      const ssize_t count = read(m_terminal, buffer, sizeof buffer);
      if (count > 0)
        m_result.err.append(buffer, static_cast<size_t>(count));
      else if (count < 0 && errno == EINTR)
        continue;
      else
        break;
    }
    close(m_terminal);
    m_terminal = -1;
  }
  int wait_status = 0;
  rusage usage{};
  while (wait4(m_pid, &wait_status, 0, &usage) < 0) {
    if (errno != EINTR) {
      m_result.start_error = std::string("waiting for the child: ") + std::strerror(errno);
      return m_result;
    }
  }
  m_result.wall_s = now_s() - m_start_s;
  m_result.max_rss_kib = usage.ru_maxrss;
  m_result.cpu_s = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                   static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
  if (WIFEXITED(wait_status)) {
    m_result.status = WEXITSTATUS(wait_status);
  } else if (WIFSIGNALED(wait_status)) {
    m_result.signal = WTERMSIG(wait_status);
    m_result.status = 128 + m_result.signal;
  }
  if (!m_command.stdout_file.empty()) m_result.out = read_file(m_command.stdout_file);
  if (m_command.stderr_to == ChildCommand::Stderr::file) m_result.err = read_file(m_command.stderr_file);
  return m_result;
}

ChildResult run_child(const ChildCommand& command) {
  return ChildProcess(command).wait();
}

std::string describe(const ChildResult& result) {
  std::string text = result.started ? "exit status " + std::to_string(result.status) : result.start_error;
  return text + "\n--- stdout ---\n" + result.out + "--- stderr ---\n" + result.err;
}

}  // namespace tessera::test
