// Runs soc_sim as a child process for the system tests: stdout and stderr go
// to files in the run's folder (no pipes to drain, so no deadlock however
// much it prints), and the exit status comes back with both texts.
#pragma once

#include <fcntl.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace tessera::test {

struct SimResult {
  int status = -1;  // exit status, or 128 + signal
  std::string out;
  std::string err;
};

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A system test's main: GoogleTest's options out of argv, then the soc_sim
// to run (the first remaining argument, else TESSERA_SOC_SIM; empty: none).
inline std::string init_soc_sim_test(int& argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc >= 2) return std::filesystem::absolute(argv[1]).string();
  const char* path = std::getenv("TESSERA_SOC_SIM");
  return path != nullptr ? path : "";
}

// Starts `soc_sim` with `args` in the folder `dir` and returns its process
// id (-1 if fork failed); `in_child`, if given, runs in the child before
// exec (to set a resource limit, say).
inline pid_t start_soc_sim(const std::string& soc_sim, const std::filesystem::path& dir,
                           const std::vector<std::string>& args, void (*in_child)() = nullptr) {
  const std::filesystem::path out_path = dir / "soc_sim.stdout";
  const std::filesystem::path err_path = dir / "soc_sim.stderr";
  std::vector<char*> argv{const_cast<char*>(soc_sim.c_str())};
  for (const auto& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0 || chdir(dir.c_str()) != 0) _exit(127);
    dup2(out, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    close(out);
    close(err);
    setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
    if (in_child != nullptr) in_child();
    execv(argv[0], argv.data());
    _exit(127);
  }
  if (pid < 0) ADD_FAILURE() << "fork failed";
  return pid;
}

// Waits for a soc_sim that start_soc_sim started in `dir`.
inline SimResult wait_soc_sim(pid_t pid, const std::filesystem::path& dir) {
  SimResult run;
  if (pid < 0) return run;
  int wstatus = 0;
  while (waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(wstatus))
    run.status = WEXITSTATUS(wstatus);
  else if (WIFSIGNALED(wstatus))
    run.status = 128 + WTERMSIG(wstatus);
  run.out = read_file(dir / "soc_sim.stdout");
  run.err = read_file(dir / "soc_sim.stderr");
  return run;
}

// Runs `soc_sim` with `args` in the folder `dir`.
inline SimResult run_soc_sim(const std::string& soc_sim, const std::filesystem::path& dir,
                             const std::vector<std::string>& args) {
  return wait_soc_sim(start_soc_sim(soc_sim, dir, args), dir);
}

// Runs `soc_sim` with `args` in the folder `dir` with its stderr on a
// pseudo-terminal `columns` wide (0: a terminal that reports no size), as a
// user at a terminal sees it; stdout goes to a file as in run_soc_sim.
// `environment` ("NAME=value") is added to the child's. SimResult::err is
// every byte the terminal received, output post-processing off (no "\r"
// added before "\n"), so that what soc_sim wrote can be counted.
// Needs -lutil (openpty).
inline SimResult run_soc_sim_on_terminal(const std::string& soc_sim, const std::filesystem::path& dir,
                                         const std::vector<std::string>& args, unsigned short columns,
                                         const std::vector<std::string>& environment = {}) {
  SimResult run;
  int terminal = -1, child_side = -1;
  winsize size{};
  size.ws_row = 24;
  size.ws_col = columns;
  if (openpty(&terminal, &child_side, nullptr, nullptr, &size) != 0) {
    ADD_FAILURE() << "openpty failed";
    return run;
  }
  termios modes{};
  tcgetattr(child_side, &modes);
  modes.c_oflag &= ~static_cast<tcflag_t>(OPOST);
  tcsetattr(child_side, TCSANOW, &modes);

  const std::filesystem::path out_path = dir / "soc_sim.stdout";
  std::vector<char*> argv{const_cast<char*>(soc_sim.c_str())};
  for (const auto& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int in = open("/dev/null", O_RDONLY);
    if (out < 0 || in < 0 || chdir(dir.c_str()) != 0) _exit(127);
    dup2(in, STDIN_FILENO);
    dup2(out, STDOUT_FILENO);
    dup2(child_side, STDERR_FILENO);
    close(in);
    close(out);
    close(child_side);
    close(terminal);
    setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
    for (const auto& variable : environment) putenv(const_cast<char*>(variable.c_str()));
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(child_side);
  if (pid < 0) {
    close(terminal);
    ADD_FAILURE() << "fork failed";
    return run;
  }
  // Read until the child's side is closed (EIO): the terminal's buffer is
  // small, and a child that cannot write would never finish.
  char buffer[4096];
  for (;;) {
    const ssize_t count = read(terminal, buffer, sizeof buffer);
    if (count > 0)
      run.err.append(buffer, static_cast<size_t>(count));
    else if (count < 0 && errno == EINTR)
      continue;
    else
      break;
  }
  close(terminal);
  int wstatus = 0;
  while (waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(wstatus))
    run.status = WEXITSTATUS(wstatus);
  else if (WIFSIGNALED(wstatus))
    run.status = 128 + WTERMSIG(wstatus);
  run.out = read_file(out_path);
  return run;
}

inline std::string describe(const SimResult& run) {
  return "exit status " + std::to_string(run.status) + "\n--- stdout ---\n" + run.out + "--- stderr ---\n" + run.err;
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A fixture with a fresh folder per test (m_dir, under the temporary folder,
// named after the test suite), removed after a passing test and kept, with
// its path printed, after a failing one so that a person can look.
class ScratchFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string suite = ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name();
    std::string pattern = (std::filesystem::temp_directory_path() / ("tessera_" + suite + "_XXXXXX")).string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr) << "cannot create " << pattern;
    m_dir = pattern;
  }
  void TearDown() override {
    if (HasFailure()) {
      std::cerr << "[ kept     ] " << m_dir.string() << "\n";
      return;
    }
    std::error_code ignored;
    std::filesystem::remove_all(m_dir, ignored);
  }

  std::filesystem::path m_dir;
};

}  // namespace tessera::test
