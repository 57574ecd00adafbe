#include "html_report.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "soc_sim_python.h"

extern char** environ;

namespace tessera {

std::string report_python() {
  const char* given = std::getenv("TESSERA_PYTHON");
  return given != nullptr && *given != '\0' ? given : TESSERA_PYTHON;
}

std::string write_html_report(const HtmlReportRequest& request) {
  const std::string python = report_python();
  std::vector<std::string> args = {python,         "-m",       "tessera_sweep.run_report", request.stats,
                                   request.output, "--frames", request.frames_dir,         "--quiet"};
  // The package is found where this build's sources are, ahead of any
  // installed copy.
  std::vector<std::string> environment;
  const char* pythonpath = std::getenv("PYTHONPATH");
  environment.push_back(std::string("PYTHONPATH=") + TESSERA_PYTHON_PACKAGES +
                        (pythonpath != nullptr && *pythonpath != '\0' ? std::string(":") + pythonpath : ""));
  for (char** variable = environ; *variable != nullptr; ++variable)
    if (std::strncmp(*variable, "PYTHONPATH=", 11) != 0) environment.emplace_back(*variable);
  std::vector<char*> argv, envp;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  for (std::string& variable : environment) envp.push_back(variable.data());
  envp.push_back(nullptr);
  pid_t pid = 0;
  const int error = ::posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), envp.data());
  if (error != 0)
    return "cannot run Python '" + python + "' for the run report: " + std::strerror(error) +
           "; run scripts/setup.sh, or name a Python with jinja2 and matplotlib in TESSERA_PYTHON";
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return std::string("cannot wait for the run report's Python: ") + std::strerror(errno);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  return "the run report '" + request.output + "' was not written (" + python + " " +
         (WIFEXITED(status) ? "exited with status " + std::to_string(WEXITSTATUS(status))
                            : "was killed by signal " + std::to_string(WTERMSIG(status))) +
         ", its message above)";
}

}  // namespace tessera
